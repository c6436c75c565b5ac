#!/usr/bin/env bash
# The paper's Fig. 10 on real data (docs/fig10.md): Debian's MRI template ch2better.nii.gz
# (mricron-data) subsampled onto BCC and onto a coarser Cartesian grid at 3%, 10% and 25% of its
# samples, reconstructed with m12, m8, m7 (BCC) and tricubic, cart7 (Cartesian), each after its
# Q^II, and compared with the original at every voxel of one common box (the same points for
# every filter). Prints one markdown table row per case, and renders each reconstruction's
# isosurface at the data-derived iso (boxrecon render's default) into WORK_DIR/render-*.png from
# two cameras: the cut-away view and the left side. Deterministic.
# Usage: scripts/fig10.sh [BUILD_DIR [WORK_DIR]]
set -euo pipefail
cd "$(dirname "$0")/.."
boxrecon="${1:-build}/apps/boxrecon"
work="${2:-${1:-build}/fig10}"
input=/usr/share/mricron/templates/ch2better.nii.gz
box=(--min -60 -92 -55 --max 60 62 73)  # inside every filter's region at 3%
mkdir -p "$work"
echo "| fraction | lattice | samples kept | filter | RMS | PSNR (dB) | RMS, voxels > 20 | PSNR, voxels > 20 (dB) |"
echo "|---|---|---|---|---|---|---|---|"
for fraction in 0.03 0.10 0.25; do
  for lattice in bcc cartesian; do
    volume="$work/$lattice-$fraction.nrrd"
    kept=$("$boxrecon" subsample --volume "$input" --lattice "$lattice" --fraction "$fraction" \
             --boundary strict -o "$volume" | sed -E 's/^kept ([0-9]+) of ([0-9]+) samples: fraction [^=]*= ([0-9.]+).*/\1 (\3)/')
    if [ "$lattice" = bcc ]; then filters="m12 m8 m7"; else filters="tricubic cart7"; fi
    for filter in $filters; do
      "$boxrecon" compare --reference "$input" --volume "$volume" --filter "$filter" \
        --prefilter q2 --mask-above 20 "${box[@]}" --json > "$work/$lattice-$fraction-$filter.json"
      /usr/bin/python3 - "$work/$lattice-$fraction-$filter.json" "$fraction" "$lattice" "$kept" "$filter" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
r, m = j["region"], j["mask"]
print(f"| {sys.argv[2]} | {sys.argv[3]} | {sys.argv[4]} | {sys.argv[5]} | {r['rms']:.4f} | "
      f"{r['psnr_db']:.3f} | {m['rms']:.4f} | {m['psnr_db']:.3f} |")
PY
    done
  done
done
# Renders (docs/fig10.md, "Renders"): 240 x 240, Q^II, iso from the data.
for fraction in 0.03 0.10 0.25; do
  for filter in m12 m8 m7 tricubic cart7; do
    case "$filter" in tricubic|cart7) lattice=cartesian ;; *) lattice=bcc ;; esac
    common=(--volume "$work/$lattice-$fraction.nrrd" --filter "$filter" --prefilter q2
            --width 240 --height 240 --quiet)
    "$boxrecon" render "${common[@]}" --cutaway --distance 1.1 \
      -o "$work/render-cut-$fraction-$filter.png" > /dev/null
    "$boxrecon" render "${common[@]}" --azimuth 180 --elevation 20 --distance 1.1 \
      -o "$work/render-left-$fraction-$filter.png" > /dev/null
  done
done
