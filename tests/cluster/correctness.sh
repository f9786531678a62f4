#!/usr/bin/env bash
# The cluster rehearsal's correctness: on 3 nodes (network namespaces, Open MPI over
# TCP only) the default scene, a metaball scene and the service give the same images, bit for bit,
# as the same rank count on shared memory on this machine. Direct send, binary-swap and radix-k.
# Skips (77) where namespaces cannot be made (not root).
# Usage: correctness.sh SORTLAST DATA_DIR REHEARSAL
source "$(dirname "$0")/cluster_lib.sh" "$1" "$3"
in_cluster 3 "$0" "$@"
data=$2
identical() { "$SORTLAST" compare "$1" "$2" --max-diff 0 >"$WORK/cmp.txt" 2>&1 || { cat "$WORK/cmp.txt"; fail "$3"; }; }

# The default scene, a 2-frame orbit, direct send; a metaball scene (particles on brick faces),
# binary-swap.
small=(--set image.width=128 --set image.height=128)
t0=$(now)
run_cluster 3 render -q -o "$WORK/tcp_default.png" "${small[@]}" --set camera.orbit.frames=2 || fail "default scene on 3 nodes"
run_cluster 3 render -q -o "$WORK/tcp_balls.png" "$data/face_particles.yaml" "${small[@]}" \
  --set compositing.strategy=binary-swap || fail "metaball scene on 3 nodes"
t1=$(now)
run_np 3 render -q -o "$WORK/shm_default.png" "${small[@]}" --set camera.orbit.frames=2 || fail "default scene, shared memory"
run_np 3 render -q -o "$WORK/shm_balls.png" "$data/face_particles.yaml" "${small[@]}" \
  --set compositing.strategy=binary-swap || fail "metaball scene, shared memory"
for f in 0000 0001; do
  identical "$WORK/shm_default_$f.png" "$WORK/tcp_default_$f.png" "default scene frame $f: 3 nodes over TCP differ from shared memory"
done
identical "$WORK/shm_balls.png" "$WORK/tcp_balls.png" "metaball scene: 3 nodes over TCP differ from shared memory"
echo "ok: default scene (2 frames, direct send) and metaball scene (binary-swap) on 3 nodes: bit-identical to shared memory ($(secs "$t0" "$t1") s on the nodes)"

# The service: rank 0 in node 0's namespace serves HTTP on its loopback; curl runs there too.
req='{"image.width":128,"image.height":128,"compositing.strategy":"radix-k","camera.position":[60,-200,150],"format":"png"}'
on_nodes
t0=$(now)
start_server 3 -q
code=$(frame "$WORK/tcp_served.png" "$req")
[ "$code" = 200 ] || { cat "$WORK/tcp_served.png"; fail "service on 3 nodes answered $code"; }
stop_server || fail "service on 3 nodes did not stop on SIGTERM"
t1=$(now)
on_nodes off
start_server 3 -q
code=$(frame "$WORK/shm_served.png" "$req")
[ "$code" = 200 ] || { cat "$WORK/shm_served.png"; fail "service on shared memory answered $code"; }
stop_server || fail "service on shared memory did not stop on SIGTERM"
identical "$WORK/shm_served.png" "$WORK/tcp_served.png" "service frame (radix-k): 3 nodes over TCP differ from shared memory"
echo "ok: a service frame (radix-k) from 3 nodes, fetched in node 0's namespace: bit-identical to shared memory (start, frame, stop: $(secs "$t0" "$t1") s)"
echo "cluster correctness passed"
