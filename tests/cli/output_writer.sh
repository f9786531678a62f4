#!/usr/bin/env bash
# The batch render's output (io/frame_writer.h): the writer thread writes an orbit's frames under
# their own names, the same files --sync-output writes; .ppm and .jpg frames; and a write that
# fails mid-orbit (frame 2's name is a folder) stops both ranks with the file named, a non-zero
# exit and no hang, with the frames before it written and none after it.
# Usage: output_writer.sh SORTLAST
source "$(dirname "$0")/../mpi/lib.sh" "$1"
small=(--set image.width=96 --set image.height=64 --set "volume.dims=[32,32,32]" --set camera.orbit.frames=4
  --set camera.orbit.elevation=30)

run_np 2 render -q -o "$WORK/a.png" "${small[@]}" || fail "orbit with the writer thread"
run_np 2 render -q --sync-output -o "$WORK/s.png" "${small[@]}" || fail "orbit with --sync-output"
for i in 0000 0001 0002 0003; do
  "$SORTLAST" compare "$WORK/a_$i.png" "$WORK/s_$i.png" --max-diff 0 >/dev/null ||
    fail "frame $i: the writer thread's file differs from the synchronous one"
done

run_np 2 render -q -o "$WORK/p.ppm" "${small[@]}" --frames 1 || fail "PPM output"
"$SORTLAST" compare "$WORK/p.ppm" "$WORK/a_0000.png" --max-diff 0 >/dev/null || fail "PPM differs from PNG"
run_np 2 render -q -o "$WORK/j.jpg" "${small[@]}" --frames 1 || fail "JPEG output"
"$SORTLAST" compare "$WORK/j.jpg" "$WORK/a_0000.png" --min-psnr 35 >/dev/null || fail "JPEG far from PNG"

mkdir "$WORK/f_0002.png"
set +e
run_np 2 render -q -o "$WORK/f.png" "${small[@]}" 2>"$WORK/stderr"
rc=$?
set -e
[ "$rc" -ne 0 ] || fail "a failed write exited 0"
[ "$rc" -ne 124 ] || fail "a failed write hung (killed by timeout)"
grep -q "error: output $WORK/f_0002.png: cannot create" "$WORK/stderr" ||
  fail "the failed file is not named: $(cat "$WORK/stderr")"
[ -s "$WORK/f_0000.png" ] && [ -s "$WORK/f_0001.png" ] || fail "the frames before the failure are missing"
[ ! -e "$WORK/f_0003.png" ] || fail "a frame was written after the failed one"
echo "output writer ok"
