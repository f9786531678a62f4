#!/usr/bin/env bash
# Soak test: a long orbit on 2 ranks, small frames, and every rank's memory must not grow after
# the warm-up: the least-squares slope of the heap in use (the per-frame heap_mb of --stats) over
# frames WARMUP.. stays below BOUND_KIB per frame, and resident memory (rss_mb) rises by at most
# 8 MiB (rss_slope.py says why both). A leak of a brick image, a texture or a message buffer per
# frame would be 9-36 KiB a frame at 96 x 96.
# Usage: render_soak.sh SORTLAST volume|particles [FRAMES] [WARMUP] [BOUND_KIB]
source "$(dirname "$0")/../mpi/lib.sh" "$1"
mode=$2 frames=${3:-300} warmup=${4:-20} bound=${5:-4}
here=$(cd "$(dirname "$0")" && pwd)
small=(--set image.width=96 --set image.height=96 --set camera.orbit.frames="$frames"
  --set camera.orbit.elevation=25)
case "$mode" in
  volume) scene=(--set "volume.dims=[32,32,32]" --set bricks.per_axis=2) ;;
  particles) scene=(--set volume.procedural=none --set particles.procedural=layers
    --set particles.count=600 --set bricks.per_axis=2) ;;
  *) fail "unknown mode $mode" ;;
esac
start=$(date +%s.%N)
run_np 2 render -q -o "$WORK/f.png" --stats "$WORK/stats.json" "${small[@]}" "${scene[@]}" ||
  fail "$mode orbit of $frames frames"
python3 - "$WORK/stats.json" "$WORK/samples.json" "$frames" <<'PY' || fail "stats"
import json, sys
s = json.load(open(sys.argv[1]))
frames = s["frames"]
assert len(frames) == int(sys.argv[3]), len(frames)
assert all(len(f["rss_mb"]) == 2 and min(f["rss_mb"]) > 0 for f in frames)
json.dump({"x": [f["frame"] for f in frames], "rss_mb": [f["rss_mb"] for f in frames],
           "heap_mb": [f["heap_mb"] for f in frames]},
          open(sys.argv[2], "w"))
PY
python3 "$here/rss_slope.py" "$WORK/samples.json" "$warmup" "$bound" "render soak $mode" ||
  fail "resident memory grows over the orbit"
echo "render soak $mode: $frames frames in $(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f", b-a}') s"
