#!/usr/bin/env bash
# Latest wins: a WebSocket client that sends 30 requests back to back (512^2, a new camera each),
# three times, gets some of them dropped ({"id", "dropped": true}), every id answered once, and the
# last id of each round an image, which is `sortlast render`'s frame of that camera (1/255).
# GET /api/health counts the dropped requests.
# Usage: latest_wins.sh SORTLAST [RANKS]
source "$(dirname "$0")/service_lib.sh" "$1"
need_node
NP=${2:-2}
start_server "$NP"
timeout 120 node "$HERE/latest_wins.mjs" "ws://127.0.0.1:$PORT/api/stream" "$WORK/out" 30 512 3 \
  | tee "$WORK/summary.json" || fail "latest wins (above)"
curl -s --max-time 20 "$BASE/api/health" >"$WORK/health.json"
echo "health: $(cat "$WORK/health.json")"
dropped=$(json "$WORK/summary.json" 'j["dropped"]')
[ "$(json "$WORK/health.json" 'j["dropped"]')" -ge "$dropped" ] || fail "/api/health counts fewer dropped requests than the client saw ($dropped)"
# The last frame is the frame of its camera.
mapfile -t sets < <(python3 -c '
import json, sys
c = json.load(open(sys.argv[1]))["stats"]["camera"]
for k in ("position", "look_at", "up"):
    print("--set"); print("camera.%s=%s" % (k, json.dumps(c[k])))
print("--set"); print("camera.fov=%r" % c["fov"])
print("--set"); print("image.width=%d" % c["width"]); print("--set"); print("image.height=%d" % c["height"])
' "$WORK/out/last.json")
render_like "$WORK/render.png" "$NP" "${sets[@]}" || fail "sortlast render ${sets[*]}"
same "$WORK/out/last.png" "$WORK/render.png" || fail "the last frame differs from sortlast render ${sets[*]}"
stop_server || fail "sortlast serve did not stop on SIGTERM"
echo "latest_wins passed"
