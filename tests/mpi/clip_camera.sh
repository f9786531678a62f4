#!/usr/bin/env bash
# The orthographic camera, an eye inside the volume, and clipping (clip.planes, clip.box) in both
# GL volume renderers, on Marschner-Lobb (41^3, 3^3 bricks: the clip plane crosses brick faces).
# Usage: clip_camera.sh SORTLAST DATA_DIR MODE
#   reference  ray caster and slicing at 0.25 voxel (ERT off) against the CPU reference, which
#              takes the same rays (Camera::pixelRay) and the same clip (common/clip.h): an
#              orthographic view, an eye inside the volume (in the middle brick), and clip planes
#              with a box, each within a PSNR bound
#   ranks      the clipped scene (a plane slanted across brick faces, and a box) has no seam: 1 brick
#              and 3^3 bricks within the 2/255 of the RGBA8 brick images; 1-4 ranks, binary-swap
#              and radix-k within 1/255 of direct send; the orthographic and eye-inside views on 1 and 3
#              ranks within 1/255; a clip that keeps a third of the volume culls the bricks wholly
#              outside it (the brick images' bytes, stats bytes_raw, shrink); bad input is refused
#              by name
# Bounds are ~1.5 dB under the values measured on llvmpipe, given at each check.
source "$(dirname "$0")/lib.sh" "$1"
DATA=$2
S=$SORTLAST
ML=$DATA/marschner_lobb.yaml
FINE=(--set render.sample_spacing=0.25 --set render.ert_threshold=1)
ORTHO=(--set camera.projection=orthographic)
INSIDE=(--set "camera.position=[3, 4, 5]" --set "camera.look_at=[-6, -8, -10]" --set camera.fov=70)
CLIP=(--set "clip.planes=[{normal: [1, 0.4, 0.3], offset: 3.5}]"
      --set "clip.box=[[-16, -18, -14], [15, 13, 17]]")

render() {  # render NP OUT [--set ...]
  local np=$1 out=$2; shift 2
  run_np "$np" render "$ML" -q -o "$out" "$@" || fail "render $*"
}
psnr_of() { "$S" compare "$1" "$2" | sed -n 's/^psnr_db=\([0-9.inf]*\).*/\1/p'; }
at_least() {  # at_least A B MESSAGE: A >= B
  python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) else 1)" "$1" "$2" || fail "$3"
}

case $3 in
reference)
  # view, min PSNR (ray caster, slicing). Measured: orthographic 49.7 / 49.7 dB, the eye inside
  # 54.9 / 54.4 dB, clipped 50.3 / 50.0 dB.
  for spec in "ortho 48 48" "inside 53 52.5" "clip 48.5 48.5"; do
    read -r view min_rc min_sl <<<"$spec"
    case $view in ortho) keys=("${ORTHO[@]}") ;; inside) keys=("${INSIDE[@]}") ;; clip) keys=("${CLIP[@]}") ;; esac
    "$S" reference "$ML" -q -o "$WORK/ref.png" "${keys[@]}" || fail "reference $view"
    for method in raycast slicing; do
      render 1 "$WORK/$view-$method.png" "${keys[@]}" "${FINE[@]}" --set render.method=$method
      min=$min_rc
      [ $method = slicing ] && min=$min_sl
      "$S" compare "$WORK/$view-$method.png" "$WORK/ref.png" --min-psnr "$min" ||
        fail "$view $method below $min dB against the reference"
      echo "$view $method: $(psnr_of "$WORK/$view-$method.png" "$WORK/ref.png") dB"
    done
  done
  ;;
ranks)
  # Measured: 1 brick against 3^3 at most 2/255 (67.2 dB); ranks and strategies bit-identical;
  # culling 45,776 brick-image bytes against 112,228 unclipped (41 %).
  RC=(--set render.method=raycast --set render.sample_spacing=0.5 --set render.ert_threshold=1)
  render 2 "$WORK/one.png" "${RC[@]}" "${CLIP[@]}" --set bricks.per_axis=1
  for np in 1 2 3 4; do render "$np" "$WORK/np$np.png" "${RC[@]}" "${CLIP[@]}"; done
  "$S" compare "$WORK/one.png" "$WORK/np1.png" --max-diff 2 || fail "clip: 3^3 bricks differ from 1 by more than 2/255 (a seam)"
  for np in 2 3 4; do
    "$S" compare "$WORK/np1.png" "$WORK/np$np.png" --max-diff 1 || fail "clip: $np ranks differ from 1 by more than 1/255"
  done
  for strategy in binary-swap radix-k; do
    render 4 "$WORK/$strategy.png" "${RC[@]}" "${CLIP[@]}" --set compositing.strategy=$strategy
    "$S" compare "$WORK/np1.png" "$WORK/$strategy.png" --max-diff 1 || fail "clip: $strategy differs from direct by more than 1/255"
  done
  # The orthographic view and the eye inside: 1 and 3 ranks agree.
  for view in ortho inside; do
    case $view in ortho) keys=("${ORTHO[@]}") ;; inside) keys=("${INSIDE[@]}") ;; esac
    render 1 "$WORK/$view-1.png" "${RC[@]}" "${keys[@]}"
    render 3 "$WORK/$view-3.png" "${RC[@]}" "${keys[@]}"
    "$S" compare "$WORK/$view-1.png" "$WORK/$view-3.png" --max-diff 1 || fail "$view: 3 ranks differ from 1"
  done
  # Culling: a box keeping the lowest third in x (the bricks of x slab 0 and a sliver of slab 1).
  raw() { python3 -c "import json, sys; print(json.load(open(sys.argv[1]))['frames'][0]['bytes_raw'])" "$1"; }
  render 2 "$WORK/all.png" "${RC[@]}" --stats "$WORK/all.json"
  render 2 "$WORK/third.png" "${RC[@]}" --set "clip.box=[[-21, -21, -21], [-7, 21, 21]]" --stats "$WORK/third.json"
  all=$(raw "$WORK/all.json") third=$(raw "$WORK/third.json")
  at_least "$(python3 -c "print(0.6 * $all)")" "$third" "clip box: the brick images did not shrink ($third vs $all bytes)"
  echo "culling: brick images $third bytes with a third kept, $all unclipped"
  # Bad input, by name, with a non-zero exit.
  # The first on 2 ranks (every rank stops, none hangs), the others as the reference reads them.
  bad() {  # bad KEY WORD [--set ...]
    local key=$1 word=$2; shift 2
    local cmd=("$S" reference)
    [ "$key" = clip.planes ] && cmd=(run_np 2 render)
    if "${cmd[@]}" "$ML" -q -o "$WORK/bad.png" "$@" 2>"$WORK/err"; then fail "$* was accepted"; fi
    grep -q "$key" "$WORK/err" && grep -q "$word" "$WORK/err" || { cat "$WORK/err"; fail "$* not refused by name"; }
  }
  bad clip.planes zero --set "clip.planes=[{normal: [0, 0, 0], offset: 1}]"
  bad clip.box empty --set "clip.box=[[0, 0, 0], [1, 1, 0]]"
  bad camera.parallel_scale "> 0" --set camera.parallel_scale=0
  ;;
*) fail "unknown mode $3" ;;
esac
echo PASS
