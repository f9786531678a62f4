#!/usr/bin/env bash
# Memory bounds in the service: a frame request for an image within --max-size but
# beyond the memory a rank may use, and POST /api/load of a scene whose volume cannot fit, are
# refused at once (400) with the estimate and the budget; the service goes on serving.
# Usage: memory_bounds.sh SORTLAST DATA_DIR
source "$(dirname "$0")/service_lib.sh" "$1"
DATA=${2:?usage: memory_bounds.sh SORTLAST DATA_DIR}
D=$WORK/scenes
mkdir -p "$D"
cp "$DATA/neghip_64x64x64_uint8.raw" "$DATA/neghip.yaml" "$D/"
# 1.25 x 10^11 samples: 500 GB of floats per copy. A loaded scene has no --set keys, so its
# budget is the machine's (90% of MemAvailable shared by the node's ranks).
printf 'volume:\n  procedural: sphere\n  dims: [5000, 5000, 5000]\n' >"$D/huge.yaml"
start_server 2 -q --data-dir "$D" neghip.yaml --max-size 32768 --set limits.memory_mib=2048
good='{"image.width":64,"image.height":64}'
code=$(frame "$WORK/a.png" "$good")
[ "$code" = 200 ] || fail "first frame answered $code"

# 20000 x 20000 is within --max-size but needs > 2 GiB of image targets on a rank.
t0=$(date +%s.%N)
code=$(frame "$WORK/big.json" '{"image.width":20000,"image.height":20000}')
t1=$(date +%s.%N)
msg=$(json "$WORK/big.json" 'j["error"]' 2>/dev/null) || msg=
[ "$code" = 400 ] || fail "a 20000^2 frame answered $code: $(head -c 300 "$WORK/big.json")"
[[ "$msg" == *"needs about"*"image targets (20000 x 20000)"*"2048 MiB (limits.memory_mib)"* ]] ||
  fail "the refusal does not name the need and the budget: $msg"
echo "20000^2 frame refused in $(python3 -c "print(f'{$t1 - $t0:.2f}')") s: $msg"

t0=$(date +%s.%N)
code=$(curl -s --max-time 20 -o "$WORK/load.json" -w '%{http_code}' -X POST --data-binary '{"scene":"huge.yaml"}' "$BASE/api/load") || true
t1=$(date +%s.%N)
msg=$(json "$WORK/load.json" 'j["error"]' 2>/dev/null) || msg=
[ "$code" = 400 ] || fail "loading huge.yaml answered $code: $(head -c 300 "$WORK/load.json")"
[[ "$msg" == *"needs about"*"bricks' samples"*"MemAvailable"* ]] ||
  fail "the load refusal does not name the need and the budget: $msg"
echo "huge.yaml load refused in $(python3 -c "print(f'{$t1 - $t0:.2f}')") s: $msg"

# Still serving (the scene loaded before, or none: either way an answer, not a dead service).
code=$(frame "$WORK/after.png" "$good")
[ "$code" = 200 ] || [ "$code" = 409 ] || fail "after the refusals a frame answered $code"
echo "after the refusals a frame answered $code"
echo "memory bounds (serve) passed"
