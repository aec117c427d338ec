#!/usr/bin/env bash
# Every tracked C++ file is clang-format clean (.clang-format). Prints "N passed, M failed".
set -uo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "clang-format not installed"; exit 1; }
passed=0; failed=0
while IFS= read -r f; do
  if clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then passed=$((passed+1));
  else echo "not formatted: $f"; failed=$((failed+1)); fi
done < <(git ls-files '*.h' '*.cpp')
echo "format: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
