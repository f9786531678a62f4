#!/usr/bin/env bash
# What a user gets: an orbit writes a numbered series with progress lines; --stats writes one JSON
# object per frame with per-rank timings and byte counts, and each rank's GL identity (ranks_gl); --quiet is quiet; EXR output works.
# Usage: outputs.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
small=(--set image.width=96 --set image.height=64 --set "volume.dims=[48,48,48]")

run_np 2 render -o "$WORK/orbit.png" --stats "$WORK/stats.json" --set camera.orbit.frames=3 \
  --set camera.orbit.elevation=30 "${small[@]}" 2>"$WORK/stderr" || fail "orbit render"
for i in 0000 0001 0002; do [ -s "$WORK/orbit_$i.png" ] || fail "orbit_$i.png missing"; done
[ ! -e "$WORK/orbit.png" ] || fail "a series must not write the plain name"
grep -q "frame 3 of 3" "$WORK/stderr" || fail "no progress line"
python3 - "$WORK/stats.json" <<'PY' || fail "stats JSON"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["ranks"] == 2 and len(s["frames"]) == 3, s
for f in s["frames"]:
    for k in ("render_s", "encode_s", "transfer_s", "peak_rss_mb"):
        assert len(f[k]) == 2 and all(v >= 0 for v in f[k]), (k, f[k])
    assert 0 < f["bytes_rle"] < f["bytes_raw"], f
    assert abs(f["rle_ratio"] - f["bytes_rle"] / f["bytes_raw"]) < 1e-9
    assert f["total_s"] > 0 and f["composite_s"] >= 0
    assert sum(f["bricks_rendered"]) + sum(f["bricks_skipped"]) == 8
# Where each rank rendered: every rank's GL identity, gathered on rank 0, in rank order.
import socket
g = s["ranks_gl"]
assert [r["rank"] for r in g] == [0, 1], g
for r in g:
    assert r["backend"] == "osmesa" and r["device"] == -1 and r["renderer"] and r["vendor"], r
    assert r["host"] == socket.gethostname(), (r["host"], socket.gethostname())
print("stats ok:", len(s["frames"]), "frames")
PY
# The orbit's frames differ from each other (the camera moves).
if "$SORTLAST" compare "$WORK/orbit_0000.png" "$WORK/orbit_0001.png" --max-diff 0 >/dev/null; then
  fail "orbit frames 0 and 1 are identical"
fi

run_np 1 render -q -o "$WORK/quiet.png" "${small[@]}" 2>"$WORK/stderr" || fail "quiet render"
[ ! -s "$WORK/stderr" ] || fail "--quiet printed: $(cat "$WORK/stderr")"

run_np 2 render -q -o "$WORK/frame.exr" "${small[@]}" || fail "EXR render"
"$SORTLAST" compare "$WORK/frame.exr" "$WORK/quiet.png" --max-diff 1 || fail "EXR differs from PNG"

# Empty bricks are skipped and counted: a transfer function that is transparent below 0.9 hides
# every brick of the 'sphere' field whose values stay under 0.9 (all but the centre ones).
run_np 2 render -q -o "$WORK/skip.png" --stats "$WORK/skip.json" --set volume.procedural=sphere \
  --set "transfer.points=[[0,0,0,0,0],[0.9,1,1,1,0],[1,1,1,1,1]]" --set bricks.per_axis=4 \
  "${small[@]}" || fail "skip render"
python3 - "$WORK/skip.json" <<'PY' || fail "skipped bricks not counted"
import json, sys
f = json.load(open(sys.argv[1]))["frames"][0]
# Only the 8 bricks touching the centre reach values >= 0.9.
assert sum(f["bricks_rendered"]) == 8 and sum(f["bricks_skipped"]) == 56, f
print("skip ok")
PY
# --psnr: each frame's PSNR against the reference, as `compare` reports it on the written files.
data=$(dirname "$0")/../data
run_np 3 render -q -o "$WORK/psnr.png" --stats "$WORK/psnr.json" --psnr "$data/neghip.yaml" \
  || fail "render --psnr"
"$SORTLAST" reference -q -o "$WORK/psnr_ref.png" "$data/neghip.yaml" || fail "reference"
want=$("$SORTLAST" compare "$WORK/psnr.png" "$WORK/psnr_ref.png" | sed 's/psnr_db=\([^ ]*\).*/\1/')
python3 - "$WORK/psnr.json" "$want" <<'PY' || fail "--psnr in stats disagrees with compare"
import json, sys
f = json.load(open(sys.argv[1]))["frames"][0]
want = float(sys.argv[2])
assert abs(f["psnr_db"] - want) < 0.01, (f["psnr_db"], want)
assert f["max_diff"] > 0 and f["reference_s"] > 0, f
print("psnr ok:", f["psnr_db"], "dB")
PY
echo "outputs ok"
