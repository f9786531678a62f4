#!/usr/bin/env bash
# The examples in docs/service.md work: starts the servers the docs start (the ```sh blocks whose
# first line is "# server for the examples" / "# server for the data-dir examples", on a free port
# instead of 8080) and runs every block whose first line is "# test[: [data-dir] [expect "REGEX"]]"
# (```sh with bash -e -o pipefail, ```js with node) against them, with 127.0.0.1:8080 replaced by
# the real address. Each must exit 0 within 60 s, and print a line matching REGEX when given.
# Blocks run in a scratch folder where build/sortlast is the binary under test and tests/ the
# repository's tests folder (the docs' paths are relative to the repository root).
# Usage: docs_examples.sh SORTLAST DOCS_MD
source "$(dirname "$0")/service_lib.sh" "$1"
DOC=${2:?usage: docs_examples.sh SORTLAST DOCS_MD}
REPO=$(cd "$HERE/../.." && pwd)
RUN=$WORK/run
mkdir -p "$RUN/build"
ln -s "$(readlink -f "$SORTLAST")" "$RUN/build/sortlast"
ln -s "$REPO/tests" "$RUN/tests"
[ -d "$HERE/node_modules" ] && ln -s "$HERE/node_modules" "$RUN/node_modules"
# The docs' mpirun lines as written, on this machine (root, 2 cores, no CMA).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

# Split the docs into numbered block files: $WORK/blocks/N.{sh,js} and N.meta (kind, options).
python3 - "$DOC" "$WORK/blocks" <<'PY'
import os, re, sys
doc, out = sys.argv[1], sys.argv[2]
os.makedirs(out)
lines = open(doc).read().split("\n")
n, i = 0, 0
while i < len(lines):
    m = re.match(r"^\s*```(sh|bash|js|javascript)\s*$", lines[i])
    if not m:
        i += 1
        continue
    indent = len(lines[i]) - len(lines[i].lstrip())
    lang = "js" if m.group(1).startswith("j") else "sh"
    body = []
    i += 1
    while i < len(lines) and lines[i].strip() != "```":
        body.append(lines[i][indent:])
        i += 1
    i += 1
    first = body[0].strip() if body else ""
    t = re.match(r"^(#|//) test(?::\s*(.*))?$", first)
    s = re.match(r"^# server for the (data-dir )?examples", first)
    if not (t or s):
        continue
    if s:
        kind, server, expect = "server", "data-dir" if s.group(1) else "plain", ""
    else:
        opts = t.group(2) or ""
        server = "data-dir" if re.search(r"\bdata-dir\b", opts) else "plain"
        e = re.search(r'expect\s+"((?:[^"\\]|\\.)*)"', opts)
        kind, expect = "test", (e.group(1) if e else "")
    open(f"{out}/{n}.{lang}", "w").write("\n".join(body[1:]) + "\n")
    open(f"{out}/{n}.meta", "w").write(f"{kind}\n{server}\n{lang}\n{expect}\n")
    n += 1
print(n)
PY

declare -A SERVER_CMD
for meta in "$WORK"/blocks/*.meta; do
  mapfile -t m <"$meta"
  [ "${m[0]}" = server ] && SERVER_CMD[${m[1]}]=${meta%.meta}.sh
done
[ -n "${SERVER_CMD[plain]:-}" ] || fail "docs: no block starting with '# server for the examples'"

# start_doc_server KIND: the docs' command, its --listen replaced by a free port, run from $RUN.
CURRENT=
start_doc_server() {
  [ "$CURRENT" = "$1" ] && return 0
  stop_server || fail "a docs server did not stop on SIGTERM"
  local cmd
  cmd=$(sed -e 's/--listen [^ ]*//' -e 's/\\$//' "${SERVER_CMD[$1]}" | tr '\n' ' ')
  # "mpirun ... build/sortlast serve ARGS": keep the rank count and the serve arguments
  local np args
  np=$(grep -o -- '-np [0-9]*' <<<"$cmd" | awk '{print $2}')
  args=$(sed 's/.*build\/sortlast serve//' <<<"$cmd")
  echo "server ($1): mpirun -np $np sortlast serve$args --listen 127.0.0.1:0"
  # shellcheck disable=SC2086
  start_server "$np" $args
  CURRENT=$1
}

cd "$RUN"  # the docs' relative paths (build/sortlast, tests/data) resolve here
failures=() count=0
for meta in $(ls "$WORK"/blocks/*.meta | sort -V); do
  mapfile -t m <"$meta"
  [ "${m[0]}" = test ] || continue
  server=${m[1]} lang=${m[2]} expect=${m[3]:-}
  [ -n "${SERVER_CMD[$server]:-}" ] || { failures+=("$(basename "$meta"): no server block for $server examples"); continue; }
  if [ "$lang" = js ] && { ! command -v node >/dev/null || [ ! -d "$HERE/node_modules/ws" ]; }; then
    echo "--- example $(basename "$meta" .meta).js: SKIPPED (node or the ws package missing)"
    continue
  fi
  start_doc_server "$server"
  block=${meta%.meta}.$lang
  sed -i "s/127\.0\.0\.1:8080/127.0.0.1:$PORT/g; s/localhost:8080/127.0.0.1:$PORT/g" "$block"
  count=$((count + 1))
  echo "--- example $(basename "$block") ($server server)"
  sed 's/^/    /' "$block"
  rc=0
  if [ "$lang" = js ]; then
    cp "$block" "$RUN/example.mjs"
    timeout 60 node example.mjs >"$WORK/out.txt" 2>&1 || rc=$?
  else
    timeout 60 bash -e -o pipefail "$block" >"$WORK/out.txt" 2>&1 || rc=$?
  fi
  sed 's/^/  | /' "$WORK/out.txt" | cut -c1-300
  if [ "$rc" != 0 ]; then
    failures+=("example $(basename "$block"): exit status $rc")
  elif [ -n "$expect" ] && ! grep -qE -- "$expect" "$WORK/out.txt"; then
    failures+=("example $(basename "$block"): no output line matches /$expect/")
  fi
done
stop_server || failures+=("a docs server did not stop on SIGTERM")
[ "$count" -ge 5 ] || failures+=("only $count tested examples found in $DOC")
[ ${#failures[@]} = 0 ] || { printf 'FAIL: %s\n' "${failures[@]}"; exit 1; }
echo "docs_examples passed ($count examples)"
