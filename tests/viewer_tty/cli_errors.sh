#!/usr/bin/env bash
# Bad case files: `pemref raster BAD.json -o OUT.png --matrix OUT.mtx` must print exactly one
# line on stderr naming the file, exit non-zero, and leave no output file behind.
set -u
pemref=$1; dir=$2
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
passed=0; failed=0
for f in "$dir"/*.json; do
  err=$("$pemref" raster "$f" -o "$tmp/out.png" --matrix "$tmp/out.mtx" 2>&1 >/dev/null); code=$?
  lines=$(printf '%s\n' "$err" | grep -c .)
  leftovers=$(ls -A "$tmp" | wc -l)
  if [ "$code" -ne 0 ] && [ "$lines" -eq 1 ] && [[ $err == *"$(basename "$f")"* ]] && [ "$leftovers" -eq 0 ]; then
    passed=$((passed+1))
  else
    echo "FAIL $(basename "$f"): exit $code, $lines lines, $leftovers files: $err"; failed=$((failed+1))
  fi
done
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ] && [ "$passed" -ge 15 ]
