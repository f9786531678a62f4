#!/usr/bin/env bash
# A frame from POST /api/frame is the frame `sortlast render` makes of the same settings on one
# rank (within 1/255, as on every rank count; rendered once and compared with the service's on 1
# and 3 ranks: half the launches): the default scene and neghip, with the scene's own settings,
# another camera, render.method=raycast, compositing.strategy=binary-swap, a transfer function
# with a built-in colour map, and gradient shading (slicing, the shading keys set in place).
# Requests are not cumulative: the scene's settings asked for again after the others give the
# first frame, byte for byte. Then a scene of two fields: one field's transfer function and
# visibility by request (see the block at the end).
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
# Several fields (`volumes`, docs/volumes.md "Several fields"), 2 ranks: a request changing field
# 1's transfer function (volumes[1].transfer.*) gives the frame of a scene file holding that
# transfer map; volumes[1].visible: false gives the frame of field 0 alone (field 1's grid lies
# inside field 0's, so the layout is the same); GET /api/scene lists both fields' data ranges
# (those of --stats) and histograms counting every sample once; other keys of an entry, a missing
# entry and a colour-map file are refused by name.
cat >"$WORK/fields.yaml" <<'Y'
volumes:
  - {procedural: sphere, dims: [33, 33, 33], transfer: {points: [[0, 1, 1, 1, 0], [0.55, 1, 1, 1, 0], [0.8, 1, 1, 1, 0.1], [1, 1, 1, 1, 0.3]], colormap: viridis}}
  - {procedural: blobs, dims: [25, 21, 27], spacing: [1.2, 1.3, 1], transfer: {preset: default, colormap: inferno}}
camera: {position: [30, 20, 44]}
image: {width: 64, height: 64}
render: {sample_spacing: 1}
Y
tf1='[[0,0,0,1,0],[0.35,0,0,1,0],[0.6,1,0.5,0,0.4],[1,1,1,0,0.8]]'
python3 - "$WORK/fields.yaml" "$tf1" >"$WORK/fields_tf1.yaml" <<'PY'
import sys
text = open(sys.argv[1]).read()
print(text.replace("transfer: {preset: default, colormap: inferno}", "transfer: {points: %s, colormap: Cool to Warm}" % sys.argv[2]))
PY
grep -q "Cool to Warm" "$WORK/fields_tf1.yaml" || fail "fields scene copy: the transfer map was not replaced"
cat >"$WORK/field0.yaml" <<'Y'
volume: {procedural: sphere, dims: [33, 33, 33]}
transfer: {points: [[0, 1, 1, 1, 0], [0.55, 1, 1, 1, 0], [0.8, 1, 1, 1, 0.1], [1, 1, 1, 1, 0.3]], colormap: viridis, preintegrated: false}
camera: {position: [30, 20, 44]}
image: {width: 64, height: 64}
render: {sample_spacing: 1}
Y
start_server 2 "$WORK/fields.yaml"
curl -sf "$BASE/api/scene" -o "$WORK/fields_scene.json" || fail "fields: GET /api/scene"
render_like "$WORK/fields_base.png" 1 "$WORK/fields.yaml" --stats "$WORK/fields_stats.json" || fail "fields: sortlast render"
python3 - "$WORK/fields_scene.json" "$WORK/fields_stats.json" <<'PY' || fail "fields: /api/scene's fields"
import json, sys
scene, stats = json.load(open(sys.argv[1])), json.load(open(sys.argv[2]))
fields = scene["fields"]
assert [f["name"] for f in fields] == ["volumes[0]", "volumes[1]"], fields
ranges = stats["data_ranges"]
assert len(ranges) == 2 and stats["data_range"] == ranges[0]["data_range"], (stats["data_range"], ranges)
for f, r, n in zip(fields, ranges, (33 * 33 * 33, 25 * 21 * 27)):
    assert f["data_range"] == r["data_range"] and f["data_range"][0] < f["data_range"][1], (f["data_range"], r)
    assert sum(f["histogram"]["counts"]) == n, (f["name"], sum(f["histogram"]["counts"]), n)
    assert f["visible_key"] == f["name"] + ".visible" and f["transfer_prefix"] == f["name"] + ".transfer.", f
    assert f["name"] + ".transfer.points" in scene["request_keys"], scene["request_keys"]
assert fields[0]["data_range"] != fields[1]["data_range"]
assert fields[1]["settings"]["transfer.colormap"] == "inferno", fields[1]["settings"]
print("ok: fields: data ranges", [f["data_range"] for f in fields], "histograms of", [sum(f["histogram"]["counts"]) for f in fields], "samples")
PY
code=$(frame "$WORK/fields_req_base.png" '{}')
[ "$code" = 200 ] || { cat "$WORK/fields_req_base.png"; fail "fields: {} answered $code"; }
same "$WORK/fields_req_base.png" "$WORK/fields_base.png" || fail "fields: the base frame differs from sortlast render's"
code=$(frame "$WORK/fields_req_tf1.png" "{\"volumes[1].transfer.points\": $tf1, \"volumes[1]\": {\"transfer\": {\"colormap\": \"Cool to Warm\"}}}")
[ "$code" = 200 ] || { cat "$WORK/fields_req_tf1.png"; fail "fields: volumes[1].transfer answered $code"; }
render_like "$WORK/fields_tf1.png" 1 "$WORK/fields_tf1.yaml" || fail "fields: sortlast render of the changed transfer map"
same "$WORK/fields_req_tf1.png" "$WORK/fields_tf1.png" || fail "fields: volumes[1].transfer by request differs from the scene file's"
same "$WORK/fields_req_tf1.png" "$WORK/fields_base.png" >/dev/null 2>&1 && fail "fields: volumes[1].transfer changed nothing"
echo "ok: fields: volumes[1].transfer by request is the scene file's frame"
code=$(frame "$WORK/fields_req_hidden.png" '{"volumes[1].visible": false}')
[ "$code" = 200 ] || { cat "$WORK/fields_req_hidden.png"; fail "fields: volumes[1].visible answered $code"; }
render_like "$WORK/field0.png" 1 "$WORK/field0.yaml" || fail "fields: sortlast render of field 0 alone"
same "$WORK/fields_req_hidden.png" "$WORK/field0.png" || fail "fields: field 1 hidden differs from field 0 alone"
same "$WORK/fields_req_hidden.png" "$WORK/fields_base.png" >/dev/null 2>&1 && fail "fields: hiding field 1 changed nothing"
echo "ok: fields: volumes[1].visible: false is field 0 alone"
for bad in '{"volumes[1].dims": [9, 9, 9]}|volumes[1].dims' '{"volumes[2].transfer.points": [[0,1,1,1,1],[1,1,1,1,1]]}|2 entries' \
  '{"volumes[1].transfer.colormap": "/etc/hostname"}|volumes[1].transfer.colormap' '{"volumes[0].visble": false}|volumes[0].visble' \
  '{"transfer.points": [[0,1,1,1,1],[1,1,1,1,1]]}|volumes'; do
  code=$(frame "$WORK/fields_bad.json" "${bad%|*}")
  [ "$code" = 400 ] && grep -qF -- "${bad#*|}" "$WORK/fields_bad.json" || { cat "$WORK/fields_bad.json"; fail "fields: ${bad%|*} answered $code"; }
done
code=$(frame "$WORK/fields_again.png" '{}')
[ "$code" = 200 ] && cmp -s "$WORK/fields_again.png" "$WORK/fields_req_base.png" || fail "fields: {} after the others gave another frame"
echo "ok: fields: other keys of an entry, a missing entry and a colour-map file refused by name"
stop_server || fail "fields: sortlast serve did not stop cleanly on SIGTERM"
echo "frames_match passed"
