#!/usr/bin/env bash
# Binary-swap and radix-k give direct send's frame within 1/255 over MPI, on a 257x131 frame
# (no multiple of any rank count), with ranks that own only empty bricks (27 bricks: the sharp band
# leaves corner bricks empty) and with more ranks than bricks (1 brick). A rank with nothing to
# show sends nothing: checked on the per-rank bytes_sent of --stats. Every schedule of 1-8 ranks
# and k = 2-4 is checked on images in tests/unit/radix_k_test.cpp (ranks as threads); here one
# rank count per shape of schedule: binary-swap with no round (1 rank), one round (2), a fold
# before one round (3), before two (5), three rounds (8); radix-4 with a fold and a round of 4
# (5), rounds of 3 and 2 (6), a fold and rounds of 3 and 2 (7). Then `auto`: see below.
# Usage: strategies.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
data=$2
scene=(render "$data/neghip.yaml" -q --set image.width=257 --set image.height=131)

# Renders with NP ranks into $WORK/NAME.png and NAME.json.
render() {
  local name=$1 np=$2; shift 2
  run_np "$np" "${scene[@]}" -o "$WORK/$name.png" --stats "$WORK/$name.json" "$@" || fail "render $name"
}
# NAME's frame within 1/255 of REF's.
same() {
  "$SORTLAST" compare "$WORK/$1.png" "$WORK/$2.png" --max-diff 1 >/dev/null ||
    fail "$1 differs from $2: $("$SORTLAST" compare "$WORK/$1.png" "$WORK/$2.png")"
}
# Checks that every rank that rendered no brick sent no byte; prints how many such ranks there were.
quiet_ranks() {
  python3 - "$WORK/$1.json" <<'PY' || fail "a rank with nothing to show sent bytes in $1"
import json, sys
s = json.load(open(sys.argv[1]))
empty = 0
for f in s["frames"]:
    assert len(f["bytes_sent"]) == s["ranks"], f
    for r in range(s["ranks"]):
        if f["bricks_rendered"][r] == 0:
            empty += 1
            assert f["bytes_sent"][r] == 0, (r, f["bytes_sent"], f["bricks_rendered"])
print(empty)
PY
}

d3=(--set bricks.per_axis=3)
render direct_d3 1 "${d3[@]}"
empty_seen=0
for np in 1 2 3 5 8; do
  render bswap_np$np "$np" "${d3[@]}" --set compositing.strategy=binary-swap
  same bswap_np$np direct_d3
  empty_seen=$((empty_seen + $(quiet_ranks bswap_np$np)))
done
# On 1 and 2 ranks every radix makes binary-swap's schedule.
for np in 5 6 7; do
  render radixk_np$np "$np" "${d3[@]}" --set compositing.strategy=radix-k --set compositing.radix=4
  same radixk_np$np direct_d3
  empty_seen=$((empty_seen + $(quiet_ranks radixk_np$np)))
done
[ "$empty_seen" -gt 0 ] || fail "no rank owned only empty bricks: the case went untested"

# More ranks than bricks: one brick; the other ranks own nothing and send nothing.
d1=(--set bricks.per_axis=1)
render direct_d1 2 "${d1[@]}"
[ "$(quiet_ranks direct_d1)" -eq 1 ] || fail "direct send: rank 1 should own nothing"
render bswap_d1 2 "${d1[@]}" --set compositing.strategy=binary-swap
render radixk_d1 3 "${d1[@]}" --set compositing.strategy=radix-k --set compositing.radix=3
same bswap_d1 direct_d1
same radixk_d1 direct_d1
[ "$(quiet_ranks bswap_d1)" -eq 1 ] || fail "binary-swap: rank 1 should own nothing"
[ "$(quiet_ranks radixk_d1)" -eq 2 ] || fail "radix-k: ranks 1 and 2 should own nothing"

# auto: every rank makes the same choice, --stats says which and why, and the frame is the chosen
# strategy's to the bit. Two shapes that choose differently: 27 bricks on 3 ranks (rank 0 would
# decode all 27 under direct send: a swap strategy), one brick on 2 ranks (direct send).
# Prints the explicit --set options of the strategy auto chose in NAME.json.
chosen() {
  python3 - "$WORK/$1.json" <<'PY' || fail "auto's choice in $1"
import json, sys
s = json.load(open(sys.argv[1]))
c = s["frames"][0]["compositing"]
assert c["strategy"] == "auto" and c["same_on_every_rank"] is True, c
assert c["why"].startswith("forecast direct") and c["forecast_s"] > 0, c
label = c["chose"]
if label.startswith("radix-k k="):
    print(f"--set compositing.strategy=radix-k --set compositing.radix={label[10:]}")
else:
    assert label in ("direct", "binary-swap"), label
    print(f"--set compositing.strategy={label}")
PY
}
render auto_d3 3 "${d3[@]}" --set compositing.strategy=auto
read -r -a pick <<<"$(chosen auto_d3)"
[ "${pick[1]}" != compositing.strategy=direct ] || fail "auto chose direct send for 27 bricks on 3 ranks"
render picked_d3 3 "${d3[@]}" "${pick[@]}"
"$SORTLAST" compare "$WORK/auto_d3.png" "$WORK/picked_d3.png" --max-diff 0 >/dev/null ||
  fail "auto's frame differs from ${pick[*]}'s"
# The same messages too: strategies can make the same frame (binary-swap and radix-k on 3 ranks).
python3 - "$WORK/auto_d3.json" "$WORK/picked_d3.json" <<'PY' || fail "auto sent other bytes than ${pick[*]}"
import json, sys
a, b = (json.load(open(p))["frames"][0]["bytes_sent"] for p in sys.argv[1:])
assert a == b, (a, b)
PY
render auto_d1 2 "${d1[@]}" --set compositing.strategy=auto
[ "$(chosen auto_d1)" = "--set compositing.strategy=direct" ] || fail "auto: $(chosen auto_d1) for one brick"
"$SORTLAST" compare "$WORK/auto_d1.png" "$WORK/direct_d1.png" --max-diff 0 >/dev/null ||
  fail "auto's frame differs from direct send's"
echo "binary-swap and radix-k agree with direct send on 1-8 ranks; auto is its choice"
