#!/usr/bin/env bash
# The main job on the bundled default scene (grows with the project; see README "Status"):
#  1. ray-traces scene (a) of the hybrid paper (data/scenes/hybrid_glass_teapot.gltf: glass
#     teapot, mirror cup, columns, walls) from its camera: reference image (full ray tree), the
#     greedy two-term images b_R, b_T, F*G, confidence and the environment layers (EXR + PNG);
#  2. renders the raster benchmark frame with pemref's llvmpipe model and, when an OpenGL
#     driver is present, through it (pemref-gl), and checks the bytes agree.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
out=${OUT_DIR:-out}
mkdir -p "$out"
./build/viewer_tty/pemref trace data/scenes/hybrid_glass_teapot.gltf --views camera --spp 3 \
  --size 640x480 --threads "$(nproc)" --out "$out/trace" --quiet
python3 - "$out/trace/trace.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
v = j["views"][0]
print(f"trace: {j['triangles']} triangles, {j['rays'] / 1e6:.2f} M rays, {j['seconds']:.2f} s")
e = v.get("greedy_vs_reference")
if e: print(f"two-term model vs full ray tree: PSNR {e['frame']['psnr_db']:.1f} dB (frame), "
            f"{e['lens']['psnr_db']:.1f} dB (glass and mirror pixels)")
PY
./build/tests/gen_cases "$out" --bench-only >/dev/null
ours=$(./build/viewer_tty/pemref raster "$out/bench.json" -o "$out/bench_pemref.png" --threads 2)
echo "raster: $ours"
if [ -x ./build/viewer_tty/pemref-gl ]; then
  gl=$(./build/viewer_tty/pemref-gl "$out/bench.json" -o "$out/bench_gl.png")
  [ "$ours" == "$gl" ] && echo "raster: identical to $(./build/viewer_tty/pemref-gl "$out/bench.json" --info 2>&1 >/dev/null | head -1)" \
    || { echo "raster: frames differ from the OpenGL driver"; exit 1; }
fi
echo "outputs: $out/trace/ (reference.png and the segmented images per view), $out/bench_pemref.png"
