#!/usr/bin/env bash
# golden_cli.sh PEMREF REPO — `pemref golden` from the command line: the README's walkthrough
# run as written (in a scratch folder that mirrors the repository), its JUnit file parsed, then
# every sub-command's exit codes: 0 pass/accepted, 1 fail/rejected, 2 could not run.
set -uo pipefail
pemref=$(readlink -f "$1"); repo=$(readlink -f "$2")
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
fails=0
expect() {  # expect CODE DESCRIPTION -- command...
  local want=$1 what=$2; shift 3
  "$@" >"$work/out.txt" 2>&1; local got=$?
  if [ "$got" -ne "$want" ]; then
    echo "FAIL: $what: exit $got, expected $want"; sed 's/^/    /' "$work/out.txt"; fails=$((fails + 1))
  else echo "ok: $what (exit $got)"; fi
}
contains() {  # contains TEXT FILE DESCRIPTION
  grep -qF -- "$1" "$2" || { echo "FAIL: $3: no \"$1\""; sed 's/^/    /' "$2"; fails=$((fails + 1)); }
}

# 1. The README's walkthrough, as written, from a folder that looks like the repository.
mkdir -p "$work/repo/build/bin" && cd "$work/repo" || exit 1
ln -s "$repo/tests" tests && ln -s "$repo/data" data && ln -s "$pemref" build/bin/pemref
sed -n '/<!-- golden-walkthrough -->/,/<!-- end-golden-walkthrough -->/p' "$repo/README.md" |
  sed '1,2d;$d' | sed '$d' >walkthrough.sh
bash -x walkthrough.sh >walkthrough.log 2>&1
contains "FAIL quad32" walkthrough.log "the walkthrough's check fails on the changed input"
contains "re-blessed: quad32" walkthrough.log "update re-blesses the changed test"
contains "2 tests, 0 failed" walkthrough.log "the last check passes"
for f in my_goldens/quad32.png my_goldens/sphere.png my_goldens/golden.json \
         my_goldens/diff/quad32.diff.png my_goldens/diff/quad32.side.png; do
  [ -s "$f" ] || { echo "FAIL: walkthrough: $f missing"; fails=$((fails + 1)); }
done
/usr/bin/python3 - junit.xml <<'EOF' || fails=$((fails + 1))
import sys, xml.etree.ElementTree as ET
root = ET.parse(sys.argv[1]).getroot()
suite = root.find("testsuite")
cases = {c.get("name"): c for c in suite.findall("testcase")}
failed = [n for n, c in cases.items() if c.find("failure") is not None]
ok = (root.tag == "testsuites" and suite.get("tests") == "2" and suite.get("failures") == "1"
      and set(cases) == {"quad32", "sphere"} and failed == ["quad32"]
      and "pixels differ" in cases["quad32"].find("failure").get("message")
      and "quad32.diff.png" in cases["quad32"].find("failure").text)
print("ok: JUnit parsed: 2 tests, quad32 failed" if ok else "FAIL: JUnit: " + ET.tostring(root, "unicode"))
sys.exit(0 if ok else 1)
EOF

# 2. Exit codes.
suite=$repo/tests/data/golden_suite
expect 0 "generate the repository's suite" -- "$pemref" golden generate "$suite" --out "$work/g"
expect 0 "check it" -- "$pemref" golden check "$suite" "$work/g" --junit "$work/j.xml"
expect 1 "compare two different goldens" -- \
  "$pemref" golden compare "$work/g/quad32.png" "$work/g/cube64_fuzzy.png" --diff "$work/d.png"
[ -s "$work/d.png" ] || { echo "FAIL: compare --diff wrote nothing"; fails=$((fails + 1)); }
expect 0 "compare a golden with itself" -- "$pemref" golden compare "$work/g/quad32.png" "$work/g/quad32.png"
expect 0 "compare two goldens fuzzily (255, every pixel)" -- \
  "$pemref" golden compare "$work/g/cube64_fuzzy.png" "$work/g/cube64_bounds.png" --fuzzy 255,4096
expect 0 "the model bounds accept the llvmpipe golden" -- \
  "$pemref" golden compare --bounds "$suite/cube64_bounds" "$work/g/cube64_bounds.png" --lsb 0
expect 1 "the model bounds reject another picture" -- \
  "$pemref" golden compare --bounds "$suite/cube64_bounds" "$work/g/quad32.png"
expect 2 "compare a missing file" -- "$pemref" golden compare "$work/g/quad32.png" "$work/none.png"
expect 2 "compare with a malformed --fuzzy" -- \
  "$pemref" golden compare "$work/g/quad32.png" "$work/g/quad32.png" --fuzzy 3
expect 2 "check a missing suite" -- "$pemref" golden check "$work/none" "$work/g"
expect 2 "check against a missing golden directory" -- "$pemref" golden check "$suite" "$work/none"
expect 2 "check with another profile than the goldens'" -- \
  "$pemref" golden check "$suite" "$work/g" --profile linear
rm "$work/g/sphere_static.png"
expect 2 "check with a golden PNG missing" -- "$pemref" golden check "$suite" "$work/g"
contains "sphere_static.png" "$work/out.txt" "the missing file is named"
mkdir -p "$work/bad" && echo '{"format": "pemref_golden_suite", "version": 1, "tests": [{"name": 1}]}' >"$work/bad/suite.json"
expect 2 "generate from a malformed suite.json" -- "$pemref" golden generate "$work/bad" --out "$work/b"
[ ! -e "$work/b" ] || { echo "FAIL: a failed generate left $work/b"; fails=$((fails + 1)); }
expect 2 "an unknown sub-command" -- "$pemref" golden frob

echo "golden_cli: $fails failed"
[ "$fails" -eq 0 ]
