#!/usr/bin/env bash
# Builds pemref and runs every test: the GoogleTest suites through CTest (including the
# llvmpipe conformance suite, which renders every generated case through Mesa via EGL), then
# the cross-build determinism check (gcc -O0, gcc -O3, clang: same golden bytes), the sanitizer
# jobs (ASan+UBSan, TSan), a short run of every fuzzer with its regression inputs, and the
# formatting check.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir "${BUILD_DIR:-build}" --output-on-failure -j2
bash scripts/check_determinism.sh
bash scripts/check_sanitizers.sh
bash scripts/fuzz.sh 20
bash scripts/check_format.sh
