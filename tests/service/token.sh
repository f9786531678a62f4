#!/usr/bin/env bash
# Security of the listening address: on an address other than 127.0.0.1/::1/localhost (here
# 127.0.0.2, which only this machine reaches) the service refuses to start without --token, with a
# message; with --token every /api/ request and the WebSocket need it (401 without it or with a
# wrong one, 200 with `Authorization: Bearer T` or `?token=T`). The token from --token-file is on
# no command line (ps); a file others may read is refused; --token still works, with a warning.
# Usage: token.sh SORTLAST
source "$(dirname "$0")/service_lib.sh" "$1"
failures=()
bad() { failures+=("$*"); echo "NOT OK: $*"; }

# 1. No --token on a non-loopback-default address: refused, non-zero exit, a message.
for addr in 127.0.0.2:0 0.0.0.0:0; do
  rc=0
  timeout 60 "${MPIRUN[@]}" -np 2 "$SORTLAST" serve --listen "$addr" >"$WORK/refused.log" 2>&1 || rc=$?
  if [ "$rc" = 0 ] || [ "$rc" = 124 ]; then
    bad "serve --listen $addr without --token: exit status $rc (expected a refusal)"
  elif ! grep -qi 'token' "$WORK/refused.log"; then
    bad "serve --listen $addr without --token: exit $rc without a message about --token: $(head -3 "$WORK/refused.log")"
  else
    echo "ok: serve --listen $addr without --token refused (exit $rc): $(grep -i token "$WORK/refused.log" | head -1)"
  fi
  grep -q 'sortlast serve: http' "$WORK/refused.log" && bad "serve --listen $addr without --token listened anyway"
done

# 1b. --token-file refusals, on every rank: a file its group or others may read; both options.
TOKEN=t$(od -An -N12 -tx1 /dev/urandom | tr -d ' \n')
printf '%s\n' "$TOKEN" >"$WORK/token" && chmod 640 "$WORK/token"
rc=0
timeout 60 "${MPIRUN[@]}" -np 2 "$SORTLAST" serve --listen 127.0.0.2:0 --token-file "$WORK/token" >"$WORK/refused.log" 2>&1 || rc=$?
if [ "$rc" = 0 ] || [ "$rc" = 124 ] || ! grep -q "readable by its group or by others (mode 0640).*chmod 600" "$WORK/refused.log"; then
  bad "--token-file of mode 640: exit $rc, $(grep -m1 error "$WORK/refused.log")"
else
  echo "ok: --token-file of mode 640 refused (exit $rc): $(grep -m1 error "$WORK/refused.log")"
fi
chmod 600 "$WORK/token"
rc=0
# (the command line is parsed before MPI starts, the same on every rank: no mpirun needed)
timeout 60 "$SORTLAST" serve --token x --token-file "$WORK/token" >"$WORK/refused.log" 2>&1 || rc=$?
[ "$rc" != 0 ] && [ "$rc" != 124 ] && grep -q "excludes" "$WORK/refused.log" \
  && echo "ok: --token with --token-file refused (exit $rc): $(head -1 "$WORK/refused.log")" \
  || bad "--token with --token-file: exit $rc, $(head -2 "$WORK/refused.log")"

# cmdline_with_token: the processes whose command line (ps, /proc/PID/cmdline) holds $TOKEN.
# The token goes to the scan by the environment, so the scan's own command line does not hold it.
cmdline_with_token() {
  TOKEN_SCAN=$TOKEN python3 -c '
import os, subprocess
token, me = os.environ["TOKEN_SCAN"], str(os.getpid())
rows = subprocess.run(["ps", "-eo", "pid=,args="], capture_output=True, text=True).stdout.splitlines()
print(" ".join(r.split(None, 1)[0] for r in rows if token in r and r.split(None, 1)[0] != me))'
}

# 2. With --token-file on 127.0.0.2 (one line break after the token, mode 600).
start_server 2 --listen 127.0.0.2:0 --token-file "$WORK/token"
case $BASE in http://127.0.0.2:*) ;; *) bad "listening on $BASE, not 127.0.0.2" ;; esac
# No process shows the token: not mpirun, not a rank (ps reads /proc/PID/cmdline).
ranks=$(pgrep -P "$MPIRUN_PID" | wc -l)
seen=$(cmdline_with_token)
if [ -n "$seen" ] || [ "$ranks" -lt 2 ]; then
  bad "--token-file: the token is on a command line ($seen) or the ranks were not found ($ranks)"
else
  echo "ok: --token-file: no command line holds the token (mpirun and its $ranks ranks running)"
fi
grep -q "warning: --token" "$SERVER_LOG" && bad "--token-file: warned about --token"
expect() {  # expect STATUS WHAT curl-args...
  local want=$1 what=$2 code; shift 2
  code=$(curl -s --max-time 30 -o "$WORK/reply" -w '%{http_code}' "$@") || true
  if [ "$code" != "$want" ]; then
    bad "$what: answered $code, expected $want ($(head -c 120 "$WORK/reply" | tr -c '[:print:]' .))"
  elif [ "$want" = 401 ] && ! json "$WORK/reply" 'j["error"]' >/dev/null 2>&1; then
    bad "$what: 401 without a JSON {\"error\": message}"
  else
    echo "ok: $what -> $code"
  fi
}
for path in /api/health /api/scene; do
  expect 401 "GET $path without the token" "$BASE$path"
  expect 401 "GET $path with a wrong Bearer token" -H "Authorization: Bearer wrong" "$BASE$path"
  expect 401 "GET $path with ?token=wrong" "$BASE$path?token=wrong"
  expect 401 "GET $path with a token prefix" "$BASE$path?token=${TOKEN%?}"
  expect 200 "GET $path with the Bearer token" -H "Authorization: Bearer $TOKEN" "$BASE$path"
  expect 200 "GET $path with ?token=" "$BASE$path?token=$TOKEN"
done
body='{"image.width":96,"image.height":96}'
expect 401 "POST /api/frame without the token" -X POST --data-binary "$body" "$BASE/api/frame"
expect 401 "POST /api/frame with a wrong token" -X POST -H "Authorization: Bearer nope" --data-binary "$body" "$BASE/api/frame"
expect 200 "POST /api/frame with the token" -X POST -H "Authorization: Bearer $TOKEN" --data-binary "$body" "$BASE/api/frame"
head -c 8 "$WORK/reply" | od -An -c | grep -q 'P   N   G' || bad "POST /api/frame with the token: not a PNG"
expect 200 "POST /api/frame?token=" -X POST --data-binary "$body" "$BASE/api/frame?token=$TOKEN"
# The WebSocket handshake needs it too.
if command -v node >/dev/null && [ -d "$HERE/node_modules/ws" ]; then
  echo '{"id":1,"image.width":96,"image.height":96}' >"$WORK/ws.txt"
  out=$(timeout 60 node "$HERE/ws_requests.mjs" "ws://127.0.0.2:$PORT/api/stream" "$WORK/ws.txt" "$WORK/ws_none" 2>&1) && rc=0 || rc=$?
  [ "$rc" = 3 ] && grep -q 401 <<<"$out" && echo "ok: WebSocket without the token: $out" \
    || bad "WebSocket without the token: exit $rc, $out (expected the handshake refused with 401)"
  out=$(timeout 60 node "$HERE/ws_requests.mjs" "ws://127.0.0.2:$PORT/api/stream?token=wrong" "$WORK/ws.txt" "$WORK/ws_wrong" 2>&1) && rc=0 || rc=$?
  [ "$rc" = 3 ] && grep -q 401 <<<"$out" && echo "ok: WebSocket with a wrong token: $out" \
    || bad "WebSocket with a wrong token: exit $rc, $out (expected the handshake refused with 401)"
  if timeout 60 node "$HERE/ws_requests.mjs" "ws://127.0.0.2:$PORT/api/stream?token=$TOKEN" "$WORK/ws.txt" "$WORK/ws_ok" \
    && [ -f "$WORK/ws_ok/0.png" ]; then
    echo "ok: WebSocket with ?token= renders"
  else
    bad "WebSocket with ?token=: no frame"
  fi
fi
stop_server || bad "sortlast serve did not stop on SIGTERM"

# 3. --token still works, with a warning; its ranks' command lines do show it (which is also
# what makes the check above able to fail).
start_server 1 --listen 127.0.0.2:0 --token "$TOKEN"
grep -q "warning: --token is on the command line, which every user of this node can read" "$SERVER_LOG" \
  && echo "ok: --token warns: $(grep -m1 warning "$SERVER_LOG")" || bad "--token: no warning"
[ -n "$(cmdline_with_token)" ] && echo "ok: --token: the token is on a command line (as warned)" \
  || bad "--token: the token found on no command line: the --token-file check above cannot fail"
expect 200 "GET /api/health with --token's Bearer token" -H "Authorization: Bearer $TOKEN" "$BASE/api/health"
stop_server || bad "sortlast serve (--token) did not stop on SIGTERM"

[ ${#failures[@]} = 0 ] || { printf 'FAIL: %s\n' "${failures[@]}"; exit 1; }
echo "token passed"
