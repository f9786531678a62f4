#!/usr/bin/env bash
# 20 clients at once (10 WebSocket, 10 HTTP), each with its own camera, two requests each: every
# request answered 200 with its own camera (the stats say so) and all 40 images distinct; four of
# them (both protocols, both rounds) are `sortlast render`'s frames of the same settings (1/255).
# Usage: concurrent.sh SORTLAST [RANKS]
source "$(dirname "$0")/service_lib.sh" "$1"
need_node
NP=${2:-3}
start_server "$NP"
timeout 120 node "$HERE/concurrent.mjs" "ws://127.0.0.1:$PORT/api/stream" "$BASE" "$WORK/out" 20 128 2 \
  || fail "concurrent clients (above)"
for name in c0_0 c7_1 c12_1 c19_0; do
  mapfile -t sets < <(sets_of "$(cat "$WORK/out/$name.json")")
  render_like "$WORK/$name.render.png" "$NP" "${sets[@]}" || fail "sortlast render ${sets[*]}"
  same "$WORK/out/$name.png" "$WORK/$name.render.png" || fail "$name differs from sortlast render ${sets[*]}"
  echo "ok: $name is sortlast render's frame"
done
stop_server || fail "sortlast serve did not stop on SIGTERM"
echo "concurrent passed"
