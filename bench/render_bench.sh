#!/usr/bin/env bash
# Run-time rendering benchmark (issue 5), default scene (a):
#  - 640x480 hybrid frames at t = 3 and t = 5 (subpixels of the 3x3 grid) vs full ray tracing of
#    the same frame at 3x3 with the same Embree code and the same two-term path model: frame time,
#    time reduction and ray reduction factors (the hybrid paper: 25-46x and 6-11x);
#  - the terminal viewer's frames per second at 160x90 cells in hybrid mode (scripted, every frame
#    a new pose, the half-block picture written to /dev/null): steady (the maps loaded and
#    prepared, as the PEM paper's FPS assumes textures resident) and over a wide sweep.
# The view lies between two viewpoint samples (both samples' maps drawn and blended). Each round
# runs every configuration once (--repeat 5: the median of 5 warm frames); rounds alternate the
# configurations so a busy neighbour slows all of them. Prints medians over rounds and their
# spread (min..max).   usage: bench/render_bench.sh [pem-dir] [rounds] [build-dir]
# pem-dir: a `pemref bake`/`pemref demo` output of scene (a) (default: out/demo/pem, made by the
# README's first command).
set -euo pipefail
cd "$(dirname "$0")/.."
pem=${1:-out/demo/pem}; rounds=${2:-5}; build=${3:-build}; threads=${THREADS:-2}
bin="$build/bin/pemref"
[ -f "$pem/manifest.json" ] || { echo "render_bench: $pem: no PEMs (run the README's first command)" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
view=orbit:5:0:1
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs); load:$(uptime | sed 's/.*average://')"
echo "scene: $(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['scene'])" "$pem/manifest.json"); view $view; $threads threads"

steal() { awk '/^cpu /{print $9, $2+$3+$4+$5+$6+$7+$8+$9}' /proc/stat; }
st0=$(steal)
frames=40
keys=$(printf 'l%.0s' $(seq 1 $((frames - 1))))
# Steady state: back and forth over the sample arc (every frame a new pose), 121 frames minus the
# same first 41 (both pay for loading and preparing the maps on first use).
arc=$(python3 -c "print(('llllhhhhkkjj' * 11)[:120])")
for ((r = 0; r < rounds; ++r)); do
  for t in 3 5; do
    "$bin" render "$pem" --view $view --size 640x480 --t $t --threads "$threads" --repeat 5 \
      --quiet -o "$tmp/h.png" --stats "$tmp/hybrid_t${t}_$r.json"
  done
  "$bin" render "$pem" --view $view --size 640x480 --method traced --spp 3 --threads "$threads" \
    --repeat 3 --quiet -o "$tmp/rt.png" --stats "$tmp/traced_$r.json"
  # Viewer: N frames minus 1 frame (start-up: loading, maps prepared on first use).
  s0=$(date +%s.%N)
  "$bin" view "$pem" --cols 160 --rows 91 --frames 1 --threads "$threads" >/dev/null
  s1=$(date +%s.%N)
  "$bin" view "$pem" --cols 160 --rows 91 --keys "$keys" --frames $frames --threads "$threads" >/dev/null
  s2=$(date +%s.%N)
  python3 -c "import sys; a,b,c,n=map(float,sys.argv[1:]); print((n-1)/((c-b)-(b-a)))" \
    "$s0" "$s1" "$s2" "$frames" > "$tmp/fps_$r.txt"
  s0=$(date +%s.%N)
  "$bin" view "$pem" --cols 160 --rows 91 --keys "${arc:0:40}" --frames 41 --threads "$threads" >/dev/null
  s1=$(date +%s.%N)
  "$bin" view "$pem" --cols 160 --rows 91 --keys "$arc" --frames 121 --threads "$threads" >/dev/null
  s2=$(date +%s.%N)
  python3 -c "import sys; a,b,c=map(float,sys.argv[1:]); print(80/((c-b)-(b-a)))" \
    "$s0" "$s1" "$s2" > "$tmp/steady_$r.txt"
done

st1=$(steal)
python3 - "$tmp" "$rounds" "$st0" "$st1" <<'PY'
import json, statistics, sys
tmp, rounds = sys.argv[1], int(sys.argv[2])
s0, t0 = map(int, sys.argv[3].split()); s1, t1 = map(int, sys.argv[4].split())
print(f"CPU time stolen by the hypervisor during the runs: {100.0 * (s1 - s0) / max(1, t1 - t0):.1f}%")
def load(name): return [json.load(open(f"{tmp}/{name}_{r}.json")) for r in range(rounds)]
def fmt(v, unit="", digits=1):
    return f"median {statistics.median(v):.{digits}f}{unit} (spread {min(v):.{digits}f}..{max(v):.{digits}f})"
traced = load("traced")
rt = [j["frame_seconds"] * 1e3 for j in traced]
rt_rays = traced[0]["ray_tracer"]["rays"] if "ray_tracer" in traced[0] else None
print(f"ray tracer 3x3: frame {fmt(rt, ' ms', 0)}")
for t in (3, 5):
    h = load(f"hybrid_t{t}")
    frame = [j["frame_seconds"] * 1e3 for j in h]
    lens = [j["lens_seconds"] * 1e3 for j in h]
    # Reductions against the ray tracer of the same round (same frame, same code).
    tr = [traced[r]["frame_seconds"] / h[r]["frame_seconds"] for r in range(rounds)]
    trl = [traced[r]["frame_seconds"] / h[r]["lens_seconds"] for r in range(rounds)]
    j = h[0]
    rays_rt = j["ray_tracer"]["rays"]
    print(f"hybrid t={t}: frame {fmt(frame, ' ms')}; lens {fmt(lens, ' ms')}")
    print(f"  stages (round medians' median, ms): rays {statistics.median(x['ray_tracing_seconds'] for x in h)*1e3:.1f}, "
          f"tessellation {statistics.median(x['tessellation_seconds'] for x in h)*1e3:.1f}, "
          f"texgen {statistics.median(x['texgen_seconds'] for x in h)*1e3:.1f}, "
          f"raster {statistics.median(x['rasterization_seconds'] for x in h)*1e3:.1f}, "
          f"background {statistics.median(x['background_seconds'] for x in h)*1e3:.1f}")
    print(f"  {j['vertex_rays']} vertex rays + {j['background_rays']} background rays, "
          f"{j['triangles_after_tessellation']} triangles; ray tracer {rays_rt} rays")
    print(f"  time reduction: whole frame {fmt(tr, 'x')}, lens objects {fmt(trl, 'x')}")
    print(f"  ray reduction: whole frame {rays_rt / (j['vertex_rays'] + j['background_rays']):.1f}x, "
          f"lens objects {rays_rt / j['vertex_rays']:.1f}x   (paper: time 25-46x, rays 6-11x)")
    print(f"  lens PSNR vs the 3x3 ray tracer: {j['vs_ray_tracer']['lens_psnr_db']:.2f} dB")
fps = [float(open(f"{tmp}/fps_{r}.txt").read()) for r in range(rounds)]
steady = [float(open(f"{tmp}/steady_{r}.txt").read()) for r in range(rounds)]
print(f"viewer 160x90 cells, hybrid (goal >= 20 FPS):")
print(f"  steady, back and forth over the sample arc: {fmt(steady, ' FPS')}")
print(f"  sweep of 195 degrees, maps loaded on first use: {fmt(fps, ' FPS')}")
PY
