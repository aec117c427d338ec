#!/usr/bin/env bash
# pemref vs Mesa on the raster benchmark frame (issues 2 and 16): 640x480, a full-screen sky
# quad and a 200x100 UV sphere (40k triangles) with reflection vectors, one 256^2 cube map,
# GL_LINEAR_MIPMAP_LINEAR, seamless; and the small-triangle frame "lens" (what the hybrid
# renderer's lens passes draw: two depth-tested layer passes over a sphere of two-pixel
# triangles, RGBA32F maps into an RGBA32F colour and a Z24 depth buffer). Pairs, each measured
# in one run:
#  - the llvmpipe profile vs llvmpipe on both frames, both with THREADS (default 2) threads;
#  - the softpipe profile vs softpipe on the benchmark frame (both single-threaded: softpipe has
#    no threads; its profile draws RGBA8 frames only).
# Frames are timed without parsing, texel generation or texture upload. Rounds alternate the two
# renderers of a pair so a busy neighbour slows both; the script prints per-renderer median and
# spread (min..max of the round medians) and the ratio of medians.
#   usage: bench/raster_bench.sh [build-dir] [rounds]   (PAIRS="llvmpipe softpipe" by default)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}; rounds=${2:-7}; threads=${THREADS:-2}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
"$build/tests/gen_cases" "$tmp" --bench-only >/dev/null
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load:$(uptime | sed 's/.*average://')"

# pair NAME THREADS DRIVER PROFILE FRAME: alternating rounds, identical bytes checked, medians.
pair() {
  local name=$1 n=$2 driver=$3 profile=$4 frame=$5 ours=() gl=() o g
  echo "$driver: $(LIBGL_ALWAYS_SOFTWARE=1 GALLIUM_DRIVER=$driver "$build/bin/pemref-gl" "$tmp/$frame.json" --info 2>&1 >/dev/null | head -1)"
  for ((r = 0; r < rounds; ++r)); do
    o=$("$build/bin/pemref" raster "$tmp/$frame.json" --profile "$profile" --threads "$n" --repeat 5)
    g=$(LIBGL_ALWAYS_SOFTWARE=1 LP_NUM_THREADS=$n "$build/bin/pemref-gl" "$tmp/$frame.json" \
        --driver "$driver" --repeat 5)
    [ "$(echo "$o" | head -1)" == "$(echo "$g" | head -1)" ] || { echo "frames differ!"; exit 1; }
    ours+=("$(echo "$o" | awk '/frame_ms_median/{print $2}')")
    gl+=("$(echo "$g" | awk '/frame_ms_median/{print $2}')")
  done
  python3 - "${ours[*]}" "${gl[*]}" "$n" "$name" "$driver" "$frame" <<'PY'
import statistics, sys
o = [float(v) for v in sys.argv[1].split()]; g = [float(v) for v in sys.argv[2].split()]
mo, mg = statistics.median(o), statistics.median(g)
n, name, drv, frame = sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6]
tag = "" if frame == "bench" else f" ({frame})"
print(f"frame {frame}: identical bytes (sha256 equal)")
print(f"pemref {name:8s} {n} thread(s): median {mo:7.2f} ms  (spread {min(o):.2f}..{max(o):.2f})")
print(f"{drv:15s} {n} thread(s): median {mg:7.2f} ms  (spread {min(g):.2f}..{max(g):.2f})")
print(f"ratio pemref/{drv}{tag}: {mo / mg:.2f}")
PY
}

for p in ${PAIRS:-llvmpipe softpipe}; do
  case $p in
    llvmpipe) pair llvmpipe "$threads" llvmpipe llvmpipe bench
              pair llvmpipe "$threads" llvmpipe llvmpipe lens ;;
    softpipe) pair softpipe 1 softpipe softpipe bench ;;
  esac
done
