#!/usr/bin/env bash
# Soak test of the service: `sortlast serve` on 2 ranks answers REQUESTS mixed requests
# (small frames with new cameras and transfer functions, bad requests, clients that disconnect;
# service_soak.py) and the memory of every rank, sampled at each good frame, must not grow after
# the warm-up: the heap in use's least-squares slope over requests WARMUP.. below BOUND_KIB per
# request, resident memory rising by at most 8 MiB (rss_slope.py).
# Usage: service_soak.sh SORTLAST [REQUESTS] [WARMUP] [BOUND_KIB]
source "$(dirname "$0")/../service/service_lib.sh" "$1"
requests=${2:-2000} warmup=${3:-200} bound=${4:-2}
here=$(cd "$(dirname "$0")" && pwd)
# The step pinned: with render.sample_spacing `auto` a request with a new transfer function
# renders three probe frames too (session/auto_spacing.h), and the slope per request
# doubled (rank 0: 1.58 against 0.82 KiB per request; per frame rendered it is lower, 0.4), which
# put rank 1 over the bound in one of five runs. The bound is per request of one frame.
start_server 2 --set "volume.dims=[32,32,32]" --set bricks.per_axis=2 --set render.sample_spacing=0.5
start=$(date +%s.%N)
python3 "$here/service_soak.py" "$BASE" "$requests" "$WORK/samples.json" ||
  { tail -20 "$SERVER_LOG"; fail "the service stopped answering as expected"; }
[ -z "${SOAK_KEEP:-}" ] || cp "$WORK/samples.json" "$SOAK_KEEP"
python3 "$here/rss_slope.py" "$WORK/samples.json" "$warmup" "$bound" "service soak" ||
  fail "the service's resident memory grows with requests"
echo "service soak: $requests requests in $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b-a}') s"
stop_server || fail "the service did not stop on SIGTERM"
