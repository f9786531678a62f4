#!/usr/bin/env bash
# Adaptive sampling rendered by the GL ray caster (adaptive.tolerance > 0, render.method=raycast):
# blocks at their own resolution, against the ray caster without it, the CPU reference of the
# original field and the CPU reference of the adaptive field itself (reference.field=adaptive).
# Usage: adaptive.sh SORTLAST DATA_DIR MODE
#   lossless   tolerance 0 is the non-adaptive path (neghip: bit-identical, no adaptive stats);
#              1e-6 % keeps every block lossless but runs the adaptive path (atlas, block table,
#              coarse steps in the few blocks that are exactly coarse): within 1/255 of the plain
#              ray caster; adaptive blocks as the skipping grid change no pixel (b = 8 vs one
#              block, adaptive.steps=fine so the sampling is the same) and shrink the brick
#              images; slicing with adaptive.tolerance > 0 is refused, naming both keys
#   tolerance  neghip at 10, 20, 40 %: data left (stats, and as adaptive-stats reports it)
#              falls strictly; PSNR against the reference of the original field falls (0.1 dB of
#              slack) and stays above a bound at 10 %
#   field      the GL image against the CPU reference of the adaptive field: with every lattice
#              step (adaptive.steps=fine) as close as the plain ray caster is to the plain
#              reference (0.5 dB); at the blocks' own resolution above a bound each, with the
#              scenes' sharp transfer functions (what fewer samples cost) and with a smooth one
#              (where the rule placing coarse samples along the ray is what shows); early ray
#              termination: 0.99 within 255 (1 - 0.99) + 2 of ERT off, and 0.9 acts
#   bricks     no seam at brick faces, where coarse samples are split between two bricks:
#              neghip (1, 2^3, 3^3 bricks) and Marschner-Lobb (1, 3^3) at 20 % (levels 0-3;
#              3^3 bricks cut blocks of 8 cells) give one image within the 2/255 of the RGBA8
#              brick images; Marschner-Lobb's 3^3 bricks give one image on 1-4 ranks (1/255)
# All renders at 0.5 voxel; ERT off unless said. Bounds are ~1.5 dB under the values measured on
# llvmpipe, given at each check.
source "$(dirname "$0")/lib.sh" "$1"
DATA=$2
S=$SORTLAST
BASE=(--set render.method=raycast --set render.sample_spacing=0.5 --set render.ert_threshold=1)

render() {  # render NP SCENE OUT [--set ...]
  local np=$1 scene=$2 out=$3; shift 3
  run_np "$np" render "$scene" -q -o "$out" "${BASE[@]}" "$@" || fail "render $(basename "$scene") $*"
}
reference() {  # reference SCENE OUT [--set ...]
  local scene=$1 out=$2; shift 2
  "$S" reference "$scene" -q -o "$out" "$@" || fail "reference $(basename "$scene") $*"
}
psnr_of() { "$S" compare "$1" "$2" | sed -n 's/^psnr_db=\([0-9.inf]*\).*/\1/p'; }
stat_of() {  # stat_of STATS.json KEY (top level) | STATS.json frames.KEY (first frame)
  python3 -c "
import json, sys
j = json.load(open(sys.argv[1])); k = sys.argv[2]
v = j['frames'][0][k[7:]] if k.startswith('frames.') else j.get(k)
print('none' if v is None else v)" "$1" "$2"
}
at_least() {  # at_least A B MESSAGE: A >= B
  python3 -c "import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) else 1)" "$1" "$2" || fail "$3"
}
plus() { python3 -c "import sys; print(float(sys.argv[1]) + float(sys.argv[2]))" "$1" "$2"; }

case $3 in
lossless)
  for name in neghip marschner_lobb; do
    scene=$DATA/$name.yaml
    render 1 "$scene" "$WORK/off.png"
    if [ $name = neghip ]; then
      render 1 "$scene" "$WORK/zero.png" --set adaptive.tolerance=0 --stats "$WORK/zero.json"
      "$S" compare "$WORK/off.png" "$WORK/zero.png" --max-diff 0 || fail "$name: tolerance 0 changed pixels"
      [ "$(stat_of "$WORK/zero.json" adaptive_data_left_percent)" = none ] ||
        fail "$name: tolerance 0 ran the adaptive path"
    fi
    # Measured: neghip 1 (88 dB), Marschner-Lobb 0 before issue 43; since the span's first and last
    # samples are read at their segments' middles (off the lattice, raycast_march.frag.glsl
    # sampleT), Marschner-Lobb 2/255 at 2 pixels (81.8 dB): the adaptive atlas's value there
    # rounds otherwise than the brick texture's (not traced further). 2/255 at up to 4 pixels.
    render 1 "$scene" "$WORK/tiny.png" --set adaptive.tolerance=1e-6 --stats "$WORK/tiny.json"
    [ "$(stat_of "$WORK/tiny.json" adaptive_data_left_percent)" != none ] ||
      fail "$name: tolerance 1e-6 did not run the adaptive path"
    "$S" compare "$WORK/off.png" "$WORK/tiny.png" --max-diff 2 >/dev/null &&
      "$S" compare "$WORK/off.png" "$WORK/tiny.png" --max-diff 1 --allow-pixels 4 ||
      fail "$name: the adaptive path at 1e-6 % differs from the plain ray caster by more than 1/255"
  done
  # Skipping on the adaptive blocks (neghip; b = 8: 512 blocks, most of them empty) against one
  # block for the volume (nothing skipped inside a brick). Both lossless, every lattice step.
  scene=$DATA/neghip.yaml
  fine=(--set adaptive.tolerance=1e-6 --set adaptive.steps=fine)
  render 1 "$scene" "$WORK/b1.png" "${fine[@]}" --set adaptive.blocks=1 --stats "$WORK/b1.json"
  render 1 "$scene" "$WORK/b8.png" "${fine[@]}" --set adaptive.blocks=8 --stats "$WORK/b8.json"
  "$S" compare "$WORK/b1.png" "$WORK/b8.png" --max-diff 1 || fail "neghip: skipping adaptive blocks changed pixels"
  small=$(stat_of "$WORK/b8.json" frames.bytes_raw) whole=$(stat_of "$WORK/b1.json" frames.bytes_raw)
  # Measured: 116,096 vs 152,980 bytes.
  at_least "$(python3 -c "print(0.9 * $whole)")" "$small" \
    "neghip: adaptive blocks did not shrink the brick images ($small vs $whole bytes)"
  echo "neghip: skipping on adaptive blocks: brick images $small bytes, $whole with one block"
  if run_np 1 render "$scene" -q -o "$WORK/x.png" --set adaptive.tolerance=10 2>"$WORK/err.txt"; then
    fail "slicing with adaptive.tolerance > 0 was accepted"
  fi
  grep -q "adaptive.tolerance.*render.method" "$WORK/err.txt" || fail "the refusal names not both keys: $(cat "$WORK/err.txt")"
  ;;
tolerance)
  scene=$DATA/neghip.yaml
  reference "$scene" "$WORK/ref.png"
  prev_left=101 prev_psnr=1000
  # Measured: data left 62.1 / 40.5 / 23.9 %, PSNR 27.9 / 23.5 / 17.2 dB (the plain ray caster:
  # 34.0 dB; 5 %: 83.0 %, 33.3 dB).
  for t in 10 20 40; do
    render 1 "$scene" "$WORK/t$t.png" --set adaptive.tolerance=$t --stats "$WORK/t$t.json"
    left=$(stat_of "$WORK/t$t.json" adaptive_data_left_percent)
    p=$(psnr_of "$WORK/t$t.png" "$WORK/ref.png")
    echo "neghip at $t %: data left $left %, $p dB against the reference"
    at_least "$prev_left" "$(plus "$left" 1e-9)" "data left did not fall at $t % ($prev_left -> $left)"
    at_least "$(plus "$prev_psnr" 0.1)" "$p" "PSNR rose at $t % ($prev_psnr -> $p dB)"
    prev_left=$left prev_psnr=$p
    [ "$t" = 10 ] && { at_least "$p" 26.5 "neghip at 10 %: $p dB < 26.5 dB against the reference"; }
    stats_left=$("$S" adaptive-stats "$scene" --set adaptive.tolerance=$t |
      python3 -c "import json, sys; print(json.load(sys.stdin)['data_left_percent'])")
    python3 -c "import sys; sys.exit(abs(float(sys.argv[1]) - float(sys.argv[2])) > 1e-9)" "$left" "$stats_left" ||
      fail "render stats say $left % left, adaptive-stats $stats_left %"
  done
  ;;
field)
  # The scenes' own (sharp) transfer functions. Every lattice step: the adaptive field's lookup,
  # as close as the plain ray caster is to the plain reference (measured: neghip 10 %: 34.2 vs
  # 34.0 dB; Marschner-Lobb 20 %: 46.7 vs 43.0 dB). Own resolution: what the fewer samples cost
  # where a narrow opacity band varies faster than a coarse block's samples (measured 32.0 and
  # 26.3 dB; halving the spacing, Marschner-Lobb gives 39.0 and 49.4 dB: the rule converges).
  for spec in "neghip 10 30.5" "marschner_lobb 20 24.8"; do
    read -r name t min_own <<<"$spec"
    scene=$DATA/$name.yaml
    reference "$scene" "$WORK/ref.png"
    render 1 "$scene" "$WORK/plain.png"
    plain=$(psnr_of "$WORK/plain.png" "$WORK/ref.png")
    reference "$scene" "$WORK/aref.png" --set adaptive.tolerance=$t --set reference.field=adaptive
    render 1 "$scene" "$WORK/fine.png" --set adaptive.tolerance=$t --set adaptive.steps=fine
    render 1 "$scene" "$WORK/own.png" --set adaptive.tolerance=$t
    fine=$(psnr_of "$WORK/fine.png" "$WORK/aref.png") own=$(psnr_of "$WORK/own.png" "$WORK/aref.png")
    echo "$name at $t %: against the adaptive field's reference: every step $fine dB, own resolution $own dB (plain ray caster vs reference: $plain dB)"
    at_least "$fine" "$(plus "$plain" -0.5)" "$name at $t %: every step gives $fine dB, the plain ray caster $plain dB"
    at_least "$own" "$min_own" "$name at $t %: own resolution gives $own dB < $min_own dB"
  done
  # A smooth transfer function (opacity and colour linear in the value): there the coarse
  # blocks' samples suffice, and the rule for where they stand along the ray is what shows: a
  # gap or an overlap of a few steps at each block entry costs 8-16 dB. Own resolution at 20 %
  # against the adaptive field's reference (measured: neghip 54.7 dB, every step 58.6;
  # Marschner-Lobb 46.0, every step 46.5).
  ramp=(--set "transfer.points=[[0,0,0,0,0],[1,1,0.8,0.6,0.5]]" --set adaptive.tolerance=20)
  for spec in "neghip 53" "marschner_lobb 44.5"; do
    read -r name min_own <<<"$spec"
    scene=$DATA/$name.yaml
    reference "$scene" "$WORK/aref.png" "${ramp[@]}" --set reference.field=adaptive
    render 1 "$scene" "$WORK/own.png" "${ramp[@]}"
    own=$(psnr_of "$WORK/own.png" "$WORK/aref.png")
    echo "$name at 20 %, smooth transfer function: own resolution $own dB against the adaptive field's reference"
    at_least "$own" "$min_own" "$name, smooth transfer function: own resolution gives $own dB < $min_own dB"
  done
  # Early ray termination on the adaptive path (neghip at 10 %; measured: 0.99 changes at most
  # 2, 0.9 up to 25).
  scene=$DATA/neghip.yaml
  q=(--set adaptive.tolerance=10)
  render 1 "$scene" "$WORK/e100.png" "${q[@]}"
  render 1 "$scene" "$WORK/e99.png" "${q[@]}" --set render.ert_threshold=0.99
  render 1 "$scene" "$WORK/e90.png" "${q[@]}" --set render.ert_threshold=0.9
  "$S" compare "$WORK/e100.png" "$WORK/e99.png" --max-diff 4 || fail "adaptive: ERT 0.99 changed a pixel by more than 4"
  "$S" compare "$WORK/e100.png" "$WORK/e90.png" --max-diff 27 || fail "adaptive: ERT 0.9 changed a pixel by more than 27"
  if "$S" compare "$WORK/e100.png" "$WORK/e90.png" --max-diff 10 >/dev/null; then
    fail "adaptive: ERT 0.9 changed no pixel by more than 10: early termination does not act"
  fi
  ;;
bricks)
  # Measured: d = 2, 3 against d = 1: neghip at most 2/255 (59.6 and 64.3 dB), Marschner-Lobb
  # bit-identical; 1-4 ranks: bit-identical. Reading a coarse sample beyond its block (no clamp
  # in the shader's lookup) broke d = 2 by 63/255 in 134 pixels.
  t20=(--set adaptive.tolerance=20)
  for d in 1 2 3; do render 2 "$DATA/neghip.yaml" "$WORK/neghip$d.png" "${t20[@]}" --set bricks.per_axis=$d; done
  render 2 "$DATA/marschner_lobb.yaml" "$WORK/ml1.png" "${t20[@]}" --set bricks.per_axis=1
  for np in 1 2 3 4; do render "$np" "$DATA/marschner_lobb.yaml" "$WORK/np$np.png" "${t20[@]}"; done
  for pair in neghip1:neghip2 neghip1:neghip3 ml1:np1; do
    "$S" compare "$WORK/${pair%%:*}.png" "$WORK/${pair##*:}.png" --max-diff 2 --min-psnr 55 \
      --diff "$WORK/diff.png" || fail "seam: ${pair##*:} differs from ${pair%%:*}"
  done
  for np in 2 3 4; do
    "$S" compare "$WORK/np1.png" "$WORK/np$np.png" --max-diff 1 || fail "adaptive: $np ranks differ from 1 rank"
  done
  ;;
*) fail "unknown mode $3" ;;
esac
echo "adaptive $3: ok"
