#!/usr/bin/env bash
# The sanitizer jobs of the test command (scripts/test.sh):
#  - AddressSanitizer + UndefinedBehaviorSanitizer (float-cast-overflow on, no recovery) over the
#    unit suites of base, raster, trace, infer, runtime and pipeline, and a small bake;
#  - ThreadSanitizer over the worker pool and parallel loop (base_tests) and a bake with two
#    samples inferred at once (--jobs 2), the two places where threads share state.
# Builds into build-asan/ and build-tsan/ (Debug, -O1). Prints what ran; fails on any report.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
scene="$root/data/scenes/mirror_sphere.gltf"
bake=(--views circle:2:10 --size 64x48 --spp 1 --res 8 --quiet)

configure() {  # dir option
  cmake -S "$root" -B "$1" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" \
    -DPEM_GL=OFF "-D$2=ON" >/dev/null
}

# Step 1: ASan + UBSan.
configure build-asan PEM_SANITIZE
suites=(base_tests raster_tests trace_tests infer_tests runtime_tests pipeline_tests)
cmake --build build-asan -j"$(nproc)" --target pemref "${suites[@]}" >/dev/null
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
for t in "${suites[@]}"; do
  bin=$(find build-asan/tests -name "$t" -type f | head -1)
  # The slowest determinism and recovery tests are covered by the Release run.
  "$bin" --gtest_brief=1 --gtest_filter='-Determinism.*:Recovery.*' >/dev/null ||
    { echo "sanitizers: $t failed under ASan+UBSan"; exit 1; }
  echo "asan+ubsan: $t passed"
done
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
build-asan/bin/pemref bake "$scene" --out "$tmp/asan" "${bake[@]}"
build-asan/bin/pemref render "$tmp/asan/pem" -o "$tmp/asan.png" --quiet
echo "asan+ubsan: bake and render passed"

# Step 2: TSan.
configure build-tsan PEM_TSAN
cmake --build build-tsan -j"$(nproc)" --target pemref base_tests >/dev/null
export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$root/tests/tsan.supp"
build-tsan/tests/base/base_tests --gtest_brief=1 >/dev/null || { echo "sanitizers: base_tests failed under TSan"; exit 1; }
echo "tsan: base_tests passed"
build-tsan/bin/pemref bake "$scene" --out "$tmp/tsan" "${bake[@]}" --jobs 2 --threads 2
echo "tsan: bake --jobs 2 --threads 2 passed"
