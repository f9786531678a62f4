# Shared by the cluster tests: runs the calling test inside scripts/cluster-rehearsal,
# where its ranks live in network namespaces ("nodes") and talk over TCP only.
# Usage, first lines of a test:  source cluster_lib.sh SORTLAST REHEARSAL; in_cluster NODES "$0" "$@"
# Outside the rehearsal, in_cluster runs REHEARSAL --nodes NODES -- bash TEST ARGS... and exits
# with its status: 77 (ctest's SKIP_RETURN_CODE) with a SKIP line where namespaces cannot be
# made here. Inside, it returns and the test goes on with lib.sh's MPIRUN (shared memory on this
# machine), WORK and fail, service_lib.sh's start_server, frame and stop_server (KILL_GRACE=1:
# ranks left get their second to print), plus run_cluster NP ARGS... (sortlast across the nodes),
# node_of RANK (the namespace of rank RANK: rank r runs on node r) and on_nodes, which makes
# start_server launch across the nodes and curl run in node 0's namespace (on_nodes off: back to
# shared memory here).
REHEARSAL=$2
source "$(dirname "${BASH_SOURCE[0]}")/../service/service_lib.sh" "$1"
LOCAL_MPIRUN=("${MPIRUN[@]}") CURL_NS=
curl() { if [ -n "$CURL_NS" ]; then ip netns exec "$CURL_NS" curl "$@"; else command curl "$@"; fi; }
on_nodes() {
  if [ "${1:-}" = off ]; then MPIRUN=("${LOCAL_MPIRUN[@]}") CURL_NS=
  else MPIRUN=("$CLUSTER_MPIRUN") CURL_NS=$(node_of 0); fi
}
in_cluster() {
  local nodes=$1 test=$2; shift 2
  [ -n "${CLUSTER_MPIRUN:-}" ] && return 0
  local rc=0
  "$REHEARSAL" --nodes "$nodes" -- bash "$test" "$@" || rc=$?
  [ "$rc" = 77 ] && echo "SKIP: the cluster rehearsal cannot run here (its message above says why)"
  exit "$rc"
}
run_cluster() { local np=$1; shift; timeout 120 "$CLUSTER_MPIRUN" -np "$np" "$SORTLAST" "$@"; }
node_of() { local n=($CLUSTER_NODES); echo "${n[$1]}"; }
now() { echo "${EPOCHREALTIME/./}"; }  # microseconds
secs() { printf '%d.%02d' $(( ($2 - $1) / 1000000 )) $(( ($2 - $1) % 1000000 / 10000 )); }  # secs T0 T1
# job_pids: mpirun (started through CLUSTER_MPIRUN) and every process in the nodes' namespaces.
job_pids() {
  local ns
  cat "$CLUSTER_DIR/mpirun.pids" 2>/dev/null || true
  for ns in $CLUSTER_NODES; do ip netns pids "$ns"; done
}
# wait_gone LIMIT_S PID...: waits until none of the processes is left (a zombie counts as gone);
# prints the seconds from $T0 (now's) until the last went, or returns 1 after LIMIT_S from $T0
# with them listed.
wait_gone() {
  local limit=$1 p s st left; shift
  left=" $* "
  while :; do
    for p in $left; do
      st=Z
      if [ -r "/proc/$p/stat" ] && read -r s <"/proc/$p/stat" 2>/dev/null; then s=${s##*) }; st=${s%% *}; fi
      [ "$st" = Z ] && left=${left/ $p / }
    done
    [ -z "${left// /}" ] && { secs "$T0" "$(now)"; return 0; }
    [ $(( $(now) - T0 )) -gt $(( limit * 1000000 )) ] && break
    sleep 0.05
  done
  echo "left $limit s after the fault:"; ps -o pid,stat,args -p "$(echo $left | tr ' ' ,)" | cut -c1-160
  return 1
}
