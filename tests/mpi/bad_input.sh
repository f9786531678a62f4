#!/usr/bin/env bash
# Bad input: each case must end every rank with a non-zero exit and a clear message naming the
# problem, within the time limit (no hang, no crash trace).
# Scope `short` (the sanitizer build, where each launch costs ~3 s): one parse error, the NaN met
# while reading, the camera inside, and every failure of a rank (while rendering, after a brick with
# images in flight, in binary-swap, a crash): the paths that free what is half built. The other
# parse-time refusals take the same path as the first.
# Usage: bad_input.sh SORTLAST DATA_DIR [full|short]
source "$(dirname "$0")/lib.sh" "$1"
data=$2
scope=${3:-full}
full() { [ "$scope" = full ]; }
raw="$data/neghip_64x64x64_uint8.raw"

expect_error() {  # expect_error "what" "message part" sortlast-args...
  local what=$1 want=$2; shift 2
  local rc=0
  run_np 3 render -q -o "$WORK/out.png" "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: $what -> $(grep -m1 'sortlast: error' "$WORK/stderr")"
}

expect_error "unknown key on the command line" "unknown scene key 'volume.dimz'" --set "volume.dimz=[1,2,3]"
if full; then
expect_error "missing file" "no such file" --set volume.file="$WORK/nope.raw"
expect_error "wrong dims for the file size" "file has 262144 bytes" \
  --set volume.file="$raw" --set "volume.dims=[64,64,65]"
head -c 200000 "$raw" >"$WORK/truncated.raw"
expect_error "truncated file" "file has 200000 bytes" \
  --set volume.file="$WORK/truncated.raw" --set "volume.dims=[64,64,64]"
printf 'volume:\n  dims: [32, 32, 32]\ncamera:\n  fovv: 30\n' >"$WORK/typo.yaml"
expect_error "unknown key in a file" "unknown scene key 'camera.fovv' (line 4)" "$WORK/typo.yaml"
printf 'volume: [unclosed\n' >"$WORK/broken.yaml"
expect_error "malformed scene file" "not valid YAML" "$WORK/broken.yaml"
expect_error "missing scene file" "cannot open" "$WORK/missing.yaml"
fi
python3 - "$WORK/nan.raw" <<'PY'
import struct, sys
v = [0.5] * (16 * 16 * 16)
v[3 + 16 * (4 + 16 * 5)] = float("nan")
open(sys.argv[1], "wb").write(struct.pack("<%df" % len(v), *v))
PY
expect_error "NaN in float data" "NaN at voxel [3, 4, 5]" \
  --set volume.file="$WORK/nan.raw" --set "volume.dims=[16,16,16]" --set volume.type=float32
expect_error "camera inside the particles" "is inside the box of the particles" --set particles.procedural=layers \
  --set "camera.position=[0.5,0.2,0.1]"
if full; then
expect_error "zero-size image" "image.width and image.height must be in [1, 32768]" --set image.width=0
expect_error "unknown backend" "expected osmesa or egl" --set render.backend=vulkan
expect_error "glow emitters with the slicing renderer" "'glow.emitters' and 'render.method: slicing'" \
  --set "glow.emitters=[{center: [0, 0, 0]}]" --set render.method=slicing
expect_error "glow emitter with a zero direction" "glow.emitters[0].direction': must not be zero" \
  --set "glow.emitters=[{center: [0, 0, 0], direction: [0, 0, 0]}]"
expect_error "bricks finer than the grid" "bricks per axis need at least" \
  --set "volume.dims=[4,4,4]" --set bricks.per_axis=4
fi
SORTLAST_TEST_FAIL_RANK=2 expect_error "one rank fails while rendering" "rank 2: injected failure" \
  --set image.width=64 --set image.height=64
# After its first brick a rank has images on the way to rank 0 (direct send overlaps sending with
# rendering; 512^2 brick images are large enough to need the receiver): the others must still
# drain them and stop. Rank 0 failing late must drain what the others send.
for r in 2 0; do
  SORTLAST_TEST_FAIL_RANK_AFTER_BRICK=$r expect_error "rank $r fails after its first brick" \
    "injected failure after a brick" --set image.width=512 --set image.height=512
done
SORTLAST_TEST_FAIL_RANK_AFTER_BRICK=1 expect_error "binary-swap: rank 1 fails after a brick" \
  "injected failure after a brick" --set compositing.strategy=binary-swap
rc=0
SORTLAST_TEST_CRASH_RANK=1 run_np 3 render -q -o "$WORK/out.png" --set image.width=64 \
  --set image.height=64 >/dev/null 2>&1 || rc=$?
[ "$rc" != 0 ] && [ "$rc" != 124 ] || fail "a crashing rank: exit code $rc"
echo "ok: a rank that crashes ends the job (exit $rc)"
