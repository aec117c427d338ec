#!/usr/bin/env bash
# pipeline_cli.sh PEMREF DATA_DIR MASKED_PSNR — the user-facing pipeline at a small size:
#  1. scene (a): bake (3 samples), render every method and --stats, each sample ray traced through
#     render = the trace's reference byte for byte, the scripted viewer, report;
#     checks: files, statistics fields, viewer frames, report contents, and that off the sample
#     circle (10° above) hybrid and layered PEM are closer to the ray tracer than the static EM,
#     that PEM mode draws the mirror cup's inside as traced (its local layer), and that
#     --max-res (maps sized by a test rendering) brings the hybrid frame closer to the trace, and
#     float maps (--map-format rgba32f) are unbounded and at least as close;
#  2. the mirror sphere: bake + report; the report leaves out the refraction term (no glass) and
#     the PEM local layer (a convex reflector).
set -euo pipefail
pemref=$1 data=$2 masked_psnr=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/pem_pipeline.XXXXXX")
trap 'rm -rf "$work"' EXIT
py=python3
[ -x /usr/bin/python3 ] && py=/usr/bin/python3

# expect_gain LABEL A.exr B.exr MIN: frame B is at least MIN dB (MIN may be negative) closer than
# frame A to sample 1's two-term frame, on each lens group's pixels (its b_R coverage).
expect_gain() {
  local g mask a_db b_db
  for g in 0 1; do
    mask="$work/a/trace/view_001/group_$g/b_R.exr"
    read -r a_db _ < <("$masked_psnr" "$2" "$work/a/trace/view_001/greedy.exr" "$mask")
    read -r b_db _ < <("$masked_psnr" "$3" "$work/a/trace/view_001/greedy.exr" "$mask")
    awk -v a="$a_db" -v b="$b_db" -v m="$4" 'BEGIN { exit !(b >= a + m) }' ||
      { echo "FAIL: $1: group $g hybrid $b_db dB against $a_db"; exit 1; }
  done
}

# Step 1: scene (a).
"$pemref" bake "$data/scenes/hybrid_glass_teapot.gltf" --out "$work/a" --views circle:3:10 \
    --size 240x180 --spp 3 --res 64 --threads 2 --quiet
for m in hybrid pem static traced; do
  "$pemref" render "$work/a/pem" --view orbit:5:10:1 -o "$work/a/$m.png" --method "$m" \
      --threads 2 --quiet --stats "$work/a/$m.json"
done
"$pemref" render "$work/a/pem" --view sample:1 -o "$work/a/single.exr" --method pem --layers 1 \
    --threads 2 --quiet
"$pemref" view "$work/a/pem" --keys "l1k2m" --cols 40 --rows 12 --threads 2 > "$work/a/view.txt"
# Every sample's camera is the one it was traced with: the ray tracer through `render` gives the
# trace's reference of that sample, byte for byte.
for i in 0 1 2; do
  "$pemref" render "$work/a/pem" --view "sample:$i" --method traced --spp 3 --threads 2 --quiet \
      -o "$work/a/traced_$i.exr"
  cmp "$work/a/traced_$i.exr" "$work/a/trace/view_00$i/reference.exr" ||
    { echo "FAIL: render --view sample:$i --method traced differs from the trace's reference"; exit 1; }
done
"$pemref" report "$work/a" --threads 2 --reference-spp 5 --no-stability --quiet
# PEM mode at a sample, on the pixels of the mirror cup (group 1) that see the cup itself (its
# local layer's coverage): the local map fitted as it is drawn (off the hull, on the visible
# surface) gives 14.3 dB against the traced frame; fitted on every polygon, 9.6.
"$pemref" render "$work/a/pem" --view sample:1 --method pem --threads 2 --quiet -o "$work/a/pem_1.exr"
read -r local_db local_px < <("$masked_psnr" "$work/a/pem_1.exr" \
    "$work/a/trace/view_001/greedy.exr" "$work/a/trace/view_001/group_1/local.exr")
awk -v d="$local_db" -v n="$local_px" 'BEGIN { exit !(n > 50 && d >= 12) }' ||
  { echo "FAIL: PEM mode, the cup's local layer: $local_db dB over $local_px pixels (12 expected)"; exit 1; }
# Map resolution from a test rendering (PEM §4 "EM Resolution"): with --max-res each map's face
# size is the finest MIP level its sample's subpixels read, within [--res, --max-res]. The layer
# maps grow, and the hybrid frame comes closer to the traced one on both lens groups, by 2.5 and
# 3.0 dB when this was written (the outside check).
"$pemref" infer "$work/a/trace" --out "$work/a/pemmax" --res 64 --max-res 256 --views 1 \
    --threads 2 --quiet
for d in pem pemmax; do
  "$pemref" render "$work/a/$d" --view sample:1 --method hybrid --threads 2 --quiet \
      -o "$work/a/hybrid_$d.exr"
done
expect_gain "--max-res 256 against --res 64" "$work/a/hybrid_pem.exr" "$work/a/hybrid_pemmax.exr" 1
# Float maps (--map-format rgba32f): solved without bounds (texels below 0 and above 1), drawn
# as RGBA32F textures into an RGBA32F colour buffer; at this size the hybrid frame is as close
# to the traced one as with 8-bit maps or closer (+0.33 dB on the teapot, +0.00 on the cup when
# this was written; the gain grows with the resolution, README), both at LOD bias -4 (float
# maps default to -2.5, which trades sharpness at the samples for fewer speckles off them).
"$pemref" infer "$work/a/trace" --out "$work/a/pemf" --res 64 --views 1 --map-format rgba32f \
    --lod-bias -4 --threads 2 --quiet
grep -q '"map_format": "rgba32f"' "$work/a/pemf/manifest.json" ||
  { echo "FAIL: --map-format rgba32f not in the manifest"; exit 1; }
"$py" - "$work/a/pemf/infer.json" <<'PY' || { echo "FAIL: float maps stayed inside [0, 1]"; exit 1; }
import json, sys
maps = json.load(open(sys.argv[1]))["maps"]
sys.exit(0 if any(m["texel_min"] < 0 or m["texel_max"] > 1 for m in maps) else 1)
PY
"$pemref" render "$work/a/pemf" --view sample:1 --method hybrid --threads 2 --quiet \
    -o "$work/a/hybrid_pemf.exr"
expect_gain "float maps against 8-bit maps" "$work/a/hybrid_pem.exr" "$work/a/hybrid_pemf.exr" -0.1
# The maps fit the tessellation they were inferred on: `infer --t 3` keeps t in the manifest and
# `render` draws with it unless told otherwise (the same bytes as --t 3, not those of --t 5).
"$pemref" infer "$work/a/trace" --out "$work/a/pemt" --res 64 --views 1 --t 3 --threads 2 --quiet
for t in own 3 5; do
  arg=(); [ "$t" = own ] || arg=(--t "$t")
  "$pemref" render "$work/a/pemt" --view sample:1 --method hybrid "${arg[@]}" --threads 2 --quiet \
      -o "$work/a/t_$t.png"
done
cmp -s "$work/a/t_own.png" "$work/a/t_3.png" ||
  { echo "FAIL: render without --t does not draw with the maps' t"; exit 1; }
if cmp -s "$work/a/t_own.png" "$work/a/t_5.png"; then
  echo "FAIL: --t 3 and --t 5 draw the same frame"; exit 1
fi
# Float maps default to LOD bias -2.5, and inference records its topology threshold (2
# subpixels) for the renderers, who draw with it unless told otherwise (--t-topology 0: t alone,
# the paper's tessellation, another frame at t = 5; the stats name the one used).
"$pemref" infer "$work/a/trace" --out "$work/a/pemd" --res 16 --views 1 --map-format rgba32f \
    --threads 2 --quiet
grep -q '"lod_bias": -2.5' "$work/a/pemd/manifest.json" && grep -q '"t_topology": 2.0' \
    "$work/a/pemd/manifest.json" || { echo "FAIL: float maps' defaults not in the manifest"; exit 1; }
for topo in own 0; do
  arg=(); [ "$topo" = own ] || arg=(--t-topology "$topo")
  "$pemref" render "$work/a/pemt" --view sample:1 --method hybrid --t 5 "${arg[@]}" --threads 2 \
      --quiet -o "$work/a/topo_$topo.png" --stats "$work/a/topo_$topo.json"
done
grep -q '"t_topology": 2.0' "$work/a/topo_own.json" && grep -q '"t_topology": 0.0' \
    "$work/a/topo_0.json" || { echo "FAIL: --stats without the topology threshold"; exit 1; }
cmp -s "$work/a/t_5.png" "$work/a/topo_own.png" ||
  { echo "FAIL: render without --t-topology does not draw with the maps' threshold"; exit 1; }
if cmp -s "$work/a/topo_own.png" "$work/a/topo_0.png"; then
  echo "FAIL: --t-topology 0 and 2 draw the same frame at t = 5"; exit 1
fi
if "$pemref" render "$work/a/pemt" --t-topology 0.1 -o "$work/a/bad.png" --quiet 2>/dev/null; then
  echo "FAIL: --t-topology 0.1 accepted"; exit 1
fi
# Maps fitted at t = 1 alone are tuned to its vertices: drawn at the renderers' t = 5 they come
# out further from the traced frame than maps that also fit the rows of t = 5 (--also-t 5, kept
# in the manifest): +0.93 and +1.69 dB on the two groups when this was written, +0.47 on the
# teapot since t = 5 refines changes of path topology down to 2 subpixels (closer to t = 1), and
# at t = 1 the latter lose little (-0.21, -0.02 dB).
for d in p1 p15; do
  also=(); [ "$d" = p1 ] || also=(--also-t 5)
  "$pemref" infer "$work/a/trace" --out "$work/a/$d" --res 64 --views 1 --t 1 "${also[@]}" \
      --threads 2 --quiet
  for t in 1 5; do
    "$pemref" render "$work/a/$d" --view sample:1 --method hybrid --t $t --threads 2 --quiet \
        -o "$work/a/${d}_t$t.exr"
  done
done
grep -q '"also_t"' "$work/a/p15/manifest.json" || { echo "FAIL: --also-t not in the manifest"; exit 1; }
expect_gain "--also-t 5 drawn at t = 5" "$work/a/p1_t5.exr" "$work/a/p15_t5.exr" 0.25
expect_gain "--also-t 5 drawn at t = 1" "$work/a/p1_t1.exr" "$work/a/p15_t1.exr" -1
# The error budget of maps fitted at a t other than the renderers' default also lists the frame
# at that default t = 5, at the sample and off it; at the sample it is the frame `render --t 5`
# draws, so its PSNR against the two-term frame is the outside check's (masked_psnr).
mkdir "$work/b15"
cp "$work/a/bake.json" "$work/b15/"
ln -s "$work/a/trace" "$work/b15/trace"
ln -s "$work/a/p15" "$work/b15/pem"
"$pemref" report "$work/b15" --threads 2 --reference-spp 2 --no-stability --no-packs --quiet
for g in 0 1; do
  read -r db _ < <("$masked_psnr" "$work/a/p15_t5.exr" "$work/a/trace/view_001/greedy.exr" \
      "$work/a/trace/view_001/group_$g/b_R.exr")
  echo "$db"
done > "$work/b15/outside.txt"
"$py" - "$work/b15" <<'PY' || { echo "FAIL: the error budget at t = 5"; exit 1; }
import json, sys
d = sys.argv[1]
outside = [float(x) for x in open(f"{d}/outside.txt").read().split()]
budget = json.load(open(f"{d}/report.json"))["budget"]
for i, b in enumerate(b for b in budget if b["position"] == "on circle"):
    st = b["stages"]
    if [x["stage"] for x in st[-2:]] != ["hardware frame", "hardware frame at t=5"]: sys.exit(f"stages {st}")
    if abs(st[-1]["psnrVsTwoTerm"] - outside[i]) > 0.01: sys.exit(f"group {i}: {st[-1]} against {outside[i]}")
for b in budget:
    if b["position"] != "on circle" and [x["stage"] for x in b["stages"]] != ["hybrid at the sample", "off the samples", "off the samples at t=5"]: sys.exit(f"off the samples: {b}")
PY
# A baked directory renders from anywhere: copied elsewhere and rendered from another working
# directory, the same bytes.
cp -r "$work/a" "$work/copied"
(cd / && "$pemref" render "$work/copied/pem" --view sample:1 --method pem --threads 2 --quiet \
    -o "$work/copied/moved.png")
"$pemref" render "$work/a/pem" --view sample:1 --method pem --threads 2 --quiet -o "$work/a/here.png"
cmp "$work/copied/moved.png" "$work/a/here.png" || { echo "FAIL: a copied bake renders differently"; exit 1; }
# Packed PEMs: a lossless pack renders the same bytes as its directory (hybrid and PEM mode), also
# from another working directory; unpacked, the same again; a lossy pack renders; a pack is not a directory to
# unpack into.
"$pemref" pack "$work/a/pem" -o "$work/a/pem.pempack" --quiet
"$pemref" pack "$work/a/pem" -o "$work/a/lossy.pempack" --max-error 31 --ratio 32 --quiet
"$pemref" unpack "$work/a/pem.pempack" -o "$work/a/unpacked"
for src in "$work/a/pem" "$work/a/pem.pempack" "$work/a/unpacked" "$work/a/lossy.pempack"; do
  for m in hybrid pem; do
    "$pemref" render "$src" --view orbit:5:10:1 --method "$m" --threads 2 --quiet \
        -o "$work/a/packed_${m}_$(basename "$src").png"
  done
done
for m in hybrid pem; do
  for b in pem.pempack unpacked; do
    cmp "$work/a/packed_${m}_pem.png" "$work/a/packed_${m}_$b.png" ||
      { echo "FAIL: $m from $b differs from the directory's frame"; exit 1; }
  done
  cmp -s "$work/a/packed_${m}_pem.png" "$work/a/packed_${m}_lossy.pempack.png" &&
    { echo "FAIL: the lossy pack's $m frame equals the directory's"; exit 1; }
done
(cd / && "$pemref" render "$work/copied/../a/pem.pempack" --view sample:1 --method pem --threads 2 \
    --quiet -o "$work/a/pack_here.png")
cmp "$work/a/pack_here.png" "$work/a/here.png" || { echo "FAIL: the pack renders differently"; exit 1; }
if "$pemref" unpack "$work/a/pem.pempack" -o "$work/a/unpacked" 2>"$work/a/err.txt"; then
  echo "FAIL: unpack into an existing directory"; exit 1
fi
grep -q "exists" "$work/a/err.txt" || { echo "FAIL: unpack error: $(cat "$work/a/err.txt")"; exit 1; }
# Step 2: the mirror sphere.
"$pemref" bake "$data/scenes/mirror_sphere.gltf" --out "$work/s" --views circle:2:10 \
    --size 96x72 --spp 2 --res 16 --threads 2 --quiet
"$pemref" report "$work/s" --threads 2 --reference-spp 2 --no-stability --no-packs --quiet
# Anisotropic maps: inferred for and drawn with GL_TEXTURE_MAX_ANISOTROPY 16, kept in the manifest;
# a value outside GL's range is refused.
"$pemref" infer "$work/s/trace" --out "$work/s/pem16" --res 16 --anisotropy 16 --threads 2 --quiet
grep -q '"max_anisotropy": 16.0' "$work/s/pem16/manifest.json" ||
  { echo "FAIL: --anisotropy 16 not in the manifest"; exit 1; }
"$pemref" render "$work/s/pem16" --view sample:1 --method pem --threads 2 --quiet -o "$work/s/a16.png"
"$pemref" render "$work/s/pem" --view sample:1 --method pem --threads 2 --quiet -o "$work/s/a1.png"
! cmp -s "$work/s/a16.png" "$work/s/a1.png" || { echo "FAIL: anisotropic maps drawn isotropically"; exit 1; }
if "$pemref" infer "$work/s/trace" --out "$work/s/bad" --anisotropy 17 --quiet 2>/dev/null; then
  echo "FAIL: --anisotropy 17 accepted"; exit 1
fi
for r in 8 24; do  # below --res, not a power of two
  if "$pemref" infer "$work/s/trace" --out "$work/s/bad" --res 16 --max-res $r --quiet 2>/dev/null; then
    echo "FAIL: --max-res $r accepted with --res 16"; exit 1
  fi
done
# The LOD bias: the default is kept in the manifest; another bias draws other frames; a bias
# outside [-4, 4] is refused.
grep -q '"lod_bias": -4.0' "$work/s/pem/manifest.json" ||
  { echo "FAIL: the default LOD bias -4 not in the manifest"; exit 1; }
"$pemref" infer "$work/s/trace" --out "$work/s/pemlb0" --res 16 --lod-bias 0 --threads 2 --quiet
"$pemref" render "$work/s/pemlb0" --view sample:1 --method pem --threads 2 --quiet -o "$work/s/lb0.png"
! cmp -s "$work/s/lb0.png" "$work/s/a1.png" || { echo "FAIL: the LOD bias changes nothing"; exit 1; }
if "$pemref" infer "$work/s/trace" --out "$work/s/bad" --lod-bias -5 --quiet 2>/dev/null; then
  echo "FAIL: --lod-bias -5 accepted"; exit 1
fi
# Golden images of its PEM directory: the same bytes with 1 and 2 threads, and check passes.
mkdir -p "$work/gs"
cat > "$work/gs/suite.json" <<'EOF'
{"format": "pemref_golden_suite", "version": 1, "tests": [
 {"name": "hybrid", "pem": "../s/pem", "view": "sample:1", "method": "hybrid"},
 {"name": "pem", "pem": "../s/pem", "view": "orbit:5:0:1", "method": "pem", "size": [64, 48]},
 {"name": "traced", "pem": "../s/pem", "view": "sample:0", "method": "traced", "spp": 2}]}
EOF
"$pemref" golden generate "$work/gs" --out "$work/g1" --threads 1 >/dev/null
"$pemref" golden generate "$work/gs" --out "$work/g2" --threads 2 >/dev/null
cmp "$work/g1/golden.json" "$work/g2/golden.json" ||
  { echo "FAIL: PEM goldens differ between 1 and 2 threads"; exit 1; }
"$pemref" golden check "$work/gs" "$work/g1" --threads 2 >/dev/null ||
  { echo "FAIL: golden check of PEM goldens"; exit 1; }
# Step 3: the PEM paper's scene: a non-convex mirror teapot, whose local layer (its reflections
# of itself: knob, handle, spout) is inferred and drawn.
"$pemref" bake "$data/scenes/pem_mirror_teapot.gltf" --out "$work/t" --views circle:2:10 \
    --size 128x96 --spp 2 --res 32 --threads 2 --quiet
"$pemref" render "$work/t/pem" --view sample:1 --method pem --threads 2 --quiet -o "$work/t/pem.png"
"$pemref" report "$work/t" --threads 2 --reference-spp 2 --no-stability --no-packs --quiet

"$py" - "$work" <<'PY'
import json, os, sys
w = sys.argv[1]
def fail(msg):
    print("FAIL:", msg); sys.exit(1)
for m in ["hybrid", "pem", "static", "traced"]:
    if not os.path.getsize(f"{w}/a/{m}.png"): fail(f"{m}.png empty")
    st = json.load(open(f"{w}/a/{m}.json"))
    for k in ["vertex_rays", "triangles_after_tessellation", "ray_tracing_seconds",
              "tessellation_seconds", "texgen_seconds", "rasterization_seconds", "frame_seconds",
              "ray_tracer", "time_reduction", "ray_reduction", "vs_ray_tracer"]:
        if k not in st: fail(f"{m}.json lacks {k}")
    if m == "hybrid" and not (st["vertex_rays"] > 0 and st["ray_tracer"]["rays"] > st["vertex_rays"]):
        fail("hybrid: vertex rays not fewer than the ray tracer's")
if not os.path.getsize(f"{w}/a/single.exr"): fail("single-layer render missing")
view = open(f"{w}/a/view.txt", encoding="utf-8").read()
frames = view.count("--- frame ")
if frames != 6: fail(f"viewer printed {frames} frames, 6 expected")
if "\u2580" not in view and "\u2584" not in view: fail("viewer frames have no half blocks")
for status in ["hybrid az 0", "hybrid az 5", "pem az 5", "static-em az 5"]:
    if status not in view: fail(f"viewer status '{status}' missing")
r = json.load(open(f"{w}/a/report.json"))
res = r["results"]
methods = {x["method"] for x in res}
for m in ["static EM", "single-layer PEM", "layered PEM", "hybrid", "ray tracer"]:
    if m not in methods: fail(f"report lacks {m}")
if len(res) != 27: fail(f"{len(res)} results, 27 expected (3 positions x 9)")
above = {(x["method"], x["setting"]): x["float"]["rmse"] for x in res if x["position"] == "10° above"}
static = above[("static EM", "")]
for key in [("hybrid", "t=5"), ("hybrid", "t=3"), ("layered PEM", "")]:
    if not above[key] < static: fail(f"10° above: {key} RMSE {above[key]} not below static EM {static}")
budget = [b for b in r["budget"] if b["position"] == "on circle"]
if len(budget) != 2: fail(f"error budget: {len(budget)} groups on the circle, 2 expected")
for b in budget:
    stages = [st["stage"] for st in b["stages"]]
    if stages != ["two-term model", "layered EM", "best maps, exact lookups", "nonnegative maps", "maps' range", "map resolution", "texgen, filtering, solve", "hardware frame"]: fail(f"budget stages {stages}")
    if not all(st["psnr"] is not None and 5 < st["psnr"] <= 100 for st in b["stages"]): fail(f"budget PSNR {b}")
    # Against the two-term frame (the maps' target) from the layered EM on; the first stage is
    # that frame itself. A mirror group's two-term frame is its full tree: both columns agree.
    if b["stages"][0]["psnrVsTwoTerm"] is not None: fail(f"budget: two-term model vs itself {b}")
    if not all(st["psnrVsTwoTerm"] is not None and 5 < st["psnrVsTwoTerm"] < 100 for st in b["stages"][1:]): fail(f"budget PSNR vs two-term {b}")
    if "mirror_cup" in b["group"] and any(abs(st["psnr"] - st["psnrVsTwoTerm"]) > 1e-9 for st in b["stages"][1:]): fail(f"mirror cup: two-term frame is not its full tree {b}")
# Each bound can only cost: the unbounded fit through the same exact lookups is the best, and the
# mirror cup reflects radiance above 2 (the lamps, the lit floor through F < 1), which maps held in
# [0, 2] (the default radiance scale) must show.
cup = {st["stage"]: st["psnr"] for b in budget if "mirror_cup" in b["group"] for st in b["stages"]}
if not cup["maps' range"] < cup["nonnegative maps"] <= cup["best maps, exact lookups"]: fail(f"mirror cup: bounds {cup}")
if not any(b["position"] == "10° above" for b in r["budget"]): fail("no off-sample budget")
if "<rect" not in open(f"{w}/a/budget.svg").read(): fail("budget.svg has no bars")
svg = open(f"{w}/a/report.svg").read()
if svg.count('class="marker"') != 27: fail("report.svg: one marker per result expected")
packs = r["packs"]
if [p["setting"] for p in packs][:2] != ["lossless", "--max-error 4"]: fail("report: pack settings")
if any(f["delta"] != 0 for f in packs[0]["frames"]): fail("report: the lossless pack changes a frame")
if not all(p["vsExr"] > 1 for p in packs): fail("report: a pack larger than the EXR maps")
if "<polyline" not in open(f"{w}/a/packs.svg").read(): fail("packs.svg has no curve")
s = json.load(open(f"{w}/s/report.json"))
decisions = " | ".join(x["decision"] for x in s["leftOut"])
if "refraction (T) term" not in decisions: fail("mirror sphere: refraction term not left out: " + decisions)
if "PEM local layer" not in decisions: fail("mirror sphere: local layer not left out: " + decisions)
mx = json.load(open(f"{w}/a/pemmax/infer.json"))
if json.load(open(f"{w}/a/pemmax/manifest.json"))["max_res"] != 256: fail("--max-res not in the manifest")
for m in mx["maps"]:
    if m["res"] not in (64, 128, 256): fail(f"--max-res: {m['name']} at face size {m['res']}")
    if abs(sum(m["levels_accessed"]) - 1) > 1e-9: fail(f"--max-res: levels accessed {m['levels_accessed']}")
if not all(m["res"] > 64 for m in mx["maps"] if m["name"].startswith("layer_")): fail("--max-res: a layer map did not grow")
t = json.load(open(f"{w}/t/pem/infer.json"))
local = [m for m in t["maps"] if m["name"] == "pem_local"]
if len(local) != 2: fail(f"PEM teapot: {len(local)} local maps, 2 expected (one per sample)")
if any("local" in l["what"] for l in t["left_out"]): fail("PEM teapot: local layer left out")
if not os.path.getsize(f"{w}/t/pem.png"): fail("PEM teapot: no PEM frame")
tr = json.load(open(f"{w}/t/report.json"))
if len(tr["results"]) != 27: fail("PEM teapot: report incomplete")
# Layered PEM ahead of single-layer PEM everywhere, 10° above the sampled circle too (with the
# vertex ellipsoid as local shell the local layer's parallax made it 0.5 dB worse there).
for pos in ["on circle", "between samples", "10° above"]:
    err = {x["method"]: x["float"]["rmse"] for x in tr["results"] if x["position"] == pos}
    if not err["layered PEM"] < err["single-layer PEM"]: fail(f"PEM teapot, {pos}: layered {err}")
print("PASS: 4 methods rendered with statistics, 6 viewer frames, 27 report results; "
      f"10° above RMSE static {static:.4f} > layered PEM {above[('layered PEM', '')]:.4f}, "
      f"hybrid t=5 {above[('hybrid', 't=5')]:.4f}; mirror sphere left out: {decisions}")
PY
