#!/usr/bin/env bash
# docs/fig10.md's interpolation table: the subsamples of scripts/fig10.sh (made here if missing,
# with the same command) reconstructed with `--prefilter interp` (m12, m8, m7 on BCC, tricubic on
# the Cartesian lattice), beside scipy's cubic B-spline interpolation of the same Cartesian
# subsample (scripts/fig10_scipy.py), all compared with the template at the voxels of
# scripts/fig10.sh's box. Prints one markdown table row per case. Deterministic.
# Usage: scripts/fig10_interp.sh [BUILD_DIR [WORK_DIR]]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
boxrecon="$build/apps/boxrecon"
work="${2:-$build/fig10}"
input=/usr/share/mricron/templates/ch2better.nii.gz
box=(-60 -92 -55 60 62 73)  # scripts/fig10.sh's box
mkdir -p "$work"
echo "| fraction | lattice | filter | RMS | PSNR (dB) | RMS, voxels > 20 | PSNR, voxels > 20 (dB) |"
echo "|---|---|---|---|---|---|---|"
for fraction in 0.03 0.10 0.25; do
  for lattice in bcc cartesian; do
    volume="$work/$lattice-$fraction.nrrd"
    [ -f "$volume" ] || "$boxrecon" subsample --volume "$input" --lattice "$lattice" \
                          --fraction "$fraction" --boundary strict -o "$volume" > /dev/null
    if [ "$lattice" = bcc ]; then filters="m12 m8 m7"; else filters="tricubic"; fi
    for filter in $filters; do
      "$boxrecon" compare --reference "$input" --volume "$volume" --filter "$filter" \
        --prefilter interp --mask-above 20 --min "${box[@]:0:3}" --max "${box[@]:3:3}" --json \
        > "$work/interp-$lattice-$fraction-$filter.json" 2> "$work/interp-$lattice-$fraction-$filter.log"
      /usr/bin/python3 - "$work/interp-$lattice-$fraction-$filter.json" "$fraction" "$lattice" \
        "$filter interp" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
r, m = j["region"], j["mask"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {r['rms']:.4f} | {r['psnr_db']:.3f} | "
      f"{m['rms']:.4f} | {m['psnr_db']:.3f} |")
PY
    done
    if [ "$lattice" = cartesian ]; then
      read -r rms psnr mrms mpsnr _ < <(PYTHONPATH="$build/python" /usr/bin/python3 \
        scripts/fig10_scipy.py "$input" "$volume" "${box[@]}")
      echo "| $fraction | cartesian | scipy cubic (map_coordinates, order 3) | $rms | $psnr | $mrms | $mpsnr |"
    fi
  done
done
