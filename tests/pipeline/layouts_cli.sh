#!/usr/bin/env bash
# layouts_cli.sh PEMREF DATA_DIR MASKED_PSNR — the notes' five EM layouts through the command line:
#  1. scene (a) traced once; `infer --parameterization` for each layout: the manifest names it,
#     a 2D layout's maps are plain W x H OpenEXR images of the layout's shape (exrheader: no
#     envmap attribute; the paraboloid's and the tennis ball's two textures side by side, with
#     pemrefCharts 2), and the hybrid and PEM frames drawn from them at the sample come closer
#     to the traced two-term frame than the static EM (by 3 dB) on every lens group (the outside check:
#     masked_psnr against the trace's greedy.exr on b_R's pixels), the cube's figures beside;
#     the static EM traced in each layout (render --parameterization) within 2 dB of the
#     cube's, and the PEM methods refusing a layout that is not their maps';
#  2. each 2D PEM packed losslessly (predictive, and JPEG 2000 at ratio 1): the hybrid frame
#     from the pack byte-identical to the directory's; a lossy pack (--ratio 8) renders, and
#     unpacks to a directory of the same layout; a manifest naming an unknown layout: one error
#     line;
#  3. `pemref study` on the mirror sphere at a small size: study.md, study.svg, study.json with
#     every layout and size, finite scores, map pictures that exist; impossible studies (a size
#     or layout twice, a size that is not a power of two, an unknown layout) one error line each.
set -euo pipefail
pemref=$1 data=$2 masked_psnr=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/pem_layouts.XXXXXX")
trap 'rm -rf "$work"' EXIT
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3

# Step 1: one trace, five layouts.
"$pemref" trace "$data/scenes/hybrid_glass_teapot.gltf" --out "$work/trace" --views circle:2:10 \
    --size 160x120 --spp 2 --threads 2 --quiet
for p in cube latlong sphere paraboloid tennis; do
  "$pemref" infer "$work/trace" --out "$work/$p" --res 32 --parameterization "$p" --threads 2 \
      --quiet
  grep -q "\"parameterization\": \"$p\"" "$work/$p/manifest.json" ||
    { echo "FAIL: $p: the manifest does not name the layout"; exit 1; }
  for m in hybrid pem; do
    "$pemref" render "$work/$p" --view sample:0 --method "$m" --threads 2 --quiet \
        -o "$work/${p}_$m.exr"
  done
done
"$pemref" render "$work/cube" --view sample:0 --method static --threads 2 --quiet \
    -o "$work/static.exr"
# A 2D map's shape (n = 32): lat-long 2n x n, the sphere map n x n, the paraboloid two n x n
# textures, the tennis ball two 2n x n/2 bands, each pair side by side.
for pwhc in latlong:64:32:1 sphere:32:32:1 paraboloid:64:32:2 tennis:128:16:2; do
  IFS=: read -r p w h charts <<<"$pwhc"
  hdr=$(exrheader "$work/$p/view_000/group_0/layer_0.exr")
  grep -q "dataWindow (type box2i): (0 0) - ($((w - 1)) $((h - 1)))" <<<"$hdr" ||
    { echo "FAIL: $p: layer_0.exr is not ${w} x ${h}"; echo "$hdr"; exit 1; }
  if grep -q "envmap" <<<"$hdr"; then echo "FAIL: $p: a 2D map with an envmap attribute"; exit 1; fi
  if [ "$charts" = 2 ]; then
    grep -q "pemrefCharts (type int): 2" <<<"$hdr" ||
      { echo "FAIL: $p: layer_0.exr does not say it holds two charts"; echo "$hdr"; exit 1; }
  elif grep -q "pemrefCharts" <<<"$hdr"; then
    echo "FAIL: $p: one texture, but pemrefCharts"; exit 1
  fi
done
for g in 0 1; do
  mask="$work/trace/view_000/group_$g/b_R.exr"
  read -r static_db _ < <("$masked_psnr" "$work/static.exr" "$work/trace/view_000/greedy.exr" "$mask")
  line="group $g: static EM $static_db dB"
  for p in cube latlong sphere paraboloid tennis; do
    for m in hybrid pem; do
      read -r db _ < <("$masked_psnr" "$work/${p}_$m.exr" "$work/trace/view_000/greedy.exr" "$mask")
      line+=", $p $m $db"
      awk -v a="$db" -v s="$static_db" 'BEGIN { exit !(a >= s + 3) }' ||
        { echo "FAIL: $line: not 3 dB closer to the traced frame than the static EM"; exit 1; }
    done
  done
  echo "$line"
done

# The static EM in each layout (render --parameterization, traced in the layout at the PEM's
# size): the same environment sampled differently, so within 2 dB of the cube's on each group
# (1.4 measured: lat-long's poles and the sphere map's rim on the mirror cup).
for p in cube latlong sphere paraboloid tennis; do
  "$pemref" render "$work/cube" --view sample:0 --method static --parameterization "$p" \
      --threads 2 --quiet -o "$work/static_$p.exr"
done
cmp "$work/static_cube.exr" "$work/static.exr" ||
  { echo "FAIL: static EM: the cube layout differs from the default"; exit 1; }
for g in 0 1; do
  mask="$work/trace/view_000/group_$g/b_R.exr"
  read -r cube_db _ < <("$masked_psnr" "$work/static.exr" "$work/trace/view_000/greedy.exr" "$mask")
  line="group $g static EM: cube $cube_db"
  for p in latlong sphere paraboloid tennis; do
    read -r db _ < <("$masked_psnr" "$work/static_$p.exr" "$work/trace/view_000/greedy.exr" "$mask")
    line+=", $p $db"
    awk -v a="$db" -v c="$cube_db" 'BEGIN { exit !(a >= c - 2 && a <= c + 2) }' ||
      { echo "FAIL: $line: not within 2 dB of the cube's static EM"; exit 1; }
  done
  echo "$line"
done
# The PEM methods draw the maps' own layout: another one is one error line.
if err=$("$pemref" render "$work/cube" --view sample:0 --method hybrid --parameterization sphere \
    -o "$work/no.png" --quiet 2>&1); then
  echo "FAIL: cube maps drawn as sphere maps"; exit 1
fi
[ "$(wc -l <<<"$err")" -eq 1 ] && grep -q "holds cube maps" <<<"$err" ||
  { echo "FAIL: --parameterization against the maps' layout: got: $err"; exit 1; }

# Step 2: packs of 2D maps.
for p in latlong sphere paraboloid tennis; do
  for opt in "" "--ratio 1"; do
    # shellcheck disable=SC2086  # opt is empty or two words
    "$pemref" pack "$work/$p" -o "$work/$p.pempack" $opt --quiet
    "$pemref" render "$work/$p.pempack" --view sample:0 --method hybrid --threads 2 --quiet \
        -o "$work/${p}_packed.exr"
    cmp "$work/${p}_packed.exr" "$work/${p}_hybrid.exr" ||
      { echo "FAIL: $p: the lossless pack ($opt) renders another frame"; exit 1; }
    rm "$work/$p.pempack"
  done
done
"$pemref" pack "$work/tennis" -o "$work/t.pempack" --ratio 8 --quiet
"$pemref" render "$work/t.pempack" --view sample:0 --method hybrid --threads 2 --quiet \
    -o "$work/tennis_lossy.exr"
"$pemref" unpack "$work/t.pempack" -o "$work/tennis_unpacked" >/dev/null
grep -q '"parameterization": "tennis"' "$work/tennis_unpacked/manifest.json" ||
  { echo "FAIL: the unpacked tennis PEM does not name its layout"; exit 1; }
"$pemref" render "$work/tennis_unpacked" --view sample:0 --method hybrid --threads 2 --quiet \
    -o "$work/tennis_unpacked.exr"
cmp "$work/tennis_unpacked.exr" "$work/tennis_lossy.exr" ||
  { echo "FAIL: the unpacked lossy tennis PEM renders another frame than its pack"; exit 1; }

# A manifest naming an unknown layout: one error line naming it.
cp -r "$work/sphere" "$work/bad"
sed -i 's/"parameterization": "sphere"/"parameterization": "cylinder"/' "$work/bad/manifest.json"
if err=$("$pemref" render "$work/bad" --view sample:0 -o "$work/bad.png" --quiet 2>&1); then
  echo "FAIL: a manifest with an unknown layout was rendered"; exit 1
fi
[ "$(wc -l <<<"$err")" -eq 1 ] && grep -q "manifest.json.*unknown parameterization 'cylinder'" <<<"$err" ||
  { echo "FAIL: unknown layout: expected one line naming manifest.json, got: $err"; exit 1; }

# Step 3: the study.
"$pemref" study "$data/scenes/mirror_sphere.gltf" --out "$work/study" --sizes 4,16 \
    --size 80x60 --reference-spp 2 --threads 2 --quiet
"$py" - "$work/study" <<'PY'
import json, math, os, sys
d = sys.argv[1]
s = json.load(open(f"{d}/study.json"))
layouts = {"cube", "latlong", "sphere", "paraboloid", "tennis"}
points = s["points"]
assert {p["layout"] for p in points} == layouts, points
assert len(points) == 10, len(points)
texels = {"cube": 6, "latlong": 2, "sphere": 1, "paraboloid": 2, "tennis": 2}
for p in points:
    assert p["texels"] == texels[p["layout"]] * p["size"] ** 2, p
    assert len(p["scores"]) == 9, p  # 3 positions x (hybrid, layered PEM, static EM)
    for q in p["scores"]:
        assert q["psnr"] is not None and math.isfinite(q["psnr"]), p
    assert os.path.exists(f"{d}/{p['picture']}"), p["picture"]
    assert os.path.exists(f"{d}/{p['pem_dir']}/manifest.json"), p["pem_dir"]
md = open(f"{d}/study.md").read()
for name in layouts:
    assert f"| {name} | 16 |" in md, name
svg = open(f"{d}/study.svg").read()
assert svg.count("<polyline") == 5 * 3, svg.count("<polyline")
# The inferred maps beat the static EM of the same layout and size on the sample (8 and 16 texels
# a side hold little; the static EM is one map for every view, the PEM the sample's own).
for p in points:
    if p["size"] == 16:
        on = {q["method"]: q["psnr"] for q in p["scores"] if q["position"] == "on circle"}
        assert on["hybrid"] > on["static EM"], p
print("study: 10 points, every layout, method and position scored")
PY
# Impossible studies: one error line each, nothing written.
for bad in "--sizes 4,4" "--sizes 3" "--layouts cube,cube" "--layouts cylinder"; do
  if err=$("$pemref" study "$data/scenes/mirror_sphere.gltf" --out "$work/nostudy" $bad --quiet 2>&1); then
    echo "FAIL: study $bad accepted"; exit 1
  fi
  [ "$(wc -l <<<"$err")" -eq 1 ] && [ ! -e "$work/nostudy" ] ||
    { echo "FAIL: study $bad: expected one error line and no output, got: $err"; exit 1; }
done
echo "PASS: layouts_cli"
