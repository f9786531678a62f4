#!/usr/bin/env bash
# The fixed scene set (render_set.sh) against tests/golden/expected, value by value in float.
# On the machine the set was recorded on (Debian 12's Mesa llvmpipe on an AVX-512 x86-64) every
# value must be identical: a change that should not change behaviour (a restructure,
# a refactor) is caught to the last bit. llvmpipe compiles its shaders for the CPU it runs on, so
# another CPU may round a few values differently; such a run passes only within a fallback bound
# stated below (2/255 per value, at most 0.5 % of an image's values beyond it) and says that it is
# not bit-identical. A real change of a renderer moves far more values than that.
# Usage: check.sh SORTLAST INSITU_DRIVER DATA_DIR [EXPECTED_DIR]
#   UPDATE=1 check.sh ...   records the set into EXPECTED_DIR instead (after an intended change).
set -euo pipefail
SL=$(realpath "$1")
HERE=$(cd "$(dirname "$0")" && pwd)
EXPECTED=${4:-$HERE/expected}
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
bash "$HERE/render_set.sh" "$SL" "$2" "$3" "$OUT/set" > "$OUT/log" 2>&1 || { cat "$OUT/log"; exit 1; }
if [ "${UPDATE:-0}" = 1 ]; then
  rm -rf "$EXPECTED" && mkdir -p "$EXPECTED" && cp "$OUT"/set/* "$EXPECTED"/
  echo "recorded $(ls "$EXPECTED" | wc -l) files into $EXPECTED"
  exit 0
fi
diff <(cd "$EXPECTED" && ls) <(cd "$OUT/set" && ls) || { echo "FAIL: the set's files differ from $EXPECTED"; exit 1; }
identical=0 close=0 failed=0
for f in "$EXPECTED"/*; do
  name=$(basename "$f")
  case "$name" in
    *.png) strict=("$SL" compare "$f" "$OUT/set/$name" --max-diff 0)
           loose=("$SL" compare "$f" "$OUT/set/$name" --max-diff 2 --allow-pixels $((96 * 96 / 200))) ;;
    *) strict=("$SL" compare --float "$f" "$OUT/set/$name")
       loose=("$SL" compare --float "$f" "$OUT/set/$name" --abs 0.0078431 --allow-values $((96 * 96 * 4 / 200))) ;;
  esac
  if "${strict[@]}" > "$OUT/cmp" 2>&1; then
    identical=$((identical + 1))
  elif "${loose[@]}" > "$OUT/cmp_loose" 2>&1; then
    close=$((close + 1))
    echo "NOT BIT-IDENTICAL (within the fallback bound): $name: $(head -1 "$OUT/cmp")"
  else
    failed=$((failed + 1))
    echo "FAIL: $name: $(cat "$OUT/cmp_loose")"
  fi
done
echo "golden set: $identical identical, $close within the fallback bound, $failed failed"
[ "$failed" = 0 ]
