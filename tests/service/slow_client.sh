#!/usr/bin/env bash
# A WebSocket client that never reads (asking for 1024^2 frames all the time) and clients that
# leave mid-frame (WebSocket closed, HTTP request aborted) do not stall the others: a third client
# gets 12 frames one after another, each within 10 s, its last one `sortlast render`'s (1/255);
# /api/health answers within 2 s throughout; afterwards the service still answers and stops.
# Usage: slow_client.sh SORTLAST [RANKS]
source "$(dirname "$0")/service_lib.sh" "$1"
need_node
NP=${2:-2}
start_server "$NP"
timeout 150 node "$HERE/slow_client.mjs" "ws://127.0.0.1:$PORT/api/stream" "$BASE" "$WORK/out" 1024 12 10 \
  || fail "slow and vanishing clients stalled the service (above)"
curl -s --max-time 10 "$BASE/api/health" >"$WORK/health.json" || fail "GET /api/health after the slow clients"
echo "health: $(cat "$WORK/health.json")"
mapfile -t sets < <(sets_of "$(cat "$WORK/out/good_last.json")")
render_like "$WORK/render.png" "$NP" "${sets[@]}" || fail "sortlast render ${sets[*]}"
same "$WORK/out/good_last.png" "$WORK/render.png" || fail "the good client's last frame differs from sortlast render ${sets[*]}"
# Still serving: a frame over HTTP.
code=$(frame "$WORK/after.png" '{"image.width":128,"image.height":128}')
[ "$code" = 200 ] || fail "a frame after the slow clients answered $code"
stop_server || fail "sortlast serve did not stop within 20 s of SIGTERM"
echo "slow_client passed"
