#!/usr/bin/env bash
# faults.sh PEMREF DATA_DIR — faults that lose nothing, for every command that writes:
#  - a read-only output directory (pemref run as an unprivileged user on a directory it cannot
#    write) and a full disk (a file-size limit, SIGXFSZ ignored so writes fail with EFBIG):
#    one error line naming a file, a non-zero exit, no file and no temporary left behind;
#  - two bakes into one directory at once: the second refuses with a clear message and the
#    first finishes with the same bytes as a bake alone.
set -u
pemref=$1 data=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/pem_faults.XXXXXX")
chmod 755 "$work"
trap 'rm -rf "$work"' EXIT
failed=0 passed=0
fail() { echo "FAIL: $*"; failed=$((failed + 1)); }
scene="$data/scenes/mirror_sphere.gltf"
small=(--views circle:2:10 --size 64x48 --spp 1)

# A baked directory and a case file to read from (written normally).
"$pemref" bake "$scene" --out "$work/ok" "${small[@]}" --res 8 --quiet || { echo "FAIL: setup bake"; exit 1; }
cat > "$work/case.json" <<'JSON'
{"width": 16, "height": 16, "clear": [10, 20, 30, 255], "passes": []}
JSON
"$pemref" pack "$work/ok/pem" -o "$work/ok.pempack" --quiet || { echo "FAIL: setup pack"; exit 1; }
chmod -R a+rX "$work/ok" "$work/case.json" "$work/ok.pempack"

# The commands that write, each into OUT (a directory that must stay as it was).
commands() {
  local out=$1
  echo "trace $scene --out $out/t ${small[*]} --quiet"
  echo "infer $work/ok/trace --out $out/p --res 8 --quiet"
  echo "bake $scene --out $out/b ${small[*]} --res 8 --quiet"
  echo "render $work/ok/pem --view sample:0 -o $out/f.png --quiet"
  echo "render $work/ok/pem --view sample:0 -o $out/f.exr --quiet"
  echo "raster $work/case.json -o $out/c.png --matrix $out/c.mtx"
  echo "stability --json $out/s.json"
  echo "pack $work/ok/pem -o $out/p.pempack --quiet"
  echo "unpack $work/ok.pempack -o $out/u"
  echo "study $scene --out $out/st --sizes 2 --layouts cube,sphere --size 32x24 --reference-spp 1 --quiet"
}

# Runs one command (as `who`: root or nobody) with an optional file-size limit in KiB; checks
# the exit, the single error line and that OUT holds nothing new.
check() {
  local label=$1 who=$2 limit=$3 out=$4 cmd=$5 before after err code
  before=$(find "$out" | sort)
  if [ "$who" = nobody ]; then
    err=$(setpriv --reuid=65534 --regid=65534 --clear-groups "$pemref" $cmd 2>&1 >/dev/null)
  else
    err=$(trap '' XFSZ; ulimit -f "$limit"; "$pemref" $cmd 2>&1 >/dev/null)
  fi
  code=$?
  after=$(find "$out" | sort)
  local lines
  lines=$(printf '%s\n' "$err" | grep -c .)
  if [ "$code" -eq 0 ] || [ "$lines" -ne 1 ] || [ "$before" != "$after" ] ||
     ! grep -q "^pemref: /" <<<"$err"; then
    fail "$label: pemref ${cmd%% *}: exit $code, $lines line(s), files: $(comm -13 <(echo "$before") <(echo "$after") | tr '\n' ' ') -- $err"
  else
    passed=$((passed + 1))
  fi
}

# Step 1: a read-only output directory (owned by root, mode 755: nobody cannot write it).
mkdir -p "$work/ro" && chmod 755 "$work/ro"
while read -r cmd; do check "read-only" nobody 0 "$work/ro" "$cmd"; done < <(commands "$work/ro")

# Step 2: a full disk: a 1 KiB file-size limit (every output is larger), in a fresh directory
# per command so that what a command may create (its directory, the lock) can be told apart.
i=0
while read -r cmd; do
  i=$((i + 1))
  mkdir -p "$work/full$i/x"
  out="$work/full$i/x"
  cmd=$(commands "$out" | sed -n "${i}p")
  # Directories and the lock file may be created; no file with data may remain.
  err=$(trap '' XFSZ; ulimit -f 1; "$pemref" $cmd 2>&1 >/dev/null); code=$?
  left=$(find "$out" -type f ! -name .pemref.lock -size +0 | head -3)
  lines=$(printf '%s\n' "$err" | grep -c .)
  if [ "$code" -ne 0 ] && [ "$lines" -eq 1 ] && [ -z "$left" ]; then
    passed=$((passed + 1))
  else
    fail "disk full: pemref ${cmd%% *}: exit $code, $lines line(s), left: $left -- $err"
  fi
done < <(commands "$work/unused")

# Step 3: two bakes at once into one directory.
args=(--views circle:3:10 --size 160x120 --spp 2 --res 16 --quiet)
"$pemref" bake "$data/scenes/hybrid_glass_teapot.gltf" --out "$work/alone" "${args[@]}"
"$pemref" bake "$data/scenes/hybrid_glass_teapot.gltf" --out "$work/twice" "${args[@]}" &
first=$!
for _ in $(seq 100); do [ -s "$work/twice/.pemref.lock" ] && break; sleep 0.05; done
err=$("$pemref" bake "$data/scenes/hybrid_glass_teapot.gltf" --out "$work/twice" "${args[@]}" 2>&1)
code=$?
wait "$first" || fail "the first bake failed"
if [ "$code" -eq 0 ] || ! grep -q "another pemref job is writing this directory" <<<"$err"; then
  fail "second bake into the same directory: exit $code: $err"
else
  passed=$((passed + 1))
fi
(cd "$work/alone" && find . \( -name '*.exr' -o -name '*.png' \) | sort | xargs md5sum) > "$work/alone.md5"
(cd "$work/twice" && md5sum --quiet -c "$work/alone.md5") || fail "the first bake's bytes changed"

echo "faults: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
