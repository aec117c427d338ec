#!/usr/bin/env bash
# The main job (grows with the project; see README "Status"): builds pemref, generates the
# raster benchmark frame (a reflective sphere under a sky, 640x480, 256^2 trilinear cube map),
# renders it with pemref's llvmpipe model and, when an OpenGL driver is present, with that
# driver through pemref-gl, and checks that the two frames are byte-identical.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=${OUT_DIR:-out}
mkdir -p "$out"
./build/tests/gen_cases "$out" --bench-only >/dev/null
ours=$(./build/viewer_tty/pemref raster "$out/bench.json" -o "$out/bench_pemref.png" --threads 2 --repeat 3)
echo "$ours" | sed 's/^/pemref:    /'
if [ -x ./build/viewer_tty/pemref-gl ]; then
  gl=$(./build/viewer_tty/pemref-gl "$out/bench.json" -o "$out/bench_gl.png" --repeat 3)
  echo "$gl" | sed 's/^/pemref-gl: /'
  [ "$(echo "$ours" | head -1)" == "$(echo "$gl" | head -1)" ] && echo "frames identical" \
    || { echo "frames differ"; exit 1; }
fi
echo "wrote $out/bench.json, $out/bench_pemref.png${gl:+, $out/bench_gl.png}"
