#!/usr/bin/env bash
# Installs everything pemref needs on a fresh Debian 12 machine (run as root). Idempotent.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake pkg-config git clang libclang-rt-14-dev
  libglm-dev nlohmann-json3-dev libcli11-dev libpng-dev libgtest-dev
  libopenexr-dev libtinygltf-dev libembree-dev libtbb-dev
  libeigen3-dev libsuitesparse-dev libzstd-dev liblzma-dev libopenjp2-7-dev
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri
  tmux python3 python3-scipy openexr clang-format
  assimp-testmodels
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
