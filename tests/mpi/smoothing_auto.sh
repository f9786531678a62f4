#!/usr/bin/env bash
# particles.smoothing: auto (io/particles.h resolveAutoSmoothing): anisotropic kernels for SPH
# output (particles closer together than the kernel radius h), round metaballs for a sparse set;
# --stats names the choice and why; the image is the explicit choice's; ranks agree.
# Usage: smoothing_auto.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
DATA=$2
S=$SORTLAST
render() {  # render NP OUT ARGS...: image and stats in $WORK
  local np=$1 out=$2; shift 2
  run_np "$np" render -q -o "$WORK/$out.png" --stats "$WORK/$out.json" "$@" || fail "render $out on $np ranks: $*"
}
chosen() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['smoothing']['chosen'])" "$WORK/$1.json"; }
reason() { python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['smoothing']['reason'])" "$WORK/$1.json"; }
AUTO=(--set particles.smoothing=auto)

# 1. The SPH dam break (41 neighbours within h on average): anisotropic, on 1 and 2 ranks, the
# same image as asking for it.
render 1 dam_auto "$DATA/dam_break.yaml" "${AUTO[@]}"
[ "$(chosen dam_auto)" = anisotropic ] || fail "dam break: auto chose $(chosen dam_auto): $(reason dam_auto)"
reason dam_auto | grep -q "neighbours within h" || fail "dam break: reason lacks the count: $(reason dam_auto)"
echo "dam break: $(reason dam_auto)"
render 1 dam_aniso "$DATA/dam_break.yaml" --set particles.smoothing=anisotropic
"$S" compare "$WORK/dam_auto.png" "$WORK/dam_aniso.png" --max-diff 0 >/dev/null || fail "dam break: auto is not anisotropic's image"
render 2 dam_auto2 "$DATA/dam_break.yaml" "${AUTO[@]}"
[ "$(chosen dam_auto2)" = anisotropic ] || fail "dam break, 2 ranks: auto chose $(chosen dam_auto2)"
"$S" compare "$WORK/dam_auto.png" "$WORK/dam_auto2.png" --max-diff 1 >/dev/null || fail "dam break: 2 ranks differ from 1"
# An explicit choice stands, and says so.
render 1 dam_none "$DATA/dam_break.yaml" --set particles.smoothing=none
[ "$(chosen dam_none)" = none ] || fail "dam break: explicit none drew $(chosen dam_none)"
reason dam_none | grep -q "^set" || fail "dam break: explicit none's reason: $(reason dam_none)"
# With billboards (round only) auto gives none rather than an error.
render 1 dam_bill "$DATA/dam_break.yaml" "${AUTO[@]}" --set particles.method=billboards --set image.width=64 \
  --set image.height=64
[ "$(chosen dam_bill)" = none ] || fail "dam break, billboards: auto chose $(chosen dam_bill)"

# 2. A sparse procedural set (the splash at spacing 1.5 > h = 0.61: no neighbour within h):
# round metaballs, the same image as smoothing none.
sparse=("$DATA/flat_lattice.yaml" --set particles.procedural=splash --set particles.count=4096
        --set particles.spacing=1.5 --set camera.position=auto --set camera.look_at=auto
        --set camera.up=[0,1,0] --set image.width=128 --set image.height=128)
render 1 sparse_auto "${sparse[@]}" "${AUTO[@]}"
[ "$(chosen sparse_auto)" = none ] || fail "sparse splash: auto chose $(chosen sparse_auto): $(reason sparse_auto)"
echo "sparse splash: $(reason sparse_auto)"
render 1 sparse_none "${sparse[@]}" --set particles.smoothing=none
"$S" compare "$WORK/sparse_auto.png" "$WORK/sparse_none.png" --max-diff 0 >/dev/null || fail "sparse splash: auto is not none's image"
echo "smoothing auto: all checks passed"
