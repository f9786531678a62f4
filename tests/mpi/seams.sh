#!/usr/bin/env bash
# Brick faces leave no seam: cutting the volume into 2^3 or 3^3 bricks gives the 1-brick image up
# to the RGBA8 rounding of intermediate images (2/255), except for at most 0.1 % of pixels on the
# volume's silhouette, where a slice polygon's outer edge is split at brick corners and pixel
# centres lying on it may fall either way. A seam would break a whole line of pixels.
# Usage: seams.sh SORTLAST SCENE
source "$(dirname "$0")/lib.sh" "$1"
scene=$2
for d in 1 2 3; do
  run_np 2 render "$scene" -q -o "$WORK/d$d.png" --set bricks.per_axis=$d || fail "render d=$d"
done
for d in 2 3; do
  "$SORTLAST" compare "$WORK/d1.png" "$WORK/d$d.png" --max-diff 2 --allow-pixels 20 --min-psnr 50 \
    --diff "$WORK/diff$d.png" || fail "d=$d differs from d=1"
done
echo "no seams"
