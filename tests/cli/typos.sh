#!/usr/bin/env bash
# A mistyped subcommand or option is named with the nearest real one, exits non-zero, and starts
# no MPI job (the command line is parsed before MPI_Init). Usage: typos.sh SORTLAST
set -uo pipefail
sl=$1
fail=0
expect() {  # expect "ARGS" "TEXT": the error names TEXT
  local out rc
  out=$($sl $1 2>&1); rc=$?
  if [ $rc -eq 0 ] || ! grep -qF -- "$2" <<<"$out"; then
    echo "FAIL: sortlast $1 (exit $rc) should say: $2"; echo "  got: $out"; fail=1
  else
    echo "ok: sortlast $1 -> $out"
  fi
}
expect "rendr" "unknown subcommand 'rendr'; did you mean 'render'?"
expect "refrence" "did you mean 'reference'?"
expect "xyzzy" "unknown subcommand 'xyzzy' (sortlast --help lists them)"
expect "render --sett volume.dims=[8,8,8]" "unknown option '--sett' for 'render'; did you mean '--set'?"
expect "serve --listn 127.0.0.1:1" "did you mean '--listen'?"
expect "render -np 2" "unknown option '-np' for 'render' (sortlast render --help lists them)"
# Errors of another kind keep CLI11's own message.
expect "render -o" "--output: 1 required TEXT missing"
$sl render --help >/dev/null || { echo "FAIL: render --help exits non-zero"; fail=1; }
[ $fail -eq 0 ] && echo "typos: every mistyped word named with its nearest match"
exit $fail
