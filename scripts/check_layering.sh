#!/usr/bin/env bash
# check_layering.sh [--self-test] — fails on any #include or target link of pemref's code that
# points up the layers or sideways between siblings (scripts/check_layering.py has the table),
# naming the file and line. --self-test: the check must fail on a copy of the tree with one
# upward include added (raster/frame.h including trace/scene.h) and name that line.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3
if [ "${1:-}" != "--self-test" ]; then
  exec "$py" "$here/check_layering.py" --root "$root"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
(cd "$root" && find base raster trace infer runtime pipeline viewer_tty \
   \( -name '*.h' -o -name '*.cpp' -o -name CMakeLists.txt \) -print0 | tar -cf - --null -T -) |
  tar -xf - -C "$tmp"
line=$(grep -n '^#include' "$tmp/raster/frame.h" | tail -1 | cut -d: -f1)
sed -i "${line}a #include \"trace/scene.h\"" "$tmp/raster/frame.h"
if out=$("$py" "$here/check_layering.py" --root "$tmp"); then
  echo "FAIL: an upward include (raster/frame.h -> trace/scene.h) passed the check"; exit 1
fi
expected="raster/frame.h:$((line + 1)): raster/ includes \"trace/scene.h\""
grep -qF "$expected" <<<"$out" || { echo "FAIL: expected '$expected' in:"; echo "$out"; exit 1; }
echo "PASS: the check fails on the added upward include: $expected"
