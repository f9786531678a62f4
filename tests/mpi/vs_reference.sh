#!/usr/bin/env bash
# GL slicing against the double-precision reference integrator of the same model. Checks a PSNR
# bound at two slice spacings AND that halving the spacing gains at least 4 dB: the renderer
# converges to the reference, so the bounds are not luck.
# Usage: vs_reference.sh SORTLAST SCENE BACKEND SPACING_A MIN_PSNR_A SPACING_B MIN_PSNR_B
source "$(dirname "$0")/lib.sh" "$1"
scene=$2 backend=$3
"$SORTLAST" reference "$scene" -q -o "$WORK/ref.png" || fail "reference"
psnr() {
  run_np 2 render "$scene" -q -o "$WORK/gl.png" --set render.backend="$backend" \
    --set render.sample_spacing="$1" >/dev/null || fail "render spacing $1"
  "$SORTLAST" compare "$WORK/gl.png" "$WORK/ref.png" --min-psnr "$2" >&2 || fail "spacing $1 below $2 dB"
  "$SORTLAST" compare "$WORK/gl.png" "$WORK/ref.png" | sed -n 's/^psnr_db=\([0-9.]*\).*/\1/p'
}
a=$(psnr "$4" "$5")
b=$(psnr "$6" "$7")
echo "spacing $4: $a dB, spacing $6: $b dB"
python3 -c "import sys; a,b=map(float,sys.argv[1:]); sys.exit(0 if b-a>=4 else 1)" "$a" "$b" \
  || fail "halving the spacing gained less than 4 dB ($a -> $b)"
