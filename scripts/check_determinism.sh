#!/usr/bin/env bash
# Builds pemref three ways (gcc -O0, gcc -O3, clang -O2) and checks that goldens come out the
# same in each build, with 1 and 2 threads, and with the baseline fragment stage forced
# (PEM_ISA=base): the whole conformance corpus and the benchmark frame (hashes; llvmpipe and
# softpipe profiles; the softpipe model's RGBA8 cases), the floats of the RGBA32F colour buffers
# (`pemref raster`'s hash), and the example golden suite (raster cases, a traced and a static-EM
# scene: golden.json and every PNG, byte for byte). Prints "determinism: N passed, M failed" (N: tests compared in every run).
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
cases="$out/cases" cases8="$out/cases_rgba8"
rm -rf "$cases" "$cases8" && "$gen" "$cases" >/dev/null
"$gen" "$cases8" --rgba8-only >/dev/null  # what the softpipe model draws

# Every build × (1 thread, 2 threads, 2 threads baseline ISA) generates both golden sets.
runs=()
for dir in "$out"/gcc-O0 "$out"/gcc-O3 "$out"/clang-O2; do
  [ -x "$dir/bin/pemref" ] || continue
  for variant in t1 t2 t2-base; do
    g="$out/golden/$(basename "$dir")-$variant"
    rm -rf "$g"
    isa=""; [ "$variant" = t2-base ] && isa=base
    threads=${variant#t}; threads=${threads%-base}
    PEM_ISA=$isa "$dir/bin/pemref" golden generate "$cases" --out "$g/corpus" --hashes-only \
      --threads "$threads" >/dev/null
    PEM_ISA=$isa "$dir/bin/pemref" golden generate "$cases8" --out "$g/corpus-softpipe" \
      --hashes-only --profile softpipe --threads "$threads" >/dev/null
    # RGBA32F colour buffers: the hash of their floats (the goldens hash their 8-bit view).
    mkdir -p "$g/float"
    for c in "$cases"/f32_*.json "$cases"/fb32_*.json "$cases"/lens.json; do
      echo "$(basename "$c" .json) $(PEM_ISA=$isa "$dir/bin/pemref" raster "$c" --threads "$threads")"
    done > "$g/float/hashes.txt"
    PEM_ISA=$isa "$dir/bin/pemref" golden generate tests/data/golden_suite --out "$g/suite" \
      --threads "$threads" >/dev/null
    runs+=("$g")
  done
done

# Compare every run with the first: per test (corpus: its pixels' hash; suite: its PNG's bytes).
/usr/bin/python3 - "${runs[@]}" <<'EOF'
import json, sys, filecmp, os
runs = sys.argv[1:]
def tests(run, part):
    return {t["name"]: t for t in json.load(open(os.path.join(run, part, "golden.json")))["tests"]}
passed = failed = 0
for part in ("corpus", "corpus-softpipe", "suite"):
    ref = tests(runs[0], part)
    for name, t in sorted(ref.items()):
        bad = []
        for run in runs[1:]:
            other = tests(run, part).get(name)
            same = other is not None and other["sha256"] == t["sha256"]
            if same and t["png"]:
                same = filecmp.cmp(os.path.join(runs[0], part, t["png"]),
                                   os.path.join(run, part, other["png"]), shallow=False)
            if not same:
                bad.append(os.path.basename(run))
        if bad:
            print(f"MISMATCH {part}/{name}: {', '.join(bad)} differ from {os.path.basename(runs[0])}")
            failed += 1
        else:
            passed += 1
# RGBA32F frames: one line per case, "name sha256: <hash of the floats>".
def floats(run):
    return dict(l.split(" ", 1) for l in open(os.path.join(run, "float", "hashes.txt")).read().splitlines())
ref = floats(runs[0])
for name, h in sorted(ref.items()):
    bad = [os.path.basename(r) for r in runs[1:] if floats(r).get(name) != h]
    if bad:
        print(f"MISMATCH float/{name}: {', '.join(bad)} differ from {os.path.basename(runs[0])}")
        failed += 1
    else:
        passed += 1
print(f"determinism: {passed} passed, {failed} failed ({len(runs)} runs each)")
sys.exit(1 if failed else 0)
EOF
