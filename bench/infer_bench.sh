#!/usr/bin/env bash
# The inference benchmark (issue 4): scene (a) at 640x480 with 3x3 supersampling, 256^2 x 6 EMs
# with every level, one viewpoint sample (all layers, both terms), 2 threads. Prints
#  (a) the time to build A (raster's rendering matrix + the stacked system) vs one forward render
#      of the same passes (the rmse_8bit render), summed over the maps;
#  (b) the solve time per iteration vs the time to stream A and A^T once each (an iteration's
#      two products) at this machine's memory bandwidth (a numpy copy of a 256 MB array; each in
#      CSR: 12 bytes per entry + 8 per row), and vs A alone;
#  (c) pemref's solve time vs scipy's lsmr on the exported system of the largest map, both to
#      pemref's objective (+1 %; scipy runs unbounded and unscaled, from 0).
# Medians of the rounds with min..max; `uptime` first.
#   usage: bench/infer_bench.sh [build-dir] [rounds] [trace-dir]   (no trace dir: traced here)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}; rounds=${2:-3}; trace=${3:-}
threads=${THREADS:-2}; res=${RES:-256}
scene=data/scenes/hybrid_glass_teapot.gltf
py=python3
if [ -x /usr/bin/python3 ] && /usr/bin/python3 -c 'import scipy' 2>/dev/null; then py=/usr/bin/python3; fi
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo "uptime:$(uptime)"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs)"
if [ -z "$trace" ]; then
    trace=$tmp/trace
    "$build/bin/pemref" trace "$scene" --out "$trace" --size 640x480 --spp 3 --views camera \
        --threads "$threads" --quiet
fi
for r in $(seq 1 "$rounds"); do
    s=$(date +%s.%N)
    "$build/bin/pemref" infer "$trace" --out "$tmp/pem_$r" --res "$res" --views 0 \
        --threads "$threads" --quiet
    echo "$(echo "$(date +%s.%N) - $s" | bc)" > "$tmp/pem_$r/wall.txt"
done
# One more run that exports the systems (not timed: the Matrix Market text is slow to write).
"$build/bin/pemref" infer "$trace" --out "$tmp/pem_x" --res "$res" --views 0 \
    --threads "$threads" --quiet --export-system "$tmp/sys"
"$py" bench/infer_bench.py "$tmp" "$rounds"
