# Shared by the service test scripts: start `sortlast serve` under mpirun on a free loopback port,
# talk to it with curl, and stop it with SIGTERM on exit. Every wait is bounded.
# Usage: source service_lib.sh SORTLAST_BINARY
# Sets SORTLAST, MPIRUN, WORK (scratch folder, removed on exit), HERE (this folder), and after
# start_server: PORT, BASE (http://ADDR:PORT), MPIRUN_PID, SERVER_LOG.
KILL_GRACE=${KILL_GRACE:-1}  # SIGTERM stops a service: its ranks get their second (lib.sh)
source "$(dirname "${BASH_SOURCE[0]}")/../mpi/lib.sh" "$1"
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
SERVER_PID= MPIRUN_PID= PORT= BASE= SERVER_LOG= SERVER_COUNT=0 STOP_STATUS=
SERVER_LIMIT=${SERVER_LIMIT:-300}  # whatever happens, a service lives at most this long

skip() { echo "SKIP: $*"; exit 77; }
need_node() {  # the WebSocket clients need node and the ws package (npm ci --prefix tests/service)
  command -v node >/dev/null || skip "node is not installed (scripts/install-deps)"
  [ -d "$HERE/node_modules/ws" ] || skip "the ws package is not installed: npm ci --prefix tests/service"
}
command -v curl >/dev/null || skip "curl is not installed"
command -v python3 >/dev/null || skip "python3 is not installed"

# start_server NP [serve arguments...]: listens on 127.0.0.1:0 unless the arguments hold --listen.
# Waits (at most 120 s) for rank 0's "sortlast serve: http://ADDR:PORT/" line.
start_server() {
  local np=$1; shift
  local listen=(--listen 127.0.0.1:0) a
  for a in "$@"; do [ "$a" = --listen ] && listen=(); done
  SERVER_LOG=$WORK/server_$((++SERVER_COUNT)).log
  timeout "$SERVER_LIMIT" "${MPIRUN[@]}" -np "$np" "$SORTLAST" serve "$@" "${listen[@]}" \
    >"$SERVER_LOG" 2>&1 &
  SERVER_PID=$!
  local url=
  for _ in $(seq 600); do
    url=$(grep -o 'sortlast serve: http://[^/ ]*' "$SERVER_LOG" | head -1 | sed 's|.*http://||') || true
    [ -n "$url" ] && break
    kill -0 "$SERVER_PID" 2>/dev/null || { cat "$SERVER_LOG"; fail "sortlast serve exited before listening"; }
    sleep 0.2
  done
  [ -n "$url" ] || { tail -20 "$SERVER_LOG"; fail "sortlast serve printed no URL within 120 s"; }
  PORT=${url##*:}
  BASE="http://$url"
  MPIRUN_PID=$(pgrep -P "$SERVER_PID" -x mpirun | head -1) || true
  [ -n "$MPIRUN_PID" ] || MPIRUN_PID=$(pgrep -P "$SERVER_PID" | head -1)
}

# stop_server: SIGTERM to mpirun, then at most 20 s for every rank to finish. Returns non-zero if
# it had to be killed; mpirun's exit status goes to STOP_STATUS (shutdown.sh checks it).
stop_server() {
  [ -n "$SERVER_PID" ] || return 0
  local pid=$SERVER_PID rc=0
  SERVER_PID=
  kill -TERM "${MPIRUN_PID:-$pid}" 2>/dev/null || true
  for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.2; done
  if kill -0 "$pid" 2>/dev/null; then
    kill -KILL "${MPIRUN_PID:-$pid}" "$pid" 2>/dev/null || true
    wait "$pid" 2>/dev/null || true
    return 1
  fi
  wait "$pid" || rc=$?
  STOP_STATUS=$rc
}
trap 'stop_server || true; rm -rf "$WORK"' EXIT

# frame OUT.png JSON [curl args...]: POST /api/frame; prints the HTTP status; the body goes to OUT,
# the X-Sortlast-Stats header to OUT.stats.json.
frame() {
  local out=$1 body=$2; shift 2
  rm -f "$out" "$out.headers"
  curl -s --max-time 60 -o "$out" -D "$out.headers" -w '%{http_code}' -X POST \
    -H 'Content-Type: application/json' --data-binary "$body" "$@" "$BASE/api/frame"
  touch "$out" "$out.headers"
  sed -n 's/^[Xx]-[Ss]ortlast-[Ss]tats: //p' "$out.headers" | tr -d '\r' >"$out.stats.json"
}

# json FILE EXPR: evaluate a Python expression on the JSON in FILE (bound to j).
json() { python3 -c 'import json,sys; j=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))' "$1" "$2"; }

# render_like OUT.png NP [render arguments...]: the batch renderer's frame of the same settings.
# render.estimate=off: the service's default (serve_job.cpp); with it on, a batch job of one frame
# would take a still image's step (session/auto_spacing.h) where the service probes.
render_like() { local out=$1 np=$2; shift 2; run_np "$np" render -q -o "$out" --set render.estimate=off "$@"; }

same() { "$SORTLAST" compare "$1" "$2" --max-diff 1 >"$WORK/compare.txt" 2>&1 || { cat "$WORK/compare.txt"; return 1; }; }

# sets_of JSON: the request's scene keys as `--set key=value` arguments for `sortlast render`, one
# per line (nested objects flattened to dotted keys; format and quality are not scene keys).
# Use: mapfile -t args < <(sets_of "$json")
sets_of() {
  python3 - "$1" <<'PY'
import json, sys
def flat(prefix, v):
    if isinstance(v, dict):
        for k, x in v.items():
            yield from flat(prefix + "." + k if prefix else k, x)
    else:
        yield prefix, v
for k, v in flat("", json.loads(sys.argv[1])):
    if k in ("format", "quality", "id"):
        continue
    print("--set")
    print(k + "=" + (v if isinstance(v, str) else json.dumps(v, separators=(",", ":"))))
PY
}
