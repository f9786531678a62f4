#!/usr/bin/env bash
# Movie output (-o NAME.mp4 / NAME.webm, io/movie_writer.h): an orbit of 240 frames at 64x48 on
# one rank is one H.264 file of 240 frames of that size (ffprobe counts the decoded frames); a
# short orbit as VP9 in WebM; an odd size padded to even; a legend drawn into a movie; an
# unknown container and an out-of-range quality refused by name. A time series (--steps) in one
# colour range (below).
# Usage: movie.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
data=$(realpath "$2")
command -v ffprobe >/dev/null || fail "ffprobe is missing (scripts/install-deps installs ffmpeg)"
small=(--set image.width=64 --set image.height=48 --set render.sample_spacing=1)
probe() {  # probe FILE: "codec,width,height,frames"
  ffprobe -v error -count_frames -select_streams v:0 \
    -show_entries stream=codec_name,width,height,nb_read_frames -of csv=p=0 "$1"
}
timeout 300 "$SORTLAST" render "$data/neghip.yaml" -q -o "$WORK/orbit.mp4" "${small[@]}" \
  --set camera.orbit.frames=240 || fail "240-frame orbit as mp4"
got=$(probe "$WORK/orbit.mp4")
[ "$got" = "h264,64,48,240" ] || fail "orbit.mp4: ffprobe says '$got', want 'h264,64,48,240'"
echo "ok: orbit.mp4: $got"

run_np 2 render "$data/neghip.yaml" -q -o "$WORK/orbit.webm" "${small[@]}" --set camera.orbit.frames=12 \
  --set movie.frame_rate=12 --set image.legend.position=right || fail "12-frame orbit as webm with a legend, 2 ranks"
got=$(probe "$WORK/orbit.webm")
[ "$got" = "vp9,64,48,12" ] || fail "orbit.webm: ffprobe says '$got', want 'vp9,64,48,12'"
echo "ok: orbit.webm: $got"

timeout 120 "$SORTLAST" render "$data/neghip.yaml" -q -o "$WORK/odd.mp4" --set image.width=63 --set image.height=47 \
  --set render.sample_spacing=1 --set camera.orbit.frames=3 || fail "odd size"
got=$(probe "$WORK/odd.mp4")
[ "$got" = "h264,64,48,3" ] || fail "odd.mp4: ffprobe says '$got', want 'h264,64,48,3' (padded to even)"
echo "ok: 63x47 padded to $got"

# A time series (--steps) with transfer.range: auto: three steps whose ranges differ ([0, 80],
# [10, 140], [20, 200]; the union [0, 200]) render with the union's colours: the union is in
# --stats, frame 1 equals step 1 rendered alone with transfer.range = the union (within 1/255)
# while step 1 alone in its own range differs (so the comparison can fail), and 3 ranks give 1
# rank's frames; the series as a movie has one frame per step, and with a 2-frame orbit the
# cameras go 0, 1, 0 (at 10 frames/s, where the last frame once went missing: its packet had no
# duration). A step beyond the series is refused naming --steps.
S=$WORK/steps
mkdir -p "$S"
python3 - "$S" <<'PY'
import sys
nx, ny, nz = 24, 20, 16
for k in range(3):
    base, peak = 10 * k, 80 + 60 * k  # every step's range differs; the slab is 40 in each
    data = bytearray(nx * ny * nz)
    for z in range(nz):
        for y in range(ny):
            for x in range(nx):
                d2 = (x - 6 - 5 * k) ** 2 + (y - 10) ** 2 + (z - 8) ** 2
                v = base
                if d2 < 25: v = peak - int((peak - 45) * d2 / 25)
                elif 3 <= z <= 4: v = 40
                data[x + nx * (y + ny * z)] = v
    open(f"{sys.argv[1]}/step_{k}.raw", "wb").write(bytes(data))
PY
printf 'volume:\n  files: "step_*.raw"\n  dims: [24, 20, 16]\n  type: uint8\ntransfer: {preset: ramp}\nimage: {width: 64, height: 48}\ncamera: {position: [40, 30, 50]}\nrender: {sample_spacing: 1}\n' >"$S/series.yaml"
for np in 1 3; do
  run_np $np render "$S/series.yaml" -q --steps all -o "$WORK/series$np.png" --stats "$WORK/series$np.json" \
    || fail "--steps all on $np rank(s)"
done
range=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["series_range"])' "$WORK/series1.json")
[ "$range" = "[0.0, 200.0]" ] || fail "series_range is $range, want [0.0, 200.0] (the union of the steps' ranges)"
for k in 0 1 2; do
  "$SORTLAST" compare "$WORK/series1_000$k.png" "$WORK/series3_000$k.png" --max-diff 1 >/dev/null \
    || fail "series frame $k: 3 ranks differ from 1 by more than 1/255"
done
# Step 1 (its own range [10, 140] is furthest from the union's) alone, in the union's range and in its own.
timeout 120 "$SORTLAST" render "$S/series.yaml" -q --set time.step=1 --set "transfer.range=[0, 200]" \
  -o "$WORK/alone_1.png" || fail "step 1 alone"
"$SORTLAST" compare "$WORK/alone_1.png" "$WORK/series1_0001.png" --max-diff 1 \
  || fail "series frame 1 differs from step 1 rendered alone with transfer.range [0, 200]"
timeout 120 "$SORTLAST" render "$S/series.yaml" -q --set time.step=1 -o "$WORK/own_1.png" || fail "step 1 alone"
"$SORTLAST" compare "$WORK/own_1.png" "$WORK/series1_0001.png" --max-diff 1 >/dev/null \
  && fail "step 1 with its own range [10, 140] looks like the series' frame: the test cannot tell the ranges apart"
echo "ok: a series of 3 steps has one colour range [0, 200] (1 and 3 ranks)"
run_np 1 render "$S/series.yaml" -q --steps 0:2 -o "$WORK/series.mp4" --set camera.orbit.frames=2 --set movie.frame_rate=10 \
  --stats "$WORK/orbit.json" || fail "--steps 0:2 as mp4 with an orbit"
got=$(probe "$WORK/series.mp4")
[ "$got" = "h264,64,48,3" ] || fail "series.mp4: ffprobe says '$got', want 'h264,64,48,3'"
python3 - "$WORK/orbit.json" <<'PY' || fail "--steps with an orbit: frame i is not step i seen by orbit camera i mod 2"
import json, sys
f = json.load(open(sys.argv[1]))["frames"]
cams = [json.dumps(x["camera"]["position"]) for x in f]
assert [x["step"] for x in f] == [0, 1, 2], [x["step"] for x in f]
assert cams[0] == cams[2] != cams[1], cams
PY
echo "ok: series.mp4: $got; steps 0, 1, 2 with orbit cameras 0, 1, 0"

expect_error() {  # expect_error "what" "message part" sortlast-args...
  local what=$1 want=$2; shift 2
  local rc=0
  timeout 120 "$SORTLAST" render "${ERR_SCENE:-$data/neghip.yaml}" -q "${small[@]}" "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: $what -> $(grep -m1 'error' "$WORK/stderr")"
}
expect_error "unknown container" "output $WORK/x.avi: no image writer" -o "$WORK/x.avi"
ERR_SCENE=$S/series.yaml expect_error "--steps beyond the series" \
  "--steps 0:5: step 5 is out of range: the scene has 3 time step(s), 0 ... 2" --steps 0:5 -o "$WORK/x.png"
expect_error "quality beyond H.264's range" "scene key 'movie.quality': 60 is outside libx264's CRF range [0, 51]" \
  -o "$WORK/q.mp4" --set movie.quality=60
