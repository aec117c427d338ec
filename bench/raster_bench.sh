#!/usr/bin/env bash
# pemref vs Mesa llvmpipe on the raster benchmark frame (issue 2): 640x480, a full-screen sky
# quad and a 200x100 UV sphere (40k triangles) with reflection vectors, one 256^2 cube map,
# GL_LINEAR_MIPMAP_LINEAR, seamless. Both renderers use 2 threads; frames are timed without
# parsing, texel generation or texture upload. Rounds alternate the two renderers so a busy
# neighbour slows both; the script prints per-renderer median and spread (min..max of the round
# medians) and the ratio of medians.   usage: bench/raster_bench.sh [build-dir] [rounds]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}; rounds=${2:-7}; threads=${THREADS:-2}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$build/tests/gen_cases" "$tmp" --bench-only >/dev/null
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load:$(uptime | sed 's/.*average://')"
echo "llvmpipe: $(LIBGL_ALWAYS_SOFTWARE=1 "$build/bin/pemref-gl" "$tmp/bench.json" --info 2>&1 >/dev/null | head -1)"
ours=(); gl=()
for ((r = 0; r < rounds; ++r)); do
  o=$("$build/bin/pemref" raster "$tmp/bench.json" --threads "$threads" --repeat 5)
  g=$(LIBGL_ALWAYS_SOFTWARE=1 LP_NUM_THREADS=$threads "$build/bin/pemref-gl" "$tmp/bench.json" --repeat 5)
  [ "$(echo "$o" | head -1)" == "$(echo "$g" | head -1)" ] || { echo "frames differ!"; exit 1; }
  ours+=("$(echo "$o" | awk '/frame_ms_median/{print $2}')")
  gl+=("$(echo "$g" | awk '/frame_ms_median/{print $2}')")
done
python3 - "${ours[*]}" "${gl[*]}" "$threads" <<'PY'
import statistics, sys
o = [float(v) for v in sys.argv[1].split()]; g = [float(v) for v in sys.argv[2].split()]
mo, mg = statistics.median(o), statistics.median(g)
print(f"frame: identical bytes (sha256 equal)")
print(f"pemref   {sys.argv[3]} threads: median {mo:7.2f} ms  (spread {min(o):.2f}..{max(o):.2f})")
print(f"llvmpipe {sys.argv[3]} threads: median {mg:7.2f} ms  (spread {min(g):.2f}..{max(g):.2f})")
print(f"ratio pemref/llvmpipe: {mo / mg:.2f}")
PY
