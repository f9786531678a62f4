#!/usr/bin/env bash
# --data-dir: the scene argument is relative to the directory; GET /api/files lists its scenes;
# POST /api/load refuses (400, with a message) a path with .., an absolute path (outside and even
# inside), a symlink to a file outside, a path through a symlinked directory leading outside and a
# missing file, and loads a good scene: its frames are `sortlast render`'s of that scene (1/255),
# and requests after a refused load still render the scene loaded before.
# Usage: data_dir.sh SORTLAST DATA_DIR
source "$(dirname "$0")/service_lib.sh" "$1"
DATA=${2:?usage: data_dir.sh SORTLAST DATA_DIR}
failures=()
bad() { failures+=("$*"); echo "NOT OK: $*"; }

D=$WORK/scenes
mkdir -p "$D/sub" "$WORK/outside"
cp "$DATA/neghip_64x64x64_uint8.raw" "$D/"
cp "$DATA/neghip.yaml" "$D/neghip.yaml"
# another scene in a subfolder: the same data, another transfer function and camera
cat >"$D/sub/other.yaml" <<'EOF'
volume: {file: ../neghip_64x64x64_uint8.raw, dims: [64, 64, 64], type: uint8}
transfer: {preset: ramp, range: [0, 255]}
image: {width: 128, height: 96}
camera: {position: [-60, 70, 90]}
EOF
cp "$D/sub/other.yaml" "$WORK/outside/secret.yaml"
sed -i 's|\.\./neghip|../scenes/neghip|' "$WORK/outside/secret.yaml"
ln -s ../outside/secret.yaml "$D/link_out.yaml"        # a symlink to a file outside
ln -s "$WORK/outside" "$D/linkdir"                     # a symlinked folder leading outside
ln -s sub/other.yaml "$D/link_in.yaml"                 # a symlink that stays inside (may be allowed)

start_server 2 --data-dir "$D" neghip.yaml
good='{"image.width":128,"image.height":96}'
code=$(frame "$WORK/neghip.png" "$good")
[ "$code" = 200 ] || fail "a frame of the starting scene answered $code"
render_like "$WORK/neghip_render.png" 2 "$DATA/neghip.yaml" --set image.width=128 --set image.height=96
same "$WORK/neghip.png" "$WORK/neghip_render.png" || bad "the scene given relative to --data-dir is not neghip.yaml"

curl -s --max-time 20 -o "$WORK/files.json" "$BASE/api/files" || fail "GET /api/files"
echo "GET /api/files: $(cat "$WORK/files.json")"
python3 - "$WORK/files.json" <<'PY' || bad "GET /api/files does not list neghip.yaml and sub/other.yaml, or lists something outside"
import json, sys
j = json.load(open(sys.argv[1]))
names = json.dumps(j)
assert "neghip.yaml" in names and "sub/other.yaml" in names, names
assert "secret.yaml" not in names, names
PY

load() {  # load SCENE: POST /api/load; prints the status, the reply in $WORK/load.json
  local body
  body=$(python3 -c 'import json,sys; print(json.dumps({"scene": sys.argv[1]}))' "$1")
  curl -s --max-time 120 -o "$WORK/load.json" -w '%{http_code}' -X POST --data-binary "$body" "$BASE/api/load" || true
}
refused() {  # refused SCENE WHY
  local code msg
  code=$(load "$1")
  msg=$(json "$WORK/load.json" 'j["error"]' 2>/dev/null) || msg=
  if [ "$code" = 400 ] && [ -n "$msg" ]; then
    echo "ok: load $1 ($2) -> 400: $msg"
  else
    bad "load $1 ($2): answered $code $(head -c 200 "$WORK/load.json"), expected 400 with a message"
  fi
  # the scene loaded before still renders the same frame
  code=$(frame "$WORK/after.png" "$good")
  { [ "$code" = 200 ] && cmp -s "$WORK/after.png" "$WORK/current.png"; } \
    || bad "after refusing $1: the frame answered $code or changed"
}
cp "$WORK/neghip.png" "$WORK/current.png"
refused ../outside/secret.yaml "a .. path out"
refused sub/../../outside/secret.yaml "a .. path through a subfolder"
refused "$WORK/outside/secret.yaml" "an absolute path outside"
refused "$D/sub/other.yaml" "an absolute path, even inside"
refused link_out.yaml "a symlink to a file outside"
refused linkdir/secret.yaml "a path through a symlinked folder outside"
refused missing.yaml "a missing file"
refused "" "an empty name"

# A good scene loads; its frames are sortlast render's of it.
code=$(load sub/other.yaml)
[ "$code" = 200 ] || bad "load sub/other.yaml answered $code: $(cat "$WORK/load.json")"
echo "load sub/other.yaml -> $code: $(head -c 300 "$WORK/load.json")"
code=$(frame "$WORK/other.png" '{}')
[ "$code" = 200 ] || bad "a frame of sub/other.yaml answered $code"
render_like "$WORK/other_render.png" 2 "$D/sub/other.yaml"
same "$WORK/other.png" "$WORK/other_render.png" || bad "the loaded scene's frame differs from sortlast render sub/other.yaml"
cp "$WORK/other.png" "$WORK/current.png"
good='{}'
refused ../outside/secret.yaml "a .. path out, after a load"
# GET /api/scene describes the loaded scene
curl -s --max-time 20 "$BASE/api/scene" >"$WORK/scene.json"
[ "$(json "$WORK/scene.json" 'j["image"]["width"], j["image"]["height"]')" = "(128, 96)" ] \
  || bad "GET /api/scene after the load does not describe sub/other.yaml: $(head -c 200 "$WORK/scene.json")"
# ... and where each rank renders (ranks_gl), one entry a rank, after a load too.
[ "$(json "$WORK/scene.json" '[(r["rank"], r["backend"], r["device"]) for r in j["ranks_gl"]]')" = "[(0, 'osmesa', -1), (1, 'osmesa', -1)]" ] \
  || bad "GET /api/scene: ranks_gl is $(json "$WORK/scene.json" 'j.get("ranks_gl")')"

stop_server || bad "sortlast serve did not stop on SIGTERM"

# The scene argument must lie inside --data-dir too.
rc=0
timeout 60 "${MPIRUN[@]}" -np 1 "$SORTLAST" serve --data-dir "$D" ../outside/secret.yaml --listen 127.0.0.1:0 \
  >"$WORK/outside.log" 2>&1 || rc=$?
if [ "$rc" = 0 ] || [ "$rc" = 124 ] || grep -q 'sortlast serve: http' "$WORK/outside.log"; then
  bad "serve --data-dir D ../outside/secret.yaml started (exit $rc)"
else
  echo "ok: a scene argument outside --data-dir is refused: $(grep -i error "$WORK/outside.log" | head -1)"
fi

[ ${#failures[@]} = 0 ] || { printf 'FAIL: %s\n' "${failures[@]}"; exit 1; }
echo "data_dir passed"
