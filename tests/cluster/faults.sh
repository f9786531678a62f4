#!/usr/bin/env bash
# Faults on the cluster rehearsal, 3 nodes over TCP. Each must end the way
# docs/robustness.md promises: every process (mpirun, the orted daemons, the ranks) gone within
# 10 s of the fault, a message naming the lost rank or node, a non-zero status, and no frame
# written half-composited (every frame written equals shared memory's frame of the same camera).
#   kill: every process of node 1 (its orted and rank 1: a node that dies) killed with SIGKILL
#         mid-orbit (binary-swap); then rank 0 (node 0's sortlast, the HTTP server) killed while
#         a client in node 0's namespace asks for frames back to back (radix-k).
#   loss: (not in ctest's set: slow) 2% of the packets dropped on every node's link, both ways,
#         for a whole orbit (netem where the kernel has it, else an iptables statistic rule):
#         slower but correct frames (bit for bit), no hang; prints the time against no loss.
#   cut:  node 1's link taken down (ip link set VETH down: packets vanish, no reset) mid-orbit,
#         its link shaped to 100 Mbit/s so that frames spend much of their time on the wire.
#         TCP alone would notice after minutes; the rehearsal's mpirun sets Open MPI's OOB
#         keepalive (1 s idle, 1 s apart, 3 probes: scripts/cluster-rehearsal), which ends it.
# Usage: faults.sh SORTLAST DATA_DIR REHEARSAL kill|cut|loss
source "$(dirname "$0")/cluster_lib.sh" "$1" "$3"
in_cluster 3 "$0" "$@"
data=$2 mode=$4
addrs=($CLUSTER_ADDRS) veths=($CLUSTER_VETHS)

# frames_complete OUT NAME SETTINGS...: every frame OUT/f_NNNN.png written is shared memory's frame
# of the same camera on 3 ranks, bit for bit (a frame cut short or half-composited is not); sets
# FRAMES to their count.
frames_complete() {
  local out=$1 name=$2 f; shift 2
  FRAMES=$(ls "$out" | grep -c '^f_[0-9]*\.png$' || true)
  [ "$FRAMES" -gt 0 ] || fail "$name: no frame written"
  mkdir -p "$WORK/ref_$name"
  run_np 3 render "$data/neghip.yaml" -q -o "$WORK/ref_$name/f.png" --frames "$FRAMES" "$@" ||
    fail "$name: the reference frames"
  for f in "$out"/f_*.png; do
    "$SORTLAST" compare "$WORK/ref_$name/$(basename "$f")" "$f" --max-diff 0 >"$WORK/cmp.txt" 2>&1 ||
      { cat "$WORK/cmp.txt"; fail "$name: $(basename "$f") is not the frame shared memory makes"; }
  done
}

# orbit_fault NAME STRATEGY: a long orbit of small frames on 3 nodes; the fault once frame 2 is written.
orbit_fault() {
  local name=$1 strategy=$2 out=$WORK/$1 mp rc=0 pids took
  local sets=(--set image.width=96 --set image.height=96 --set compositing.strategy="$strategy"
              --set camera.orbit.frames=5000)
  # Open MPI's start across the namespaces hung about 1 launch in 30 while every node shared this
  # machine's host name and session folder (fixed in the rehearsal's agent: 0 of 120 since;
  # docs/cluster-rehearsal.md). A launch is not the fault this test is about, so one that still
  # has no frame 2 after 30 s while running is killed and started again, at most 3 times.
  mkdir -p "$out"
  local try
  for try in 1 2 3; do
    rm -f "$out"/f_*.png
    timeout 120 "$CLUSTER_MPIRUN" -np 3 "$SORTLAST" render "$data/neghip.yaml" -q -o "$out/f.png" \
      "${sets[@]}" >"$out/log" 2>&1 &
    mp=$!
    for _ in $(seq 300); do [ -e "$out/f_0002.png" ] && break; kill -0 "$mp" 2>/dev/null || break; sleep 0.1; done
    [ -e "$out/f_0002.png" ] && break
    kill -0 "$mp" 2>/dev/null || { cat "$out/log"; fail "$name: the job ended before frame 2"; }
    echo "$name: launch $try hung (no frame 2 after 30 s): killed, started again"
    kill -KILL "$mp" 2>/dev/null || true
    pkill -KILL -f "$CLUSTER_MPIRUN" 2>/dev/null || true
    for n in $CLUSTER_NODES; do for p in $(ip netns pids "$n"); do kill -KILL "$p" 2>/dev/null || true; done; done
    wait "$mp" 2>/dev/null || true
  done
  [ -e "$out/f_0002.png" ] || { cat "$out/log"; fail "$name: no frame 2 in 3 launches of 30 s"; }
  pids=$(job_pids)
  T0=$(now)
  case $name in
    node_kill) kill -KILL $(ip netns pids "$(node_of 1)") ;;
    link_cut) ip link set "${veths[1]}" down
              ip netns exec "$(node_of 1)" ss -tn 2>/dev/null | awk 'NR > 1 && $3 > 0 {q += $3} END {print "bytes queued on node 1 at the cut:", q + 0}' ;;
  esac
  took=$(wait_gone 10 $pids) || { echo "$took"; cat "$out/log"; fail "$name: processes left 10 s after the fault"; }
  wait "$mp" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || { cat "$out/log"; fail "$name: status $rc"; }
  # Open MPI names the node by its address (--host), or the rank that died.
  grep -qE "node ${addrs[1]}( |$)|rank 1 " "$out/log" || { cat "$out/log"; fail "$name: no message naming node ${addrs[1]} or rank 1"; }
  frames_complete "$out" "$name" "${sets[@]}"
  echo "ok: $name mid-orbit ($strategy, 3 nodes): every process gone ${took} s after the fault, status $rc, $FRAMES frames written, each shared memory's frame bit for bit: $(grep -m1 -oE "(Remote daemon|Peer host|mpirun noticed).*(node |host: *)${addrs[1]}.*|mpirun noticed.*rank 1 .*" "$out/log")"
}

case $mode in
  kill)
    orbit_fault node_kill binary-swap
    # The service: rank 0 (node 0's sortlast, which serves HTTP) killed mid-request.
    on_nodes
    start_server 3 -q --set compositing.strategy=radix-k --set "volume.dims=[48,48,48]"
    (for i in $(seq 300); do
       curl -s --max-time 15 -o /dev/null -w '%{http_code}\n' -X POST -d "{\"image.width\":96,\"image.height\":96,\"camera.fov\":$((20 + i % 20))}" \
         "$BASE/api/frame" >>"$WORK/codes" || exit 0
     done) &
    client=$!
    for _ in $(seq 200); do [ "$(grep -cx 200 "$WORK/codes" 2>/dev/null)" -ge 3 ] && break; sleep 0.1; done
    [ "$(grep -cx 200 "$WORK/codes" 2>/dev/null)" -ge 3 ] || fail "service: no 3 frames served within 20 s"
    pids=$(job_pids)
    victim=$(for p in $(ip netns pids "$(node_of 0)"); do if [ "$(cat "/proc/$p/comm" 2>/dev/null)" = sortlast ]; then echo "$p"; fi; done)
    [ -n "$victim" ] || fail "service: no sortlast process in node 0"
    T0=$(now)
    kill -KILL $victim
    took=$(wait_gone 10 $pids) || { echo "$took"; cat "$SERVER_LOG"; fail "service: processes left 10 s after rank 0 was killed"; }
    for _ in $(seq 100); do kill -0 "$client" 2>/dev/null || break; sleep 0.1; done
    kill -0 "$client" 2>/dev/null && fail "service: the client still waits 10 s after the job ended"
    SERVER_PID_WAS=$SERVER_PID; SERVER_PID=
    rc=0; wait "$SERVER_PID_WAS" || rc=$?
    [ "$rc" != 0 ] && [ "$rc" != 124 ] || { cat "$SERVER_LOG"; fail "service: status $rc"; }
    grep -qE "rank 0 |node ${addrs[0]}( |$)" "$SERVER_LOG" || { cat "$SERVER_LOG"; fail "service: no message naming rank 0 or node ${addrs[0]}"; }
    echo "ok: rank 0 of the service killed on node 0 after $(grep -cx 200 "$WORK/codes") frames: every process gone ${took} s after, status $rc, the client answered or disconnected: $(grep -m1 -oE 'mpirun noticed.*' "$SERVER_LOG")"
    ;;
  cut)
    "$CLUSTER_SHAPE" 100mbit
    orbit_fault link_cut direct
    ;;
  loss)
    sets=(--set image.width=256 --set image.height=256 --set camera.orbit.frames=12)
    for pct in 0 2; do
      "$CLUSTER_SHAPE" 1gbit $([ "$pct" = 0 ] || echo "$pct")
      mkdir -p "$WORK/loss$pct"
      T0=$(now)
      run_cluster 3 render "$data/neghip.yaml" -q -o "$WORK/loss$pct/f.png" "${sets[@]}" --stats "$WORK/loss$pct.json" ||
        fail "orbit with $pct% loss: status $?"
      took[$pct]=$(secs "$T0" "$(now)")
    done
    dropped=0
    for ns in $CLUSTER_NODES; do
      dropped=$((dropped + $(ip netns exec "$ns" iptables -L -v -n -x 2>/dev/null | awk '/DROP/ {s += $1} END {print s + 0}')))
    done
    frames_complete "$WORK/loss2" loss "${sets[@]}"
    echo "ok: 12-frame orbit (256², 3 nodes, 1 Gbit/s) with 2% loss: $FRAMES frames bit for bit, ${took[2]} s against ${took[0]} s without loss ($dropped packets dropped by the iptables statistic rules; 0 where netem drops them)"
    ;;
  *) fail "mode $mode: kill, cut or loss" ;;
esac
echo "cluster faults ($mode) passed"
