#!/usr/bin/env bash
# transfer.colormap through the whole program: neghip at 96x96 coloured by viridis gives the same
# image on 1 and 2 ranks (1/255), agrees with the CPU reference of the same key, and differs from
# the uncoloured reference (so the key is not ignored by both); a preset file named relative to
# the scene file gives the built-in's image exactly; bad maps end every rank with the message.
# Usage: colormap.sh SORTLAST DATA_DIR COLORMAPS_DIR
source "$(dirname "$0")/lib.sh" "$1"
data=$(realpath "$2") maps=$(realpath "$3")
SORTLAST=$(realpath "$SORTLAST")  # the preset-file case runs from another directory
# Measured on llvmpipe at 0.25 voxel: 38.9 dB against the reference (17.0 dB between the
# references with and without the map).
MIN_PSNR=37.4
common=(--set image.width=96 --set image.height=96 --set render.sample_spacing=0.25)

timeout 120 "$SORTLAST" render "$data/neghip.yaml" -q -o "$WORK/np1.png" "${common[@]}" --set transfer.colormap=viridis || fail "render, 1 rank"
run_np 2 render "$data/neghip.yaml" -q -o "$WORK/np2.png" "${common[@]}" --set transfer.colormap=viridis || fail "render, 2 ranks"
"$SORTLAST" compare "$WORK/np1.png" "$WORK/np2.png" --max-diff 1 || fail "1 and 2 ranks differ"
"$SORTLAST" reference "$data/neghip.yaml" -q -o "$WORK/ref.png" "${common[@]}" --set transfer.colormap=viridis || fail "reference"
"$SORTLAST" compare "$WORK/np2.png" "$WORK/ref.png" --min-psnr "$MIN_PSNR" || fail "below $MIN_PSNR dB against the reference"
"$SORTLAST" reference "$data/neghip.yaml" -q -o "$WORK/ref_plain.png" "${common[@]}" || fail "reference without a map"
"$SORTLAST" compare "$WORK/np2.png" "$WORK/ref_plain.png" --min-psnr 25 >/dev/null \
  && fail "the coloured image is as close to the uncoloured reference as to its own: the map did nothing"
echo "ok: viridis on 1 and 2 ranks, against the reference"

# A ParaView preset file beside the scene (a copy of the built-in), picked by name.
mkdir -p "$WORK/maps"
cp "$maps/viridis.json" "$WORK/maps/mine.json"
sed -e "s|file: neghip_64x64x64_uint8.raw|file: $data/neghip_64x64x64_uint8.raw|" \
  -e "s|^  preset: sharp$|  preset: sharp\n  colormap: maps/mine.json#Viridis (matplotlib)|" "$data/neghip.yaml" >"$WORK/scene.yaml"
grep -q "colormap: maps/mine.json" "$WORK/scene.yaml" || fail "scene copy: neghip.yaml has changed, adapt the sed lines"
(cd / && run_np 2 render "$WORK/scene.yaml" -q -o "$WORK/file.png" "${common[@]}") || fail "render with the preset file"
"$SORTLAST" compare "$WORK/np2.png" "$WORK/file.png" --max-diff 0 || fail "the preset file's image differs from the built-in's"
echo "ok: preset file relative to the scene file"

# Bad maps: on 2 ranks once (every rank must end, none hang), then on 1 (mpirun is slow to start).
expect_error() {  # expect_error RANKS "what" "message part" sortlast-args...
  local np=$1 what=$2 want=$3; shift 3
  local rc=0
  local launch=(run_np "$np"); [ "$np" = 1 ] && launch=(timeout 120 "$SORTLAST")
  "${launch[@]}" render "$data/neghip.yaml" -q -o "$WORK/out.png" "${common[@]}" "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: $what -> $(grep -m1 'sortlast: error' "$WORK/stderr")"
}
printf '[{"Name": "x", "RGBPoints": [0, 0, 0, 0, 1, 1, 1' >"$WORK/broken.json"
expect_error 2 "malformed JSON" "scene key 'transfer.colormap': colour-map file $WORK/broken.json: not valid JSON" \
  --set transfer.colormap="$WORK/broken.json"
printf '{"RGBPoints": [0, 0, 0, 0, 1, 1, 1, 1], "ColorSpace": "Step"}' >"$WORK/step.json"
expect_error 1 "unknown colour space" "$WORK/step.json: unknown ColorSpace \"Step\"" --set transfer.colormap="$WORK/step.json"
expect_error 1 "missing file" "colour-map file $WORK/none.json: cannot open" --set transfer.colormap="$WORK/none.json"
expect_error 1 "unknown name" "unknown colour map 'viridiss' (built in: " --set transfer.colormap=viridiss
