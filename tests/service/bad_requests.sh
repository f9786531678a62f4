#!/usr/bin/env bash
# Bad requests get a 4xx with {"error": message} naming the problem, over HTTP and over the
# WebSocket stream, and the service goes on: after each one, the same valid request gives the
# same PNG, byte for byte (HTTP) or within 1/255 (the WebSocket's).
# Usage: bad_requests.sh SORTLAST DATA_DIR
source "$(dirname "$0")/service_lib.sh" "$1"
DATA=${2:?usage: bad_requests.sh SORTLAST DATA_DIR}

start_server 2 "$DATA/neghip.yaml"
good='{"image.width":128,"image.height":112,"camera.position":[120,60,90]}'
code=$(frame "$WORK/good.png" "$good")
[ "$code" = 200 ] || fail "the valid request answered $code"

# status | what the message must mention (extended regex, any case) | body
cases=(
  '400|camera\.positon|{"camera.positon":[200,100,300]}'
  '400|zoom|{"camera":{"zoom":2}}'
  '400|volume\.dims|{"volume.dims":[32,32,32]}'
  '400|volume\.file|{"volume.file":"other.raw"}'
  '400|bricks\.per_axis|{"bricks.per_axis":3}'
  '400|camera\.fov|NaN|{"camera.fov":NaN}'
  '400|camera\.position|inf|finite|range|overflow|{"camera.position":[1e999,60,90]}'
  '400|camera\.fov|{"camera.fov":".nan"}'
  '400|camera\.position|{"camera.position":[".inf",60,90]}'
  '400|image\.background|{"image.background":[".nan",0,0]}'
  '400|transfer\.points|{"transfer.points":[[0,0,0,0,0],[1,1,1,1,".nan"]]}'
  '400|camera\.up|{"camera.up":[0,0,0]}'
  '400|camera\.parallel_scale|{"camera.parallel_scale":0}'
  '400|image\.width|{"image.width":0}'
  '400|image\.width|{"image.width":100000}'
  '400|image\.width|4096|{"image.width":5000}'
  '400|image\.height|{"image.height":-5}'
  '400|image\.width|{"image.width":"wide"}'
  '400|time\.step|{"time.step":1}'
  '400|time\.step|{"time.step":-1}'
  '400|json|parse|{"image.width":'
  '400|object|[1,2,3]'
  '400|render\.method|magic|{"render.method":"magic"}'
  '400|compositing\.strategy|{"compositing.strategy":"telepathy"}'
  '400|transfer\.points|{"transfer.points":[[0,0,0]]}'
  '400|ert_threshold|{"render.ert_threshold":0}'
  '400|shading_shininess|{"render.shading":true,"render.shading_shininess":0}'
  '400|format|gif|{"format":"gif"}'
  '400|quality|{"format":"jpeg","quality":500}'
)

failures=()
check_reply() {  # check_reply WHAT STATUS BODYFILE WANT_STATUS REGEX
  local what=$1 status=$2 body=$3 want=$4 re=$5 msg problem=
  if ! msg=$(python3 -c 'import json,sys; e=json.load(open(sys.argv[1])).get("error"); assert isinstance(e,str) and e; print(e)' "$body" 2>/dev/null); then
    problem="$what: answered $status without a JSON {\"error\": message}: $(head -c 60 "$body" | tr -c '[:print:]' .)"
  elif [ "$status" != "$want" ]; then
    problem="$what: answered $status ($msg), expected $want"
  elif ! grep -qiE -- "$re" <<<"$msg"; then
    problem="$what: $status, but the message does not name the problem ($re): $msg"
  fi
  if [ -n "$problem" ]; then failures+=("$problem"); echo "NOT OK: $problem"; else echo "ok: $what -> $status: ${msg:0:160}"; fi
}

for c in "${cases[@]}"; do
  want=${c%%|*}; rest=${c#*|}
  # the regex is everything up to the last | before the body; bodies hold no |
  body=${rest##*|}; re=${rest%|*}
  code=$(frame "$WORK/bad.out" "$body")
  check_reply "POST /api/frame $body" "$code" "$WORK/bad.out" "$want" "$re"
  code=$(frame "$WORK/after.png" "$good")
  if [ "$code" != 200 ] || ! cmp -s "$WORK/after.png" "$WORK/good.png"; then
    failures+=("after $body: the valid request answered $code / another image")
  fi
done

# A body over 1 MiB: 413.
python3 -c 'import json; print(json.dumps({"transfer.points": [[i / 200000, 1, 1, 1, 0.5] for i in range(200000)]}))' >"$WORK/big.json"
code=$(curl -s --max-time 60 -o "$WORK/bad.out" -w '%{http_code}' -X POST -H 'Content-Type: application/json' \
  --data-binary @"$WORK/big.json" "$BASE/api/frame")
check_reply "POST /api/frame with a $(stat -c %s "$WORK/big.json")-byte body" "$code" "$WORK/bad.out" 413 'large|size|bytes|MiB|limit'
code=$(frame "$WORK/after.png" "$good")
{ [ "$code" = 200 ] && cmp -s "$WORK/after.png" "$WORK/good.png"; } || failures+=("after the large body: the valid request answered $code / another image")

# Other paths and methods: 4xx with a message.
for m_p in "GET /api/frame" "GET /api/nothing" "DELETE /api/scene"; do
  code=$(curl -s --max-time 20 -o "$WORK/bad.out" -w '%{http_code}' -X "${m_p% *}" "$BASE${m_p#* }")
  case $code in 4??) echo "ok: $m_p -> $code" ;; *) failures+=("$m_p answered $code (expected 4xx)") ;; esac
done

# Recording without --record-dir: 403, naming the option.
code=$(curl -s --max-time 20 -o "$WORK/bad.out" -w '%{http_code}' -X POST --data-binary '{"path":"x.mp4"}' "$BASE/api/record")
check_reply "POST /api/record without --record-dir" "$code" "$WORK/bad.out" 403 'record-dir'

# The same bad requests over the WebSocket: {"id", "status": 400, "error"}, then the valid one.
# ws_cases NAME CASE...: one connection sends the cases one at a time, then the valid request.
ws_cases() {
  local name=$1 i=0 c want rest body re k n; shift
  local dir=$WORK/ws_$name wants=()
  mkdir -p "$dir"
  : >"$dir/messages.txt"
  for c in "$@"; do
    want=${c%%|*}; rest=${c#*|}; body=${rest##*|}; re=${rest%|*}
    case $body in  # give the JSON objects an id
      '{'*'}') body=$(python3 -c 'import sys; print("{\"id\":%s,%s" % (sys.argv[2], sys.argv[1][1:]))' "$body" "$i") ;;
    esac
    echo "$body" >>"$dir/messages.txt"
    wants+=("$want|$re|$body")
    i=$((i + 1))
  done
  python3 -c 'import json,sys; j=json.loads(sys.argv[1]); j["id"]=999; print(json.dumps(j))' "$good" >>"$dir/messages.txt"
  if ! timeout 120 node "$HERE/ws_requests.mjs" "ws://127.0.0.1:$PORT/api/stream" "$dir/messages.txt" "$dir/out"; then
    failures+=("WebSocket ($name): the connection ended before every message was answered ($(wc -l <"$dir/out/replies.jsonl") of $((i + 1)) answered; last sent: $(sed -n "$(($(wc -l <"$dir/out/replies.jsonl") + 1))p" "$dir/messages.txt"))")
    echo "NOT OK: ${failures[-1]}"
  fi
  mapfile -t replies <"$dir/out/replies.jsonl"
  for k in "${!wants[@]}"; do
    [ "$k" -lt "${#replies[@]}" ] || break
    w=${wants[$k]}; want=${w%%|*}; rest=${w#*|}; body=${rest##*|}; re=${rest%|*}
    echo "${replies[$k]}" >"$WORK/reply.json"
    check_reply "WebSocket $body" "$(json "$WORK/reply.json" 'j.get("status")')" "$WORK/reply.json" "$want" "$re"
  done
  [ "${#replies[@]}" = $((i + 1)) ] || return 0
  echo "${replies[-1]}" >"$WORK/reply.json"
  [ "$(json "$WORK/reply.json" 'j.get("status"), j.get("id")')" = "(200, 999)" ] \
    || failures+=("WebSocket ($name): the valid request after the bad ones answered ${replies[-1]}")
  { [ -f "$dir/out/$i.png" ] && same "$dir/out/$i.png" "$WORK/good.png"; } \
    || failures+=("WebSocket ($name): the valid request after the bad ones gave another image")
}
if command -v node >/dev/null && [ -d "$HERE/node_modules/ws" ]; then
  # A number too large for a double gets its own connection: it is the one that must not end it.
  plain=() overflow=()
  for c in "${cases[@]}"; do
    case $c in *1e999*) overflow+=("$c") ;; *) plain+=("$c") ;; esac
  done
  ws_cases plain "${plain[@]}"
  ws_cases overflow "${overflow[@]}"
else
  echo "(node or the ws package missing: WebSocket part skipped)"
fi

stop_server || failures+=("sortlast serve did not stop cleanly on SIGTERM")
[ ${#failures[@]} = 0 ] || { printf 'FAIL: %s\n' "${failures[@]}"; exit 1; }
echo "bad_requests passed"
