#!/usr/bin/env bash
# Every speed figure of issue 17 in one command, each pair measured in one run (the scripts it
# calls alternate the two sides round by round): raster vs llvmpipe at 2 and 1 threads on the
# benchmark frame and the small-triangle frame, and the softpipe profile vs softpipe
# (raster_bench.sh), inference (infer_bench.sh: building A vs a
# forward render, an LSMR iteration vs streaming A and A^T, time to pemref's objective vs scipy's
# lsmr),
# hybrid frames and the viewer (render_bench.sh, on the demo's PEMs: made first when missing).
# Prints each script's report, the CPU share stolen by the hypervisor over the whole run, and one
# verdict line per goal. Run it on an idle machine (`uptime` is printed first).
#   usage: bench/all.sh [build-dir] [rounds]      (output also in bench-all.log)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}; rounds=${2:-5}
log=bench-all.log
steal() { awk '/^cpu /{print $9, $2+$3+$4+$5+$6+$7+$8+$9}' /proc/stat; }
st0=$(steal)
{
  echo "uptime:$(uptime)"
  echo "== raster, llvmpipe profile, 2 threads, and softpipe profile"
  THREADS=2 bash bench/raster_bench.sh "$build" "$rounds"
  echo "== raster, llvmpipe profile, 1 thread"
  THREADS=1 PAIRS=llvmpipe bash bench/raster_bench.sh "$build" "$rounds"
  echo "== inference"
  bash bench/infer_bench.sh "$build" 3
  echo "== hybrid frames and the viewer"
  [ -f out/demo/pem/manifest.json ] || "$build/bin/pemref" demo --out out/demo --threads "$(nproc)"
  bash bench/render_bench.sh out/demo/pem 3 "$build"
} 2>&1 | tee "$log"
st1=$(steal)
/usr/bin/python3 - "$log" "$st0" "$st1" <<'PY'
import re, sys
text = open(sys.argv[1]).read()
s0, t0, s1, t1 = map(float, sys.argv[2].split() + sys.argv[3].split())
def first(pattern, after=""):
    start = text.find(after) if after else 0
    m = re.search(pattern, text[max(start, 0):])
    return float(m.group(1)) if m else None
figures = [
    ("raster vs llvmpipe, 2 threads", first(r"ratio pemref/llvmpipe: ([0-9.]+)"), 1.0, "<="),
    ("raster vs llvmpipe, 1 thread",
     first(r"ratio pemref/llvmpipe: ([0-9.]+)", "== raster, llvmpipe profile, 1 thread"), 1.0, "<="),
    ("raster vs llvmpipe, small triangles, 2 thr",
     first(r"ratio pemref/llvmpipe \(lens\): ([0-9.]+)"), 1.0, "<="),
    ("raster vs llvmpipe, small triangles, 1 thr",
     first(r"ratio pemref/llvmpipe \(lens\): ([0-9.]+)", "== raster, llvmpipe profile, 1 thread"),
     1.0, "<="),
    ("softpipe profile vs softpipe", first(r"ratio pemref/softpipe: ([0-9.]+)"), 1.0, "<="),
    ("build A / forward render", first(r"\(a\).*ratio ([0-9.]+)"), 2.0, "<="),
    ("LSMR iteration / streaming A and A^T", first(r"\(b\).*ratio ([0-9.]+)"), 1.5, "<="),
    ("time to objective, pemref / scipy", first(r"ratio pemref/scipy ([0-9.]+)"), 0.5, "<="),
    ("hybrid frame t=5, ms (goal 100)", first(r"hybrid t=5: frame median ([0-9.]+)"), 200.0, "<="),
]
print(f"== verdicts (CPU stolen by the hypervisor over the whole run: "
      f"{100.0 * (s1 - s0) / max(1.0, t1 - t0):.1f}%)")
for name, value, goal, op in figures:
    if value is None:
        print(f"{name:44s}  not measured")
        continue
    met = value <= goal
    print(f"{name:44s} {value:9.2f}  goal {op} {goal:g}: {'met' if met else 'NOT met'}")
PY
