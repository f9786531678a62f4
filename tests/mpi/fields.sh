#!/usr/bin/env bash
# Several fields (`volumes`, docs/volumes.md "Several fields"): two procedural fields on different
# grids (tests/data/two_fields.yaml) against the CPU reference of their mixture; the same frame
# on 1-4 ranks and with every compositing strategy (1/255); one field given through `volumes`
# gives the image of the same field given as `volume`, exactly; a bad key in an entry and a mode
# several fields cannot do end every rank with a message naming the key.
# Usage: fields.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
data=$2
scene=$data/two_fields.yaml
# Measured on llvmpipe: see MIN_PSNR's figure in docs/volumes.md ("Several fields").
MIN_PSNR=45
common=(-q --set render.sample_spacing=0.5)

"$SORTLAST" reference "$scene" "${common[@]}" -o "$WORK/ref.png" || fail "reference"
timeout 120 "$SORTLAST" render "$scene" "${common[@]}" -o "$WORK/np1.png" || fail "render, 1 rank"
"$SORTLAST" compare "$WORK/ref.png" "$WORK/np1.png" --min-psnr "$MIN_PSNR" || fail "below $MIN_PSNR dB against the reference"
echo "ok: two fields against the reference: $("$SORTLAST" compare "$WORK/ref.png" "$WORK/np1.png")"
# Each field matters: the reference of either one alone is far from the mixture's.
for keep in 0 1; do
  python3 - "$scene" "$keep" >"$WORK/one_$keep.yaml" <<'PY'
import sys
text = open(sys.argv[1]).read().split("\n")
start = [i for i, l in enumerate(text) if l.startswith("  - procedural")]
keep = int(sys.argv[2])
drop = start[1 - keep]
end = start[1] if drop == start[0] else next(i for i, l in enumerate(text) if l.startswith("camera"))
print("\n".join(text[:drop] + text[end:]))
PY
  "$SORTLAST" reference "$WORK/one_$keep.yaml" "${common[@]}" -o "$WORK/ref_$keep.png" || fail "reference of field $keep alone"
  "$SORTLAST" compare "$WORK/ref.png" "$WORK/ref_$keep.png" --min-psnr 30 >/dev/null &&
    fail "the mixture is as close to field $keep alone as to itself: the other field did nothing"
done
echo "ok: each field changes the frame"

for np in 2 3 4; do
  for strategy in direct binary-swap radix-k auto; do
    [ "$np" = 3 ] && [ "$strategy" = radix-k ] && continue  # radix-k's 3-rank schedule is binary-swap's fold
    run_np "$np" render "$scene" "${common[@]}" -o "$WORK/np${np}_$strategy.png" \
      --set compositing.strategy="$strategy" --set bricks.per_axis=3 || fail "render $np ranks, $strategy"
    "$SORTLAST" compare "$WORK/np1.png" "$WORK/np${np}_$strategy.png" --max-diff 1 >/dev/null ||
      fail "$np ranks ($strategy, 27 bricks) differ from 1 rank (8 bricks): $("$SORTLAST" compare "$WORK/np1.png" "$WORK/np${np}_$strategy.png")"
  done
done
echo "ok: 1-4 ranks, every strategy, 8 and 27 bricks within 1/255"

# One field through volumes is the volume form: the same image.
cat >"$WORK/as_volumes.yaml" <<'Y'
volumes:
  - procedural: blobs
    dims: [41, 25, 30]
    spacing: [1, 1.6, 0.9]
    transfer: {preset: default, colormap: inferno}
image: {width: 64, height: 64}
Y
cat >"$WORK/as_volume.yaml" <<'Y'
volume: {procedural: blobs, dims: [41, 25, 30], spacing: [1, 1.6, 0.9]}
transfer: {preset: default, colormap: inferno}
image: {width: 64, height: 64}
Y
run_np 2 render "$WORK/as_volumes.yaml" -q -o "$WORK/as_volumes.png" || fail "render one field as volumes"
run_np 2 render "$WORK/as_volume.yaml" -q -o "$WORK/as_volume.png" || fail "render one field as volume"
"$SORTLAST" compare "$WORK/as_volume.png" "$WORK/as_volumes.png" --max-diff 0 || fail "one field: volumes differs from volume"
echo "ok: one field through volumes is the volume form"

expect_error() {  # expect_error "what" "message part" sortlast-args...
  local what=$1 want=$2; shift 2
  local rc=0
  run_np 2 render "$@" -q -o "$WORK/out.png" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: $what -> $(grep -m1 'error' "$WORK/stderr")"
}
sed 's/^    spacing: \[1, 1.6, 0.9\]$/    spacing: [1, 1.6, 0.9]\n    dimz: [3, 3, 3]/' "$scene" >"$WORK/bad_key.yaml"
grep -q dimz "$WORK/bad_key.yaml" || fail "scene copy: two_fields.yaml has changed, adapt the sed line"
expect_error "a bad key in entry 1" "unknown scene key 'volumes[1].dimz'" "$WORK/bad_key.yaml"
expect_error "slicing with two fields" "scene keys 'volumes' and 'render.method: slicing'" "$scene" --set render.method=slicing
# A raw file of the wrong size in entry 1 (the message names the entry's file key).
head -c 1000 /dev/zero >"$WORK/short.raw"
sed "s|^  - procedural: blobs$|  - file: $WORK/short.raw|" "$scene" >"$WORK/bad_file.yaml"
expect_error "a raw file of the wrong size in entry 1" "volumes[1].file" "$WORK/bad_file.yaml"
