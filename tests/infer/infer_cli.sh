#!/usr/bin/env bash
# infer_cli.sh — `pemref trace` then `pemref infer --export-system` on scene (a) at a tiny size;
# infer_cli_check.py checks infer.json, the files, and re-solves one exported system with scipy.
# Usage: infer_cli.sh PEMREF SCENE CHECK_PY. Fails (never skips) when python3 or scipy is missing.
set -euo pipefail
pemref=$1 scene=$2 check=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/pem_infer_cli.XXXXXX")
trap 'rm -rf "$work"' EXIT
# The system python (apt's python3-scipy, scripts/setup.sh) before whatever python3 is first on PATH.
py=python3
if [ -x /usr/bin/python3 ] && /usr/bin/python3 -c 'import scipy' 2>/dev/null; then py=/usr/bin/python3; fi
"$py" -c 'import numpy, scipy.sparse, scipy.optimize' || {
    echo "FAIL: python3 with numpy and scipy is required (scripts/setup.sh installs python3-scipy)"
    exit 1
}
"$pemref" trace "$scene" --out "$work/trace" --size 64x48 --spp 1 --layers 2 --views camera \
    --threads 2 --quiet
"$pemref" infer "$work/trace" --out "$work/pem" --res 16 --threads 2 --quiet \
    --export-system "$work/system"
"$py" "$check" "$work/pem" "$work/system"
