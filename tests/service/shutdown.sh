#!/usr/bin/env bash
# Stopping the service: SIGTERM to mpirun (also with a large frame in flight) and SIGTERM to rank 0
# end every rank within 5 s, cleanly (rank 0 says "stopped"), and no sortlast process left; SIGTERM to
# rank 0 also exits 0 (Open MPI 4.1's mpirun itself exits 1 when it is signalled, even when every
# rank exits 0 — a trivial MPI program does the same — so its status is not checked there); SIGTERM to a worker
# rank alone ends the job within 20 s with a message; a rank killed with SIGKILL ends the job with mpirun's message, a non-zero status
# and no hang (a client waiting for a frame is answered or disconnected within 20 s).
# Usage: shutdown.sh SORTLAST
source "$(dirname "$0")/service_lib.sh" "$1"

# rank_pid N: the pid of rank N of the running service (a child of mpirun).
rank_pid() {
  local p
  for p in $(pgrep -P "$MPIRUN_PID"); do
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$1" && { echo "$p"; return 0; }
  done
  return 1
}
rank_pids() { pgrep -P "$MPIRUN_PID" | tr '\n' ' '; }
now() { date +%s.%N; }
# wait_gone SECONDS PID...: 0 once none of the processes is left (zombies count as gone).
wait_gone() {
  local limit=$1 p alive; shift
  local end; end=$(python3 -c "import time; print(time.time() + $limit)")
  while :; do
    alive=
    for p in "$@"; do
      [ -e "/proc/$p" ] && [ "$(awk '{print $3}' "/proc/$p/stat" 2>/dev/null)" != Z ] && alive=1
    done
    [ -z "$alive" ] && return 0
    python3 -c "import time,sys; sys.exit(time.time() > $end)" || return 1
    sleep 0.1
  done
}
# stop_by SIGNAL TARGET_PID WHAT [any]: signal, then every rank and mpirun gone within 5 s, exit 0
# (any: mpirun was signalled, its own status is not the ranks').
stop_by() {
  local sig=$1 target=$2 what=$3 any=${4:-} ranks server=$SERVER_PID rc=0 t0 t1
  ranks=$(rank_pids)
  [ -n "$ranks" ] || fail "$what: no rank processes found under mpirun $MPIRUN_PID"
  t0=$(now)
  kill "-$sig" "$target"
  # shellcheck disable=SC2086
  wait_gone 5 $ranks "$MPIRUN_PID" || { ps -o pid,stat,cmd -p "${ranks// /,}$MPIRUN_PID" || true; fail "$what: ranks or mpirun still running 5 s after SIG$sig"; }
  t1=$(now)
  SERVER_PID=
  wait "$server" || rc=$?
  echo "$what: all ranks ended $(python3 -c "print(f'{$t1 - $t0:.2f}')") s after SIG$sig, exit status $rc"
  # (checked at the end, so that every case runs)
  [ "$rc" = 0 ] || [ -n "$any" ] || { tail -5 "$SERVER_LOG"; failures+=("$what: exit status $rc after SIG$sig (expected 0)"); }
}

failures=()

# 1. SIGTERM to mpirun, idle: the ranks stop cleanly (rank 0 says so).
start_server 3
code=$(frame "$WORK/a.png" '{"image.width":128,"image.height":128}')
[ "$code" = 200 ] || fail "first frame answered $code"
stop_by TERM "$MPIRUN_PID" "SIGTERM to mpirun (idle)" any
grep -q 'sortlast serve: stopped' "$SERVER_LOG" || { cat "$SERVER_LOG"; fail "SIGTERM to mpirun: rank 0 did not stop cleanly"; }

# 2. SIGTERM to mpirun while a large frame renders.
start_server 2 -q
curl -s --max-time 30 -o /dev/null -X POST -d '{"image.width":2048,"image.height":2048,"render.sample_spacing":0.25}' \
  "$BASE/api/frame" &
curl_pid=$!
sleep 0.5
stop_by TERM "$MPIRUN_PID" "SIGTERM to mpirun (frame in flight)" any
timeout 10 tail --pid="$curl_pid" -f /dev/null || fail "the client waiting for a frame was left hanging"
wait "$curl_pid" || true

# 3. SIGTERM to rank 0 alone: it ends the service for every rank, exit status 0.
start_server 3 -q
code=$(frame "$WORK/b.png" '{"image.width":96,"image.height":96}')
[ "$code" = 200 ] || fail "frame before SIGTERM to rank 0 answered $code"
pid=$(rank_pid 0) || fail "rank 0 not found"
stop_by TERM "$pid" "SIGTERM to rank 0"

# 3b. SIGTERM to a worker rank alone: rank 0 goes on serving, the worker gives up after its
# 10 s grace and aborts the job (service/frame_commands.h): ended within 20 s, with a message.
start_server 3 -q
pid=$(rank_pid 2) || fail "rank 2 not found"
ranks=$(rank_pids)
t0=$(now)
kill -TERM "$pid"
# shellcheck disable=SC2086
wait_gone 20 $ranks "$MPIRUN_PID" || fail "the service still runs 20 s after SIGTERM to rank 2"
t1=$(now)
server=$SERVER_PID SERVER_PID= rc=0
wait "$server" || rc=$?
echo "SIGTERM to rank 2: the job ended $(python3 -c "print(f'{$t1 - $t0:.2f}')") s later, exit status $rc"
[ "$rc" != 124 ] || fail "the service ran until its time limit after SIGTERM to rank 2"
grep -qi 'signal' "$SERVER_LOG" || { cat "$SERVER_LOG"; fail "no message after SIGTERM to rank 2"; }

# 4. SIGKILL to a worker rank: mpirun ends the job with a message, non-zero, within 20 s.
start_server 3
code=$(frame "$WORK/c.png" '{"image.width":96,"image.height":96}')
[ "$code" = 200 ] || fail "frame before SIGKILL answered $code"
ranks=$(rank_pids)
pid=$(rank_pid 1) || fail "rank 1 not found"
t0=$(now)
kill -KILL "$pid"
# A client asking for a frame now gets an answer or a closed connection, not a hang.
code=$(timeout 25 curl -s --max-time 20 -o "$WORK/after_kill.txt" -w '%{http_code}' -X POST \
  -d '{"image.width":96,"image.height":96}' "$BASE/api/frame") || true
[ "$code" != 200 ] || fail "a frame was rendered after rank 1 was killed"
# shellcheck disable=SC2086
wait_gone 20 $ranks "$MPIRUN_PID" || fail "the service still runs 20 s after rank 1 was killed"
t1=$(now)
server=$SERVER_PID SERVER_PID= rc=0
wait "$server" || rc=$?
[ "$rc" != 0 ] || fail "mpirun exited 0 after a rank was killed"
[ "$rc" != 124 ] || fail "the service ran until its time limit after a rank was killed"
grep -qiE 'rank 1|signal 9|killed|aborted' "$SERVER_LOG" || { cat "$SERVER_LOG"; fail "no message about the lost rank"; }
echo "SIGKILL to rank 1: the job ended $(python3 -c "print(f'{$t1 - $t0:.2f}')") s later, exit status $rc, client got '$code'"
grep -iE 'rank 1|signal 9|killed' "$SERVER_LOG" | head -3
[ ${#failures[@]} = 0 ] || { printf 'FAIL: %s\n' "${failures[@]}"; exit 1; }
echo "shutdown passed"
