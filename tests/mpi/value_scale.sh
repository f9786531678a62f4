#!/usr/bin/env bash
# transfer.scale through the whole program: neghip (uint8, mostly zeros) under a log scale over
# [1, 255] gives the same image on 1 and 2 ranks (ray caster, 1/255), agrees with the CPU reference
# of the same keys within MIN_PSNR (the ray caster, and slicing with pre-integration), and differs
# from the linear scale's reference (so no path ignores the key); a log scale whose range comes
# from data through zero, or is given through zero, ends every rank with a message naming the key
# and the value.
# Usage: value_scale.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
data=$(realpath "$2")
# Measured on llvmpipe at 0.25 voxel, 96x96: ray caster 52.7 dB, slicing 57.2 dB (pre-integrated:
# 52.7 and 57.3) against the reference; 10.4 dB between the log image and the linear reference.
MIN_PSNR=45
common=(--set image.width=96 --set image.height=96 --set render.sample_spacing=0.25
        --set transfer.preset=default --set "transfer.range=[1, 255]" --set transfer.scale=log)

timeout 120 "$SORTLAST" render "$data/neghip.yaml" -q -o "$WORK/raycast1.png" "${common[@]}" \
  --set render.method=raycast || fail "raycast, 1 rank"
run_np 2 render "$data/neghip.yaml" -q -o "$WORK/raycast2.png" "${common[@]}" --set render.method=raycast ||
  fail "raycast, 2 ranks"
"$SORTLAST" compare "$WORK/raycast1.png" "$WORK/raycast2.png" --max-diff 1 || fail "raycast: 1 and 2 ranks differ"
run_np 2 render "$data/neghip.yaml" -q -o "$WORK/slicing2.png" "${common[@]}" --set render.method=slicing \
  --set transfer.preintegrated=true || fail "slicing, pre-integrated, 2 ranks"
"$SORTLAST" reference "$data/neghip.yaml" -q -o "$WORK/ref.png" "${common[@]}" || fail "reference"
for method in raycast slicing; do
  "$SORTLAST" compare "$WORK/${method}2.png" "$WORK/ref.png" --min-psnr "$MIN_PSNR" ||
    fail "$method: below $MIN_PSNR dB against the reference"
done
"$SORTLAST" reference "$data/neghip.yaml" -q -o "$WORK/ref_linear.png" "${common[@]}" --set transfer.scale=linear ||
  fail "linear reference"
"$SORTLAST" compare "$WORK/raycast2.png" "$WORK/ref_linear.png" --min-psnr 25 >/dev/null &&
  fail "the log image is as close to the linear reference as to its own: the scale did nothing"
echo "ok: log scale on 1 and 2 ranks, ray caster and pre-integrated slicing, against the reference"

expect_error() {  # expect_error RANKS "what" "message part" sortlast-args...
  local np=$1 what=$2 want=$3; shift 3
  local rc=0
  local launch=(run_np "$np"); [ "$np" = 1 ] && launch=(timeout 120 "$SORTLAST")
  "${launch[@]}" render "$data/neghip.yaml" -q -o "$WORK/out.png" --set image.width=32 --set image.height=32 "$@" \
    >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: $what -> $(grep -m1 'error' "$WORK/stderr")"
}
expect_error 2 "log over the data's range through zero" "transfer.scale: log needs a range with both ends > 0" \
  --set transfer.scale=log --set transfer.range=auto
expect_error 1 "log over a given range through zero" "scene key 'transfer.range': [0, 255] has an end <= 0" \
  --set transfer.scale=log
