#!/usr/bin/env bash
# The main job on the bundled default scene (a) of the hybrid paper (glass teapot, mirror cup,
# columns, walls; data/scenes/hybrid_glass_teapot.gltf):
#  1. `pemref demo`: bakes the scene (ray tracing of 3 viewpoint samples, layered EM inference),
#     renders it on and off the sample circle with every method and writes the
#     error-against-run-time report (out/demo/report.{md,svg,json}, out/demo/views/*.png);
#  2. renders the raster benchmark frame with pemref's llvmpipe model and, when an OpenGL
#     driver is present, through it (pemref-gl), and checks the bytes agree.
set -euo pipefail
cd "$(dirname "$0")/.."
# Only what the demo runs (the tests' binaries are built by scripts/test.sh).
targets="pemref gen_cases"
grep -q '^PEM_GL:BOOL=OFF' build/CMakeCache.txt 2>/dev/null || targets="$targets pemref-gl"
PEM_TARGETS=$targets bash scripts/build.sh || PEM_TARGETS="pemref gen_cases" bash scripts/build.sh
out=${OUT_DIR:-out}
mkdir -p "$out"
./build/bin/pemref demo --out "$out/demo" --threads "$(nproc)"
./build/tests/gen_cases "$out" --bench-only >/dev/null
ours=$(./build/bin/pemref raster "$out/bench.json" -o "$out/bench_pemref.png" --threads 2)
echo "raster: $ours"
if [ -x ./build/bin/pemref-gl ]; then
  gl=$(./build/bin/pemref-gl "$out/bench.json" -o "$out/bench_gl.png")
  [ "$ours" == "$gl" ] && echo "raster: identical to $(./build/bin/pemref-gl "$out/bench.json" --info 2>&1 >/dev/null | head -1)" \
    || { echo "raster: frames differ from the OpenGL driver"; exit 1; }
fi
echo "outputs: $out/demo/ (report.md, report.svg, views/), $out/bench_pemref.png"
