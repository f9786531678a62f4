#!/usr/bin/env bash
# A time series (volume.files: "step_*.raw"): the service's frame of time.step K is the frame
# `sortlast render` makes of step K's file alone (volume.file), and of the series scene with
# --set time.step=K (within 1/255), asked for in the order 0, 2, 1, 2 (a step seen before comes from
# the cache) over HTTP and the WebSocket; the steps differ; GET /api/scene reports 3 steps and the
# step shown; time.step 3 is refused (400). The frames recorded into a movie (POST /api/record).
# Usage: series.sh SORTLAST [RANKS]
source "$(dirname "$0")/service_lib.sh" "$1"
NP=${2:-2}
failures=()
bad() { failures+=("$*"); echo "NOT OK: $*"; }

S=$WORK/series
mkdir -p "$S"
# Three 40x36x32 uint8 volumes: a ball that moves along x and grows brighter, and a fixed slab.
python3 - "$S" <<'PY'
import sys
nx, ny, nz = 40, 36, 32
for k in range(3):
    cx, cy, cz, r = 12 + 8 * k, 18, 16, 8 + 2 * k
    data = bytearray(nx * ny * nz)
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                d2 = (x - cx) ** 2 + (y - cy) ** 2 + (z - cz) ** 2
                v = 0
                if d2 < r * r:
                    v = int((100 + 70 * k) * (1 - d2 / (r * r))) + 20
                elif 4 <= z <= 6:
                    v = 60
                data[x + nx * (y + ny * z)] = min(v, 255)
    open(f"{sys.argv[1]}/step_{k}.raw", "wb").write(bytes(data))
PY
common='  dims: [40, 36, 32]
  type: uint8
transfer: {preset: ramp, range: [0, 255]}
image: {width: 128, height: 112}
camera: {position: [70, 45, 80]}
bricks: {per_axis: 2}'
printf 'volume:\n  files: "step_*.raw"\n%s\n' "$common" >"$S/series.yaml"
for k in 0 1 2; do printf 'volume:\n  file: step_%s.raw\n%s\n' "$k" "$common" >"$S/one_$k.yaml"; done

mkdir -p "$WORK/rec/sub" && ln -s "$WORK" "$WORK/rec/out"
start_server "$NP" "$S/series.yaml" --record-dir "$WORK/rec"
curl -s --max-time 20 "$BASE/api/scene" >"$WORK/scene.json"
[ "$(json "$WORK/scene.json" 'j.get("steps")')" = 3 ] || bad "GET /api/scene: steps is $(json "$WORK/scene.json" 'j.get("steps")'), expected 3"

for k in 0 1 2; do
  render_like "$WORK/one_$k.png" "$NP" "$S/one_$k.yaml" || fail "sortlast render of step_$k.raw alone"
  render_like "$WORK/series_$k.png" "$NP" "$S/series.yaml" --set time.step=$k \
    || { bad "sortlast render series.yaml --set time.step=$k failed"; continue; }
  same "$WORK/series_$k.png" "$WORK/one_$k.png" \
    || bad "sortlast render --set time.step=$k differs from rendering step_$k.raw alone"
done
cmp -s "$WORK/one_0.png" "$WORK/one_1.png" && fail "steps 0 and 1 give the same image: the test data is wrong"

i=0
for k in 0 2 1 2; do
  code=$(frame "$WORK/frame_$i.png" "{\"time.step\":$k}")
  if [ "$code" != 200 ]; then bad "time.step $k (request $i) answered $code: $(head -c 200 "$WORK/frame_$i.png")"; continue; fi
  [ "$(json "$WORK/frame_$i.png.stats.json" 'j.get("step")')" = "$k" ] || bad "time.step $k: the stats say step $(json "$WORK/frame_$i.png.stats.json" 'j.get("step")')"
  same "$WORK/frame_$i.png" "$WORK/one_$k.png" && echo "ok: time.step $k (request $i) is step_$k.raw's frame" \
    || bad "time.step $k (request $i) differs from sortlast render of step_$k.raw"
  curl -s --max-time 20 "$BASE/api/scene" >"$WORK/scene.json"
  [ "$(json "$WORK/scene.json" 'j.get("step")')" = "$k" ] || bad "GET /api/scene after time.step $k: step is $(json "$WORK/scene.json" 'j.get("step")')"
  i=$((i + 1))
done
# A request without time.step shows the scene's own step (0), not the last one asked for.
code=$(frame "$WORK/plain.png" '{}')
{ [ "$code" = 200 ] && same "$WORK/plain.png" "$WORK/one_0.png"; } || bad "a request without time.step after step 2 is not step 0's frame"

code=$(frame "$WORK/bad.json" '{"time.step":3}')
if [ "$code" = 400 ] && grep -q 'time.step' "$WORK/bad.json"; then echo "ok: time.step 3 -> 400: $(cat "$WORK/bad.json")"
else bad "time.step 3 answered $code: $(head -c 200 "$WORK/bad.json")"; fi

if command -v node >/dev/null && [ -d "$HERE/node_modules/ws" ]; then
  printf '%s\n' '{"id":1,"time.step":2}' '{"id":2,"time.step":0}' '{"id":3,"time.step":1}' >"$WORK/ws.txt"
  timeout 120 node "$HERE/ws_requests.mjs" "ws://127.0.0.1:$PORT/api/stream" "$WORK/ws.txt" "$WORK/ws" \
    || bad "WebSocket: not every step answered"
  n=0
  for k in 2 0 1; do
    { [ -f "$WORK/ws/$n.png" ] && same "$WORK/ws/$n.png" "$WORK/one_$k.png"; } || bad "WebSocket time.step $k differs from step_$k.raw's frame"
    n=$((n + 1))
  done
fi
# Recording (POST /api/record): 3 frames (steps 0, 1, 2; the last at 64x56, scaled into the
# movie's 128x112) into sub/steps.mp4 under --record-dir; ffprobe counts 3 frames of 128x112.
# A path leaving the directory (.., a symbolic link out) is refused with 400 and a message.
record() {  # record OUT.json JSON: POST /api/record; prints the HTTP status
  curl -s --max-time 60 -o "$1" -w '%{http_code}' -X POST -H 'Content-Type: application/json' \
    --data-binary "$2" "$BASE/api/record"
}
for bad_path in ../escape.mp4 out/escape.mp4 /tmp/escape.mp4; do
  code=$(record "$WORK/rec.json" "{\"path\":\"$bad_path\"}")
  if [ "$code" = 400 ] && grep -q "$bad_path" "$WORK/rec.json"; then echo "ok: record $bad_path -> 400: $(cat "$WORK/rec.json")"
  else bad "record $bad_path answered $code: $(cat "$WORK/rec.json")"; fi
done
[ ! -e "$WORK/escape.mp4" ] || bad "a refused recording left $WORK/escape.mp4"
code=$(record "$WORK/rec.json" '{"stop":true}')
[ "$code" = 409 ] || bad "stop while not recording answered $code: $(cat "$WORK/rec.json")"
code=$(record "$WORK/rec.json" '{"path":"sub/steps.mp4","frame_rate":10}')
[ "$code" = 200 ] || bad "record sub/steps.mp4 answered $code: $(cat "$WORK/rec.json")"
code=$(record "$WORK/rec2.json" '{"path":"other.mp4"}')
[ "$code" = 409 ] || bad "a second recording while one runs answered $code: $(cat "$WORK/rec2.json")"
for req in '{"time.step":0}' '{"time.step":1}' '{"time.step":2,"image":{"width":64,"height":56}}'; do
  code=$(frame "$WORK/rec_frame.png" "$req")
  [ "$code" = 200 ] || bad "frame $req while recording answered $code"
done
code=$(record "$WORK/rec.json" '{"stop":true}')
[ "$code" = 200 ] || bad "stop answered $code: $(cat "$WORK/rec.json")"
[ "$(json "$WORK/rec.json" '(j.get("frames"), j.get("frames_scaled"))')" = "(3, 1)" ] \
  || bad "stop: $(cat "$WORK/rec.json"), expected 3 frames, 1 scaled"
got=$(ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=codec_name,width,height,nb_read_frames \
  -of csv=p=0 "$WORK/rec/sub/steps.mp4" 2>&1) || true
[ "$got" = "h264,128,112,3" ] && echo "ok: recorded sub/steps.mp4: $got" || bad "recorded movie: ffprobe says '$got', want 'h264,128,112,3'"
stop_server || bad "sortlast serve did not stop on SIGTERM"

[ ${#failures[@]} = 0 ] || { printf 'FAIL: %s\n' "${failures[@]}"; exit 1; }
echo "series passed"
