#!/usr/bin/env bash
# Configures and builds pemref (Release) into ${BUILD_DIR:-build}: every target, or only
# those listed in PEM_TARGETS (e.g. PEM_TARGETS="pemref gen_cases").
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=${BUILD_TYPE:-Release} "$@" >/dev/null
targets=()
for t in ${PEM_TARGETS:-}; do targets+=(--target "$t"); done
cmake --build "$build" -j"$(nproc)" "${targets[@]}"
