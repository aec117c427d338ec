#!/usr/bin/env bash
# pack_rd.sh — the rate–distortion table of packed PEMs (issue 18): for each pack setting, the
# pack's bytes per viewpoint sample, its ratio against the directory's float EXR and 8-bit PNG
# maps, and the change of the hybrid frame's lens PSNR (against the same frame ray-traced at
# 3×3, `pemref render --stats`) on the three samples, between two samples and 10° above; the
# seconds to pack and to unpack (decode every map, write the EXR and PNG files).
#   bash bench/pack_rd.sh [PEM_DIR=out/demo/pem] [SIZE=320x240]
set -euo pipefail
cd "$(dirname "$0")/.."
pem=${1:-out/demo/pem}
size=${2:-320x240}
bin=build/bin/pemref
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
views=(sample:0 sample:1 sample:2 orbit:5:0:1 orbit:0:10:1)

# Lens PSNR of each view, one line of numbers.
psnrs() {
  local src=$1 out=""
  for v in "${views[@]}"; do
    "$bin" render "$src" --view "$v" --size "$size" --threads 2 -o "$work/f.png" \
      --stats "$work/s.json" --quiet
    out+=" $(/usr/bin/python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['vs_ray_tracer']['lens_psnr_db'])" "$work/s.json")"
  done
  echo "$out"
}

base=$(psnrs "$pem")
echo "| setting | bytes/sample | vs EXR | vs PNG | max texel error | ΔPSNR on samples | between | above | pack s | open s |"
echo "|---|---|---|---|---|---|---|---|---|---|"
settings=("--codec zstd" "--codec xz" "--ratio 1" "--max-error 2" "--max-error 4" "--max-error 8"
          "--max-error 31 --ratio 16" "--max-error 31 --ratio 24" "--max-error 31 --ratio 32"
          "--max-error 31 --ratio 48" "--max-error 31 --ratio 48 --wavelet 53"
          "--max-error 31 --ratio 56" "--max-error 31 --ratio 64" "--max-error 31 --ratio 96")
for s in "${settings[@]}"; do
  # shellcheck disable=SC2086
  t0=$(date +%s.%N)
  line=$("$bin" pack "$pem" -o "$work/p.pempack" $s)
  t1=$(date +%s.%N)
  "$bin" unpack "$work/p.pempack" -o "$work/u"
  t2=$(date +%s.%N)
  rm -rf "$work/u"
  now=$(psnrs "$work/p.pempack")
  /usr/bin/python3 - "$s" "$line" "$base" "$now" "$t0" "$t1" "$t2" <<'PY'
import re, sys
setting, line, base, now = sys.argv[1:5]
t0, t1, t2 = (float(x) for x in sys.argv[5:8])
b = [float(x) for x in base.split()]
n = [float(x) for x in now.split()]
d = [y - x for x, y in zip(b, n)]
per = re.search(r"\(([0-9]+) per sample\)", line).group(1)
exr = re.search(r"([0-9.]+):1 against the EXR", line).group(1)
png = re.search(r"([0-9.]+):1 against the PNG", line).group(1)
err = re.search(r"max error ([0-9]+)", line).group(1)
on = sum(d[:3]) / 3
print(f"| `{setting}` | {per} | {exr}:1 | {png}:1 | {err} | {on:+.2f} dB (worst {min(d[:3]):+.2f}) | {d[3]:+.2f} dB | {d[4]:+.2f} dB | {t1 - t0:.1f} | {t2 - t1:.1f} |")
PY
done
