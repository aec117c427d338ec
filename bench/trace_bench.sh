#!/usr/bin/env bash
# The tracer benchmark (issue 3): on the hybrid scene (a) at 640x480 with 3x3 supersampling and
# 2 threads, (1) primary and secondary Mrays/s of our single-ray path (EmbreeScene::Intersect, as
# the tracer uses it) vs Embree's own rtcIntersect1 and 8/16-ray packets on the same rays,
# (2) reference (full ray tree) and greedy two-term frame times, median over rounds, and rays per
# frame for both (the paper: 480 s and 6.15 M rays per full-tree frame on a 1 GHz Athlon),
# (3) the greedy model's error against the full tree (from `pemref trace --frames-only`).
#   usage: bench/trace_bench.sh [build-dir] [rounds] [scene]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}; rounds=${2:-3}; scene=${3:-data/scenes/hybrid_glass_teapot.gltf}
threads=${THREADS:-2}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load:$(uptime | sed 's/.*average://')"
"$build/tests/trace/trace_bench" "$scene" 640x480 3 "$threads" "$rounds" all
"$build/bin/pemref" trace "$scene" --out "$tmp" --threads "$threads" --frames-only --quiet
python3 - "$tmp/trace.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); v = j["views"][0]; e = v["greedy_vs_reference"]
rf, rg = v["rays_reference"]["total"], v["rays_greedy"]["total"]
print(f"rays/frame: full tree {rf / 1e6:.2f} M, greedy {rg / 1e6:.2f} M (ratio {rf / rg:.2f}); "
      f"secondary only: {v['rays_reference']['secondary'] / 1e6:.2f} M vs {v['rays_greedy']['secondary'] / 1e6:.2f} M")
for k in ("frame", "lens"):
    print(f"greedy vs full tree, {k:5s}: RMSE {e[k]['rmse']:.4f}  PSNR {e[k]['psnr_db']:.2f} dB "
          f"(display range [0,1]); HDR RMSE {e[k + '_hdr']['rmse']:.4f}  ({e[k]['pixels']} pixels)")
PY
