#!/usr/bin/env bash
# fuzz.sh [SECONDS] [HARNESS...] — runs the libFuzzer harnesses (tests/fuzz/) for SECONDS each
# (default 20: the short run of the test command; the long runs use 600 or more), from seed
# corpora built out of tests/data, data/ and a small bake, keeping what they find in
# build-fuzz/corpus/<harness>. Built with clang, -fsanitize=fuzzer-no-link,address,undefined on
# the whole project. A crash, a hang (timeout 10 s), an out-of-memory or a sanitizer report fails
# it; the reproducer is left in build-fuzz/ and each known one is a regression input under
# tests/data/fuzz_regressions/<harness>/ (replayed first, every run).
# Prints, per harness: seconds, executions, coverage, corpus size.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
seconds=${1:-20}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(case gltf exr manifest keys png pack)
out=$root/build-fuzz

# Step 1: the build.
CXX=clang++ cmake -S "$root" -B "$out" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPEM_GL=OFF \
  -DPEM_FUZZ=ON -DPEM_WERROR=OFF \
  -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=(--target "fuzz_$h"); done
cmake --build "$out" -j"$(nproc)" "${targets[@]}" --target pemref >/dev/null

# Step 2: seed corpora (once; then the harnesses' own corpora grow).
seed() {  # harness files...
  local dir=$out/corpus/$1; shift
  mkdir -p "$dir"
  [ -n "$(ls -A "$dir")" ] && return 0
  for f in "$@"; do [ -f "$f" ] && cp "$f" "$dir/$(echo "$f" | md5sum | cut -c1-12)_$(basename "$f")"; done
  return 0
}
if [ ! -d "$out/seedbake" ]; then
  "$out/bin/pemref" bake "$root/data/scenes/mirror_sphere.gltf" --out "$out/seedbake" \
    --views circle:2:10 --size 32x24 --spp 1 --res 4 --quiet
fi
seed case "$root"/tests/data/cases/*.json "$root"/tests/data/bad_cases/*.json
seed gltf "$root"/data/scenes/*.gltf "$root"/tests/data/bad_scenes/*.gltf \
  "$root"/tests/data/trace_scenes/*.gltf $(find /usr/share/assimp/models/glTF2 -name '*.gltf' -size -64k 2>/dev/null | head -40)
seed exr "$root"/data/env/*.exr $(find "$out/seedbake" -name '*.exr' -size -64k | head -20)
seed manifest $(find "$out/seedbake" -name '*.json')
seed png $(find "$out/seedbake" "$root/tests/data" -name '*.png' -size -64k | head -20)
if [ ! -f "$out/seedbake/lossy.pempack" ]; then
  "$out/bin/pemref" pack "$out/seedbake/pem" -o "$out/seedbake/lossless.pempack" --quiet
  "$out/bin/pemref" pack "$out/seedbake/pem" -o "$out/seedbake/lossy.pempack" --max-error 3 --quiet
fi
seed pack "$out/seedbake/lossless.pempack" "$out/seedbake/lossy.pempack"
mkdir -p "$out/corpus/keys" && printf 'hjkl+-ud12345m[]rq\033[A\033[D' > "$out/corpus/keys/seed"

# Step 3: the regressions, then the runs.
status=0
for h in "${harnesses[@]}"; do
  reg=$root/tests/data/fuzz_regressions/$h
  if [ -d "$reg" ] && [ -n "$(ls -A "$reg")" ]; then
    "$out/tests/fuzz/fuzz_$h" "$reg"/* >/dev/null 2>&1 || { echo "fuzz $h: a regression input fails"; status=1; }
  fi
  log=$out/fuzz_$h.log
  if (cd "$out" && "$out/tests/fuzz/fuzz_$h" "$out/corpus/$h" -max_total_time="$seconds" \
        -timeout=10 -rss_limit_mb=3000 -max_len=65536 -print_final_stats=1 >"$log" 2>&1); then
    runs=$(grep -m1 'stat::number_of_executed_units' "$log" | awk '{print $2}')
    cov=$(grep -E '^#[0-9]+.*(DONE|pulse)' "$log" | tail -1 | grep -o 'cov: [0-9]*' || true)
    echo "fuzz $h: ${seconds} s, ${runs:-?} executions, ${cov:-cov: ?}, corpus $(ls "$out/corpus/$h" | wc -l)"
  else
    echo "fuzz $h: FOUND A DEFECT (log $log):"; grep -E 'ERROR|SUMMARY|Test unit written' "$log" | head -5
    status=1
  fi
done
exit $status
