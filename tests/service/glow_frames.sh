#!/usr/bin/env bash
# Glow emitters in a resident session (docs/glow.md): frames of a glow scene at two sizes
# and cameras, over a volume with the ray caster and alone, equal `sortlast render`'s (1/255) and
# are within the glow tests' bounds of `sortlast reference` (tests/mpi/glow.sh); a
# request for 8-bit partial images (compositing.precision rgba8, which would clamp the glow) is
# refused with a message naming both keys, and the service keeps answering. The glow keys are frame
# keys: a request moving and adding emitters gets the reference's frame; removing every emitter, or
# adding one to a session started without glow, is refused.
# Usage: glow_frames.sh SORTLAST DATA_DIR
source "$(dirname "$0")/service_lib.sh" "$1"
scene=$2/glow.yaml
# The volume's step pinned at 0.5 voxel, where the bound against the reference was measured.
vol=(--set volume.procedural=blobs --set "volume.dims=[24,24,24]" --set render.method=raycast
     --set render.sample_spacing=0.5
     --set glow.box=auto --set glow.intensity=0.02 --set glow.core_radius=0.03)
for case in alone volume; do
  extra=() far='[2.5,1.5,-3]'
  [ $case = volume ] && extra=("${vol[@]}") far='[30,18,-36]'  # outside the volume's box
  start_server 2 "$scene" "${extra[@]}"
  for req in '{"image.width":96,"image.height":96}' \
             '{"image.width":80,"image.height":112,"camera.position":'"$far"'}'; do
    code=$(frame "$WORK/served.png" "$req")
    [ "$code" = 200 ] || { cat "$WORK/served.png"; fail "$case: $req answered $code"; }
    mapfile -t sets < <(sets_of "$req")
    render_like "$WORK/batch.png" 2 "$scene" "${extra[@]}" "${sets[@]}" || fail "render ${sets[*]}"
    same "$WORK/served.png" "$WORK/batch.png" || fail "$case: the frame of $req differs from sortlast render"
    # And against the independent reference (render shares the session code with serve): one
    # level alone; in the volume, the volume's own sampling: without glow it is 4 levels, 56.9 dB
    # off at the far camera (with glow: 4, 58.3 dB; 3, 62.9 dB at the near one).
    "$SORTLAST" reference "$scene" "${extra[@]}" "${sets[@]}" -q -o "$WORK/ref.png" || fail "reference ${sets[*]}"
    bound=(--max-diff 1); [ $case = volume ] && bound=(--max-diff 4 --min-psnr 56)
    "$SORTLAST" compare "$WORK/served.png" "$WORK/ref.png" "${bound[@]}" || fail "$case: the frame of $req is off the reference"
    [ -f "$WORK/first.png" ] || cp "$WORK/served.png" "$WORK/first.png"
    echo "ok: $case $req"
  done
  # The emitters are frame keys: move one, add one, change intensity and exposure.
  req='{"image.width":96,"image.height":96,"glow.intensity":0.05,"glow.exposure":2,"glow.emitters":[{"center":[0.3,0.1,0],"direction":[0,1,0],"color":[1,0.5,0.2]},{"center":[-0.5,0.2,0.1],"a":0.5,"color":[0.2,0.5,1]}]}'
  code=$(frame "$WORK/moved.png" "$req")
  [ "$code" = 200 ] || { cat "$WORK/moved.png"; fail "$case: new emitters answered $code"; }
  mapfile -t sets < <(sets_of "$req")
  "$SORTLAST" reference "$scene" "${extra[@]}" "${sets[@]}" -q -o "$WORK/ref.png" || fail "reference ${sets[*]}"
  bound=(--max-diff 1); [ $case = volume ] && bound=(--max-diff 4 --min-psnr 56)
  "$SORTLAST" compare "$WORK/moved.png" "$WORK/ref.png" "${bound[@]}" || fail "$case: new emitters off the reference"
  "$SORTLAST" compare "$WORK/moved.png" "$WORK/first.png" --max-diff 8 >/dev/null && fail "$case: the new emitters changed nothing"
  code=$(frame "$WORK/refused.txt" '{"glow.emitters":[]}')
  [ "$code" = 400 ] && grep -q "glow.emitters" "$WORK/refused.txt" || { cat "$WORK/refused.txt"; fail "$case: removing every emitter was not refused ($code)"; }
  code=$(frame "$WORK/refused.txt" '{"compositing.precision":"rgba8"}')
  [ "$code" = 400 ] && grep -q "compositing.precision" "$WORK/refused.txt" && grep -q "glow.emitters" "$WORK/refused.txt" \
    || { cat "$WORK/refused.txt"; fail "$case: an rgba8 request was not refused naming the keys ($code)"; }
  code=$(frame "$WORK/after.png" '{"image.width":96,"image.height":96}')
  [ "$code" = 200 ] || fail "$case: no frame after the refusal ($code)"
  stop_server || fail "$case: sortlast serve did not stop on SIGTERM"
  rm -f "$WORK/first.png"
done
# A session started without emitters refuses a request that adds them (its bricks cover no glow box).
start_server 2 "$scene" --set "glow.emitters=[]" --set volume.procedural=blobs --set "volume.dims=[16,16,16]"
code=$(frame "$WORK/refused.txt" '{"glow.emitters":[{"center":[0,0,0]}]}')
[ "$code" = 400 ] && grep -q "started without glow emitters" "$WORK/refused.txt" || { cat "$WORK/refused.txt"; fail "adding emitters to a session without glow was not refused ($code)"; }
stop_server || fail "sortlast serve did not stop on SIGTERM"
echo "glow_frames passed"
