#!/usr/bin/env bash
# Movie output (-o NAME.mp4 / NAME.webm, io/movie_writer.h): an orbit of 240 frames at 64x48 on
# one rank is one H.264 file of 240 frames of that size (ffprobe counts the decoded frames); a
# short orbit as VP9 in WebM; an odd size padded to even; a legend drawn into a movie; an
# unknown container and an out-of-range quality refused by name.
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

expect_error() {  # expect_error "what" "message part" sortlast-args...
  local what=$1 want=$2; shift 2
  local rc=0
  timeout 120 "$SORTLAST" render "$data/neghip.yaml" -q "${small[@]}" "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: $what -> $(grep -m1 'error' "$WORK/stderr")"
}
expect_error "unknown container" "output $WORK/x.avi: no image writer" -o "$WORK/x.avi"
expect_error "quality beyond H.264's range" "scene key 'movie.quality': 60 is outside libx264's CRF range [0, 51]" \
  -o "$WORK/q.mp4" --set movie.quality=60
