#!/usr/bin/env bash
# Builds pemref three ways (gcc -O0, gcc -O3, clang -O2) and checks that every conformance case
# and the benchmark frame hash the same in each build, with 1 and 2 threads, and with the
# baseline fragment stage forced (PEM_ISA=base). Prints "N passed, M failed".
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
out=${DET_DIR:-$root/build-determinism}
mkdir -p "$out"

build() {  # name cxx build_type
  local dir="$out/$1"
  CXX=$2 cmake -S "$root" -B "$dir" -DCMAKE_BUILD_TYPE="$3" -DPEM_BUILD_TESTS=OFF -DPEM_GL=OFF \
    >/dev/null
  cmake --build "$dir" -j"$(nproc)" --target pemref >/dev/null
}
build gcc-O0 g++ Debug
build gcc-O3 g++ Release
if command -v clang++ >/dev/null; then build clang-O2 clang++ RelWithDebInfo; fi

# The corpus, written by the test build's case generator (or built here).
gen="${BUILD_DIR:-build}/tests/gen_cases"
[ -x "$gen" ] || { cmake --build "${BUILD_DIR:-build}" --target gen_cases >/dev/null; }
cases="$out/cases"
rm -rf "$cases" && "$gen" "$cases" >/dev/null

passed=0; failed=0
for c in "$cases"/*.json; do
  ref=""
  for dir in "$out"/gcc-O0 "$out"/gcc-O3 "$out"/clang-O2; do
    [ -x "$dir/bin/pemref" ] || continue
    for variant in "--threads 1" "--threads 2" "--threads 2 base"; do
      args=${variant% base}
      if [[ $variant == *base ]]; then
        h=$(PEM_ISA=base "$dir/bin/pemref" raster "$c" $args)
      else
        h=$("$dir/bin/pemref" raster "$c" $args)
      fi
      if [ -z "$ref" ]; then ref=$h; elif [ "$h" != "$ref" ]; then
        echo "MISMATCH $(basename "$c") $(basename "$dir") $variant: $h vs $ref"; failed=$((failed+1)); continue 2
      fi
    done
  done
  passed=$((passed+1))
done
echo "determinism: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
