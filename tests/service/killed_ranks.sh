#!/usr/bin/env bash
# `sortlast serve` with a rank killed by SIGKILL while a client asks for frames one after another:
# every rank and mpirun gone within 10 s, with mpirun's message naming the rank, a non-zero
# status, and the client answered or disconnected (not left hanging). Rank 0 and worker ranks, 2,
# 3 and 4 ranks, direct send and binary-swap.
# Usage: killed_ranks.sh SORTLAST
source "$(dirname "$0")/service_lib.sh" "$1"
now() { date +%s.%N; }
gone() {  # gone PID...: none left (zombies count as gone)
  local p
  for p in "$@"; do [ -e "/proc/$p" ] && [ "$(awk '{print $3}' "/proc/$p/stat" 2>/dev/null)" != Z ] && return 1; done
  return 0
}
kill_serving() {
  local np=$1 strategy=$2 victim=$3 p pid= ranks= t0 t1 rc=0 client
  start_server "$np" -q --set compositing.strategy="$strategy" --set "volume.dims=[48,48,48]"
  for p in $(pgrep -P "$MPIRUN_PID"); do
    ranks+="$p "
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$victim" && pid=$p
  done
  [ -n "$pid" ] || fail "np $np: rank $victim not found"
  # A client asking for frames back to back (each bounded): the kill lands mid-frame or between.
  (for i in $(seq 200); do
     curl -s --max-time 15 -o /dev/null -w '%{http_code}\n' -X POST -d "{\"image.width\":64,\"image.height\":64,\"camera.fov\":$((20 + i % 20))}" \
       "$BASE/api/frame" >>"$WORK/codes_${np}_$victim" || exit 0
   done) &
  client=$!
  for _ in $(seq 100); do grep -qx 200 "$WORK/codes_${np}_$victim" 2>/dev/null && break; sleep 0.1; done
  grep -qx 200 "$WORK/codes_${np}_$victim" || fail "np $np: no frame served within 10 s"
  sleep 0.3
  t0=$(now)
  kill -KILL "$pid"
  for _ in $(seq 100); do
    # shellcheck disable=SC2086
    gone $ranks "$MPIRUN_PID" && break
    sleep 0.1
  done
  t1=$(now)
  # shellcheck disable=SC2086
  gone $ranks "$MPIRUN_PID" || fail "np $np $strategy: processes left 10 s after SIGKILL to rank $victim"
  local server=$SERVER_PID
  SERVER_PID=
  wait "$server" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || fail "np $np $strategy: exit status $rc after rank $victim was killed"
  timeout 20 tail --pid="$client" -f /dev/null || fail "np $np: the client was left hanging"
  grep -qE "rank $victim .*signal 9" "$SERVER_LOG" || { cat "$SERVER_LOG"; fail "np $np: no message naming rank $victim"; }
  echo "serve np $np $strategy, SIGKILL to rank $victim after $(grep -cx 200 "$WORK/codes_${np}_$victim") frames: all gone in $(python3 -c "print(f'{$t1 - $t0:.2f}')") s, status $rc: $(grep -m1 -oE "mpirun noticed.*" "$SERVER_LOG")"
}
# Each rank count, each strategy, rank 0 and a worker, in four runs (about 6 s each).
kill_serving 2 direct 1
kill_serving 3 binary-swap 0
kill_serving 4 direct 0
kill_serving 4 binary-swap 3
echo "killed ranks (serve) passed"
