#!/usr/bin/env bash
# The main job on the bundled default scene (grows with the project: see README).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
./build/viewer_tty/pemref raster data/cases/reflective_sphere.json -o out/reflective_sphere.png
echo "wrote out/reflective_sphere.png"
