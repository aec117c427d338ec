#!/usr/bin/env bash
# conformance_golden.sh GEN_CASES PEMREF REPO OUT — the hardware model checked without a GL
# driver: the generated corpus rendered with the llvmpipe profile must give the pixel hashes
# kept in tests/data/conformance_golden/golden.json (made with `pemref golden generate CASES
# --hashes-only`, the cases having passed against live llvmpipe). A mismatch leaves the rendered
# image under OUT/diff. After a deliberate change to the generator or the model (and a passing
# conformance_tests run against live llvmpipe):
#   pemref golden update OUT/cases tests/data/conformance_golden
set -euo pipefail
gen=$1 pemref=$2 repo=$3 out=$4
rm -rf "$out" && mkdir -p "$out"
"$gen" "$out/cases" >/dev/null
"$pemref" golden check "$out/cases" "$repo/tests/data/conformance_golden" --diff-dir "$out/diff" \
  --threads 2 | grep -v '^PASS'
