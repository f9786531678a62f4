#!/usr/bin/env bash
# The same scene on 1, 2, 3 and 4 ranks gives the same image within 1/255 per channel.
# Usage: ranks_agree.sh SORTLAST SCENE|default [--set key=value ...]
source "$(dirname "$0")/lib.sh" "$1"
scene=$2; shift 2
[ "$scene" = default ] && scene=()  # the built-in default scene
for np in 1 2 3 4; do
  run_np "$np" render "${scene[@]}" -q -o "$WORK/np$np.png" "$@" || fail "render with $np ranks"
done
for np in 2 3 4; do
  "$SORTLAST" compare "$WORK/np1.png" "$WORK/np$np.png" --max-diff 1 || fail "$np ranks differ from 1 rank"
done
echo "ranks 1-4 agree"
