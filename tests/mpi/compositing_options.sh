#!/usr/bin/env bash
# The compositing options change what travels, never more of the frame than they promise:
# - overlap on/off (direct send): the identical frame;
# - RLE off: the identical frame, and more bytes sent;
# - rgba8 precision: within a stated bound of float, and fewer bytes for the swap strategies;
# - an .exr output holds the float frame, which rounds to the PNG frame within 1/255;
# - render.pipeline serial and overlapped (session/brick_stages.h): the identical frame on 3 ranks
#   (binary-swap folds one: the compositor reads the frame's order after the bricks' stage), and
#   --stats' stages consistent (each rank drew, the frame's draw time within its total).
# Usage: compositing_options.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
data=$2
scene=(render "$data/neghip.yaml" -q --set image.width=257 --set image.height=131 --set bricks.per_axis=3)

render() {  # render NAME NP OUT_EXT sortlast-args...
  local name=$1 np=$2 ext=$3; shift 3
  run_np "$np" "${scene[@]}" -o "$WORK/$name.$ext" --stats "$WORK/$name.json" "$@" || fail "render $name"
}
diff_at_most() {  # diff_at_most A B N: A's and B's frames within N/255
  "$SORTLAST" compare "$WORK/$1" "$WORK/$2" --max-diff "$3" >/dev/null ||
    fail "$1 vs $2 beyond $3/255: $("$SORTLAST" compare "$WORK/$1" "$WORK/$2")"
}
bytes() {  # total bytes sent by all ranks over all frames
  python3 -c 'import json,sys; s=json.load(open(sys.argv[1])); print(int(sum(sum(f["bytes_sent"]) for f in s["frames"])))' "$WORK/$1.json"
}

render overlap 4 png
render no_overlap 4 png --set compositing.overlap=false
diff_at_most overlap.png no_overlap.png 0

render no_rle 4 png --set compositing.rle=false
diff_at_most overlap.png no_rle.png 0
[ "$(bytes no_rle)" -gt "$(bytes overlap)" ] || fail "RLE off sent no more bytes than RLE on"

# Direct send in RGBA8 rounds after each of up to 3 x 3 bricks' blends along a ray: half a step
# each, so a few steps at most. The swap strategies round once per round (2 on 4 ranks).
render direct8 4 png --set compositing.precision=rgba8
diff_at_most overlap.png direct8.png 3
render bswap 4 png --set compositing.strategy=binary-swap
render bswap8 4 png --set compositing.strategy=binary-swap --set compositing.precision=rgba8
diff_at_most bswap.png bswap8.png 2
[ "$(bytes bswap8)" -lt "$(bytes bswap)" ] || fail "binary-swap rgba8 sent no fewer bytes than float"
"$SORTLAST" compare "$WORK/overlap.png" "$WORK/direct8.png" --max-diff 0 >/dev/null &&
  fail "rgba8 direct send gave the float frame exactly: the option does nothing here"

# EXR: the float frame, written opaque over the background like the PNG.
for s in direct binary-swap; do
  render "exr_$s" 4 exr --set compositing.strategy=$s
  diff_at_most overlap.png "exr_$s.exr" 1
done

for p in serial overlapped; do
  render "pipeline_$p" 3 png --set compositing.strategy=binary-swap --set render.pipeline=$p --set camera.orbit.frames=2
done
for f in 0000 0001; do diff_at_most "pipeline_serial_$f.png" "pipeline_overlapped_$f.png" 0; done
python3 - "$WORK/pipeline_overlapped.json" <<'PY' || fail "stages in --stats"
import json, sys
for f in json.load(open(sys.argv[1]))["frames"]:
    s = f["stages"]
    assert len(s["draw_s"]) == 3 and all(d > 0 for d in s["draw_s"]), s["draw_s"]
    assert 0 < s["frame_draw_s"] <= f["total_s"], (s["frame_draw_s"], f["total_s"])
    assert s["critical"] in ("draw", "issue", "readback", "encode", "exchange", "composite"), s["critical"]
    assert abs(s["outside_draw_s"] - (f["total_s"] - s["frame_draw_s"])) < 1e-9
PY
echo "overlap, RLE off, rgba8, EXR and the two pipelines behave as stated"
