#!/usr/bin/env bash
# A rank killed with SIGKILL mid-orbit: every rank and mpirun are gone within 10 s, with a
# message, and a non-zero status. Open MPI's mpirun notices the child's death itself (waitpid),
# kills the other ranks and prints "mpirun noticed that process rank R ... exited on signal 9";
# ranks blocked in MPI with the dead peer never see an error first (measured: 2 to 5 s from the
# kill until every process is gone, on a loaded 2-core machine). Rank 0 and a worker rank, direct
# send and binary-swap. On 2 ranks also an MPI error, which must become a message.
# Usage: killed_ranks.sh SORTLAST DATA_DIR NP
KILL_GRACE=1  # the ranks left must have their second to print (lib.sh)
source "$(dirname "$0")/lib.sh" "$1"
data=$2 np=$3
now() { date +%s.%N; }
# kill_mid_orbit STRATEGY RANK: a long orbit of small frames; SIGKILL to RANK once frame 2 is written.
kill_mid_orbit() {
  local strategy=$1 victim=$2 out=$WORK/$1_$2 mp pid p t0 t1 rc=0 ranks=
  mkdir -p "$out"
  timeout 120 "${MPIRUN[@]}" -np "$np" "$SORTLAST" render "$data/neghip.yaml" -q -o "$out/f.png" \
    --set image.width=48 --set image.height=48 --set camera.orbit.frames=5000 \
    --set compositing.strategy="$strategy" >"$out/log" 2>&1 &
  mp=$!
  for _ in $(seq 600); do [ -e "$out/f_0002.png" ] && break; kill -0 "$mp" 2>/dev/null || break; sleep 0.1; done
  [ -e "$out/f_0002.png" ] || { cat "$out/log"; fail "np $np $strategy: no frame 2 within 60 s"; }
  # timeout runs mpirun; mpirun's children are the ranks (each knows its OMPI_COMM_WORLD_RANK).
  local mpirun_pid; mpirun_pid=$(pgrep -P "$mp" -x mpirun | head -1)
  [ -n "$mpirun_pid" ] || fail "np $np: mpirun not found under $mp"
  for p in $(pgrep -P "$mpirun_pid"); do
    ranks+="$p "
    tr '\0' '\n' <"/proc/$p/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$victim" && pid=$p
  done
  [ -n "${pid:-}" ] || fail "np $np: rank $victim not found"
  t0=$(now)
  kill -KILL "$pid"
  # Every rank and mpirun gone (zombies count as gone) within 10 s.
  for _ in $(seq 100); do
    local alive=
    for p in $ranks $mpirun_pid; do
      [ -e "/proc/$p" ] && [ "$(awk '{print $3}' "/proc/$p/stat" 2>/dev/null)" != Z ] && alive=1
    done
    [ -z "$alive" ] && break
    sleep 0.1
  done
  t1=$(now)
  [ -z "$alive" ] || { ps -o pid,stat,cmd -p "${ranks// /,}$mpirun_pid" || true; kill -KILL $ranks "$mpirun_pid" 2>/dev/null; fail "np $np $strategy: processes left 10 s after SIGKILL to rank $victim"; }
  wait "$mp" || rc=$?
  [ "$rc" != 0 ] || fail "np $np $strategy: exit status 0 after rank $victim was killed"
  [ "$rc" != 124 ] || fail "np $np $strategy: ran to the time limit after rank $victim was killed"
  grep -qE "rank $victim .*signal 9|sortlast: error" "$out/log" || { cat "$out/log"; fail "np $np $strategy: no message naming the lost rank $victim"; }
  echo "np $np $strategy, SIGKILL to rank $victim after $(ls "$out" | grep -c png) frames: all gone in $(python3 -c "print(f'{$t1 - $t0:.2f}')") s, status $rc: $(grep -m1 -oE "mpirun noticed.*|sortlast: error.*" "$out/log")"
}
kill_mid_orbit direct $((np - 1))
kill_mid_orbit binary-swap 0
# An MPI error (a send to a rank that does not exist) is a message naming the rank, the phase and
# MPI's own text (session/mpi_errors.h), not an abort without text.
if [ "$np" = 2 ]; then
  rc=0
  SORTLAST_TEST_MPI_ERROR_RANK=1 run_np 2 render "$data/neghip.yaml" -q -o "$WORK/e.png" \
    --set image.width=48 --set image.height=48 >"$WORK/e.log" 2>&1 || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || { cat "$WORK/e.log"; fail "MPI error: status $rc"; }
  grep -qE "sortlast: error: rank 1: MPI error while rendering a frame: .*rank" "$WORK/e.log" ||
    { cat "$WORK/e.log"; fail "MPI error: no message naming it"; }
  echo "MPI error on rank 1: $(grep -m1 'sortlast: error' "$WORK/e.log")"
fi
echo "killed ranks on $np passed"
