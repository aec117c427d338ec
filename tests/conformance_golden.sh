#!/usr/bin/env bash
# conformance_golden.sh GEN_CASES PEMREF REPO OUT — the hardware models checked without a GL
# driver: the generated corpus rendered with the llvmpipe and softpipe profiles must give the
# pixel hashes kept in tests/data/conformance_golden/golden.json and
# tests/data/conformance_golden_softpipe/golden.json (made with `pemref golden generate CASES
# --hashes-only [--profile softpipe]`, the cases having passed against live llvmpipe and
# softpipe; the softpipe goldens cover the RGBA8 cases only, gen_cases --rgba8-only; an RGBA32F
# frame's hash is its 8-bit view, the live test compares its floats). A mismatch leaves the
# rendered image under OUT/diff. After a deliberate change to the generator or a model (and a passing conformance_tests run against both live drivers):
#   pemref golden update OUT/cases tests/data/conformance_golden
#   pemref golden update OUT/cases_rgba8 tests/data/conformance_golden_softpipe
set -euo pipefail
gen=$1 pemref=$2 repo=$3 out=$4
rm -rf "$out" && mkdir -p "$out"
"$gen" "$out/cases" >/dev/null
"$gen" "$out/cases_rgba8" --rgba8-only >/dev/null  # the softpipe model draws RGBA8 only
for g in conformance_golden conformance_golden_softpipe; do
  cases=$out/cases
  [ "$g" = conformance_golden_softpipe ] && cases=$out/cases_rgba8
  "$pemref" golden check "$cases" "$repo/tests/data/$g" --diff-dir "$out/diff_$g" \
    --threads 2 | grep -v '^PASS'
done
