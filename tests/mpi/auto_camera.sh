#!/usr/bin/env bash
# camera.position: auto frames the whole scene: a wide flat particle pool (procedural
# layers: 3 layers of a wide disc) and a long thin volume (200 x 16 x 16 samples, every sample
# half opaque, so the image shows the whole box), in square, wide and tall images on 2 ranks: the
# outermost rows and columns of every frame are background. The old distance (2 x the largest
# extent, still camera.orbit.radius: auto) crops the tall frame of the volume, so this test can fail.
# Usage: auto_camera.sh SORTLAST
source "$(dirname "$0")/lib.sh" "$1"
here=$(dirname "$0")
bg=(--set 'image.background=[0.2,0.3,0.4]')
border() {  # border IMAGE: pixels of the outermost rows and columns that are not background
  python3 "$here/png_border.py" "$1" 51 77 102 | tee "$WORK/border.txt" >&2
  sed 's/border_pixels_not_background=\([0-9]*\).*/\1/' "$WORK/border.txt"
}
check() {  # check NAME ARGS...: rendered with the automatic camera, nothing on the border
  local name=$1 n; shift
  run_np 2 render -q -o "$WORK/$name.png" "${bg[@]}" "$@" || fail "$name: render failed"
  n=$(border "$WORK/$name.png")
  [ "$n" = 0 ] || fail "$name: $n border pixels are not background (cropped)"
  grep -q "pixels_not_background=[1-9]" "$WORK/border.txt" || fail "$name: nothing drawn"
  echo "ok: $name: $(cat "$WORK/border.txt")"
}
pool=(--set volume.procedural=none --set particles.procedural=layers)
long=(--set 'volume.dims=[200,16,16]' --set 'transfer.points=[[0,1,1,1,0.5],[1,1,1,1,0.5]]')
check pool_square "${pool[@]}" --set image.width=96 --set image.height=96
check pool_wide "${pool[@]}" --set image.width=128 --set image.height=64
check pool_tall "${pool[@]}" --set image.width=64 --set image.height=128
check long_square "${long[@]}" --set image.width=96 --set image.height=96
check long_tall "${long[@]}" --set image.width=72 --set image.height=128
# The old automatic distance, 2 x the largest extent (199) along (0.55, 0.35, 1): it crops.
old=$(python3 -c "import math; d=[0.55,0.35,1.0]; n=math.hypot(*d); print(','.join(str(2*199*x/n) for x in d))")
run_np 2 render -q -o "$WORK/old.png" "${bg[@]}" "${long[@]}" --set image.width=72 --set image.height=128 \
  --set "camera.position=[$old]" || fail "old camera: render failed"
n=$(border "$WORK/old.png")
[ "$n" -gt 0 ] || fail "the old distance did not crop the tall frame: the test would not notice cropping"
echo "ok: the old distance (2 x largest extent) leaves $n border pixels drawn"
echo "auto camera passed"
