#!/usr/bin/env bash
# The web viewer in a headless browser against a real `sortlast serve`: starts the service on
# 127.0.0.1:PORT with a token, runs browser_test.mjs (first frame, orbit drag, transfer-function
# drag; Debian's chromium through playwright-core), renders the viewer's last frames again with
# `sortlast render` (the camera the page reports, the settings it requested) and compares them
# (within 1/255), and stops the service with SIGTERM.
# With FIELDS.yaml (a scene of several fields) the service also gets --data-dir FIELDS.yaml's
# folder, and the page loads that scene at the end (POST /api/load), edits field 1's transfer
# function (that frame compared with `sortlast render` of FIELDS.yaml) and hides field 0 (the
# request and a changed image checked; frames_match.sh compares hiding with sortlast render).
# Usage: browser.sh SORTLAST PORT [SCENE.yaml|default] [RANKS] [FIELDS.yaml]
# Screenshots and frames go to $BROWSER_TEST_OUT when set (kept), else to a scratch folder.
# Needs node, tests/service/node_modules (npm ci --prefix tests/service; scripts/install-deps)
# and /usr/bin/chromium (or $CHROMIUM); without them it exits 77 (skipped).
source "$(dirname "$0")/../mpi/lib.sh" "$1"
HERE=$(cd "$(dirname "$0")" && pwd)
PORT=${2:?usage: browser.sh SORTLAST PORT [SCENE.yaml|default] [RANKS]}
scene=("${3:-default}")
[ "${scene[0]}" = default ] && scene=()
NP=${4:-2}
FIELDS_SCENE=${5:-}
serve_extra=()
if [ -n "$FIELDS_SCENE" ]; then
  serve_extra=(--data-dir "$(dirname "$FIELDS_SCENE")")
  export FIELDS_SCENE_NAME=$(basename "$FIELDS_SCENE")
  # --data-dir: a scene argument is relative to it
  [ ${#scene[@]} -gt 0 ] && scene=("$(realpath --relative-to="$(dirname "$FIELDS_SCENE")" "${scene[0]}")")
fi
OUT=${BROWSER_TEST_OUT:-$WORK/out}
mkdir -p "$OUT"
CHROMIUM=${CHROMIUM:-/usr/bin/chromium}
export CHROMIUM

skip() { echo "SKIP: $*"; exit 77; }
command -v node >/dev/null || skip "node is not installed (scripts/install-deps)"
[ -x "$CHROMIUM" ] || skip "$CHROMIUM is not installed (scripts/install-deps)"
[ -d "$HERE/node_modules/playwright-core" ] || skip "playwright-core is not installed: npm ci --prefix tests/service"
command -v curl >/dev/null || skip "curl is not installed"

TOKEN=$(od -An -N12 -tx1 /dev/urandom | tr -d ' \n')
SERVER_PID=
stop_server() {  # SIGTERM, then at most 20 s for every rank to finish
  [ -n "$SERVER_PID" ] || return 0
  kill -TERM "$SERVER_PID" 2>/dev/null || true
  for _ in $(seq 100); do kill -0 "$SERVER_PID" 2>/dev/null || break; sleep 0.2; done
  if kill -0 "$SERVER_PID" 2>/dev/null; then
    kill -KILL "$SERVER_PID" 2>/dev/null || true
    SERVER_PID=
    return 1
  fi
  wait "$SERVER_PID" 2>/dev/null || true
  SERVER_PID=
}
trap 'stop_server; rm -rf "$WORK"' EXIT

# timeout: a service that never stops is ended after 15 minutes whatever happens here
timeout 900 "${MPIRUN[@]}" -np "$NP" "$SORTLAST" serve "${scene[@]}" --listen "127.0.0.1:$PORT" \
  --token "$TOKEN" "${serve_extra[@]}" >"$OUT/server.log" 2>&1 &
SERVER_PID=$!

up=
for _ in $(seq 240); do  # at most ~120 s for the ranks to load the scene
  kill -0 "$SERVER_PID" 2>/dev/null || { cat "$OUT/server.log"; fail "sortlast serve exited before answering"; }
  if curl -sf "http://127.0.0.1:$PORT/api/health?token=$TOKEN" >/dev/null; then up=1; break; fi
  sleep 0.5
done
[ -n "$up" ] || { tail -20 "$OUT/server.log"; fail "no answer from /api/health on port $PORT"; }
# The token guards the API.
code=$(curl -s -o /dev/null -w '%{http_code}' "http://127.0.0.1:$PORT/api/scene")
[ "$code" = 401 ] || [ "$code" = 403 ] || fail "/api/scene without the token answered $code"

timeout 420 node "$HERE/browser_test.mjs" "http://127.0.0.1:$PORT/?token=$TOKEN" "$OUT" "$SORTLAST" \
  || { tail -20 "$OUT/server.log"; fail "browser test"; }

# The frames the viewer showed are the frames `sortlast render` makes of the same settings.
for prefix in "" tf_ cm_ sh_ mip_ clip_ fields_; do
  [ -f "$OUT/${prefix}render_args.txt" ] || continue
  mapfile -t args <"$OUT/${prefix}render_args.txt"
  this_scene=("${scene[@]}")
  [ -n "$FIELDS_SCENE" ] && [ -n "${scene[0]:-}" ] && this_scene=("$(dirname "$FIELDS_SCENE")/${scene[0]}")
  [ "$prefix" = fields_ ] && this_scene=("$FIELDS_SCENE")
  run_np "$NP" render "${this_scene[@]}" -q -o "$WORK/${prefix}render.png" "${args[@]}" \
    || fail "sortlast render of the viewer's ${prefix}frame settings"
  "$SORTLAST" compare "$OUT/${prefix}frame.png" "$WORK/${prefix}render.png" --max-diff 1 \
    || fail "the viewer's ${prefix}frame.png differs from sortlast render's frame"
done

stop_server || fail "sortlast serve did not stop within 20 s of SIGTERM"
echo "browser test passed (screenshots in $OUT)"
