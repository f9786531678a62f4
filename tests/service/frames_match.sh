#!/usr/bin/env bash
# A frame from POST /api/frame is the frame `sortlast render` makes of the same settings on one
# rank (within 1/255, as on every rank count; rendered once and compared with the service's on 1
# and 3 ranks: half the launches): the default scene and neghip, with the scene's own settings,
# another camera, render.method=raycast, compositing.strategy=binary-swap, a transfer function
# with a built-in colour map, and gradient shading (slicing, the shading keys set in place).
# Requests are not cumulative: the scene's settings asked for again after the others give the
# first frame, byte for byte.
# Usage: frames_match.sh SORTLAST DATA_DIR
source "$(dirname "$0")/service_lib.sh" "$1"
DATA=${2:?usage: frames_match.sh SORTLAST DATA_DIR}

requests=(
  '{"image.width":160,"image.height":128}'
  '{"image.width":160,"image.height":128,"camera.position":[-150,90,-210],"render.method":"raycast"}'
  '{"image":{"width":144,"height":144},"compositing.strategy":"binary-swap","camera.position":[60,-200,150],"format":"png"}'
  '{"image.width":128,"image.height":128,"render.method":"raycast","compositing.strategy":"binary-swap","transfer.points":[[0,0,0,0,0],[0.5,1,0.5,0,0.2],[1,1,1,1,0.9]],"transfer.colormap":"Cool to Warm"}'
  '{"image.width":128,"image.height":128,"render":{"shading":true,"shading_specular":0.5,"shading_shininess":8}}'
)
for scene in default "$DATA/neghip.yaml"; do
  sargs=("$scene"); [ "$scene" = default ] && sargs=()
  name=$(basename "$scene" .yaml)
  # neghip is 64^3 around the origin's corner: cameras as far out, scaled
  for np in 1 3; do
    start_server "$np" "${sargs[@]}"
    i=0
    for req in "${requests[@]}"; do
      if [ "$name" = neghip ]; then  # neghip's box is [0,63]^3: move the cameras out of it
        req=$(sed -e 's/\[-150,90,-210\]/[-80,50,-100]/' -e 's/\[60,-200,150\]/[120,-60,140]/' <<<"$req")
      fi
      out=$WORK/${name}_np${np}_$i.png
      code=$(frame "$out" "$req")
      [ "$code" = 200 ] || { cat "$out"; fail "$name, $np rank(s): $req answered $code"; }
      mapfile -t sets < <(sets_of "$req")
      batch=$WORK/${name}_${i}_render.png
      if [ ! -e "$batch" ]; then
        render_like "$batch" 1 "${sargs[@]}" "${sets[@]}" || fail "sortlast render $name ${sets[*]}"
      fi
      same "$out" "$batch" \
        || fail "$name, $np rank(s): the frame of $req differs from sortlast render ${sets[*]} (1 rank)"
      echo "ok: $name, $np rank(s): $req"
      i=$((i + 1))
    done
    # Not cumulative: the first request again, after raycast / binary-swap / other cameras.
    code=$(frame "$WORK/again.png" "${requests[0]}")
    [ "$code" = 200 ] || fail "$name: the first request again answered $code"
    cmp -s "$WORK/again.png" "$WORK/${name}_np${np}_0.png" \
      || fail "$name, $np rank(s): the first request again gave another image (settings carried over?)"
    stop_server || fail "$name, $np rank(s): sortlast serve did not stop cleanly on SIGTERM"
  done
done
echo "frames_match passed"
