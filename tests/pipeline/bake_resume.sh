#!/usr/bin/env bash
# bake_resume.sh PEMREF SCENE — a bake killed with SIGKILL at three random moments and started
# again each time ends with the same PEM bytes (.exr, .png) as an uninterrupted bake; a bake
# resumed with other options (which would mix two settings in one PEM) is refused with one line
# naming bake.json and the option, and changes nothing.
set -euo pipefail
pemref=$1
scene=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
args=(--views circle:3:10 --size 128x96 --spp 1 --res 32 --quiet)

# Step 1: the uninterrupted bake, timed.
start=$(date +%s%N)
"$pemref" bake "$scene" --out "$work/full" "${args[@]}"
full_ms=$((($(date +%s%N) - start) / 1000000))
echo "uninterrupted bake: ${full_ms} ms"

# Step 2: three kills at random moments of one bake, a restart after each. Each kill comes
# 5-35% of the uninterrupted time after its start (a restart redoes lost work and pays its own
# start-up, so three such kills land before the end); a sequence where the bake finished before
# a kill is started over (at most 5 times).
RANDOM=${PEM_SEED:-7}
interrupted=0
for attempt in 1 2 3 4 5; do
  rm -rf "$work/resumed"
  interrupted=0
  for k in 1 2 3; do
    delay_ms=$((full_ms * (5 + RANDOM % 30) / 100))
    "$pemref" bake "$scene" --out "$work/resumed" "${args[@]}" &
    pid=$!
    sleep "$(printf '%d.%03d' $((delay_ms / 1000)) $((delay_ms % 1000)))"
    kill -9 "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    if [ -f "$work/resumed/pem/manifest.json" ]; then
      echo "attempt $attempt, kill $k after ${delay_ms} ms: the bake had already finished"
      break
    fi
    interrupted=$((interrupted + 1))
    done_samples=$(find "$work/resumed/pem" -name sample.json 2>/dev/null | wc -l)
    echo "attempt $attempt, kill $k after ${delay_ms} ms: $done_samples sample(s) done"
  done
  [ "$interrupted" -eq 3 ] && break
done
"$pemref" bake "$scene" --out "$work/resumed" "${args[@]}"

# Step 3: same bytes, no temporaries left.
(cd "$work/full" && find . \( -name '*.exr' -o -name '*.png' \) | sort | xargs md5sum) > "$work/full.md5"
(cd "$work/resumed" && md5sum --quiet -c "$work/full.md5")
count=$(wc -l < "$work/full.md5")
extra=$(cd "$work/resumed" && find . \( -name '*.exr' -o -name '*.png' \) | wc -l)
[ "$count" -eq "$extra" ] || { echo "FAIL: $extra files after resuming, $count expected"; exit 1; }
if find "$work/resumed" -name '*.tmp*' | grep -q .; then echo "FAIL: temporaries left"; exit 1; fi
[ "$interrupted" -eq 3 ] || { echo "FAIL: only $interrupted kill(s) interrupted the bake"; exit 1; }

# Step 4: resumed with other options: refused, nothing changed.
for other in "--res 64" "--parameterization tennis" "--size 64x48" "--views circle:2:10" \
    "--map-format rgba32f" "--t 2"; do
  opts=()  # args with `other` in place of its option
  for o in "--views circle:3:10" "--size 128x96" "--spp 1" "--res 32" "--quiet" "$other"; do
    # shellcheck disable=SC2206  # an option and its value
    [ "$o" != "$other" ] && [ "${o%% *}" = "${other%% *}" ] || opts+=($o)
  done
  if err=$("$pemref" bake "$scene" --out "$work/resumed" "${opts[@]}" 2>&1); then
    echo "FAIL: a bake resumed with $other was accepted"; exit 1
  fi
  [ "$(wc -l <<<"$err")" -eq 1 ] && grep -q "bake.json: this bake was started with ${other%% *}" <<<"$err" ||
    { echo "FAIL: resumed with $other: expected one line naming bake.json and the option, got: $err"; exit 1; }
done
(cd "$work/resumed" && md5sum --quiet -c "$work/full.md5")
"$pemref" bake "$scene" --out "$work/resumed" "${args[@]}" --threads 2  # threads: not a setting
echo "PASS: $count files byte-identical after $interrupted interrupted run(s); other options refused"
