#!/usr/bin/env bash
# hostile.sh PEMREF DATA_DIR — damaged and hostile trace and PEM directories: truncated or
# wrong-size EXR files, maps of the wrong resolution, missing files, manifests that disagree
# with the trace, symbolic links leading outside the directory, garbage JSON. Each gives one
# error line naming the file and the cause, a non-zero exit and no crash; extra files are
# ignored. Nothing outside the named directories is read: a link to a file outside is refused.
set -u
pemref=$1 data=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/pem_hostile.XXXXXX")
trap 'rm -rf "$work"' EXIT
failed=0 passed=0
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }

"$pemref" bake "$data/scenes/mirror_sphere.gltf" --out "$work/good" --views circle:2:10 \
    --size 64x48 --spp 1 --res 8 --quiet || { echo "FAIL: setup bake"; exit 1; }
"$pemref" bake "$data/scenes/mirror_sphere.gltf" --out "$work/res16" --views circle:2:10 \
    --size 64x48 --spp 1 --res 16 --quiet || { echo "FAIL: setup bake"; exit 1; }
echo "outside the directory" > "$work/secret.exr"

# expect NAME MUST_NAME COMMAND... — a fresh copy of the good bake in $d, damaged by `damage`
# (a function the caller set), then COMMAND must fail with one line naming MUST_NAME.
expect() {
  local name=$1 must=$2; shift 2
  d="$work/case_$name"; rm -rf "$d"; cp -r "$work/good" "$d"
  damage
  local err code lines
  err=$("$@" 2>&1 >/dev/null); code=$?
  lines=$(printf '%s\n' "$err" | grep -c .)
  if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$lines" -eq 1 ] && grep -qF -- "$must" <<<"$err"; then
    passed=$((passed + 1))
  else
    fail "$name: exit $code, $lines line(s), wanted '$must': $err"
  fi
}
render() { "$pemref" render "$d/pem" --view sample:0 --method "$1" -o "$work/out.png" --quiet; }
infer() { "$pemref" infer "$d/trace" --out "$d/pem2" --res 8 --quiet; }

map="pem/view_000/group_0/pem_distant.exr"
damage() { truncate -s 300 "$d/$map"; }; expect truncated_map "$map" render pem
damage() { : > "$d/$map"; }; expect empty_map "$map" render pem
damage() { cp "$work/res16/$map" "$d/$map"; }; expect map_of_other_size "face size 16" render pem
damage() { rm "$d/$map"; }; expect missing_map "missing maps" render pem
damage() { rm "$d/$map"; ln -s "$work/secret.exr" "$d/$map"; }; expect map_linked_outside "leads outside" render pem
damage() { rm -r "$d/pem/view_000"; ln -s "$work/res16/pem/view_000" "$d/pem/view_000"; }
expect view_linked_outside "leads outside" render hybrid
damage() { echo '{"format": "pemref_pem", "version": 2, "views": [' > "$d/pem/manifest.json"; }
expect garbage_manifest "manifest.json" render hybrid
damage() { sed -i 's/"inferred_views": \[/"inferred_views": [7, /' "$d/pem/manifest.json"; }
expect inferred_view_missing "manifest.json" render hybrid
damage() { sed -i 's/"res": 8/"res": 0/' "$d/pem/manifest.json"; }
expect manifest_res_wrong "manifest.json: res 0" render pem
img="trace/view_001/group_0/b_R.exr"
damage() { truncate -s 100 "$d/$img"; }; expect truncated_trace_image "$img" infer
damage() { cp "$d/trace/view_001/reference.exr" "$d/$img"; }; expect wrong_channels "$img" infer
damage() { rm "$d/$img"; }; expect missing_trace_image "$img" infer
damage() { rm "$d/$img"; ln -s "$work/secret.exr" "$d/$img"; }; expect trace_image_outside "leads outside" infer
damage() { python3 - "$d/trace/trace.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1])); j["views"].append(j["views"][0]); json.dump(j, open(sys.argv[1], "w"))
PY
}
expect view_count_mismatch "view_002" infer
damage() { sed -i 's/"size": \[/"size": [1, /' "$d/trace/trace.json"; }; expect size_garbage "trace.json" infer
damage() { sed -i 's#"scene": "[^"]*"#"scene": "../../../etc/passwd"#; s#"scene_given": "[^"]*"#"scene_given": "/etc/passwd"#' "$d/trace/trace.json"; }
expect scene_not_gltf "passwd" infer

# Extra files and directories are ignored.
d="$work/extra"; cp -r "$work/good" "$d"
mkdir -p "$d/pem/view_000/group_0/junk" && echo x > "$d/pem/view_009.txt" && echo y > "$d/pem/view_000/group_0/layer_9.exr"
if "$pemref" render "$d/pem" --view sample:0 -o "$work/extra.png" --quiet; then passed=$((passed + 1)); else fail "extra files"; fi

echo "hostile: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
