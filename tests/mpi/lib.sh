# Shared by the MPI test scripts: how to launch ranks on localhost, and a scratch folder.
# Usage: source lib.sh SORTLAST_BINARY
set -euo pipefail
SORTLAST=$1
MPIRUN=(mpirun --oversubscribe --bind-to none)
if [ "$(id -u)" = 0 ]; then MPIRUN+=(--allow-run-as-root); fi
export OMPI_MCA_btl_vader_single_copy_mechanism=none  # containers often forbid CMA
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# Every run is bounded: a hang is a failure, not a stuck test suite.
run_np() { local np=$1; shift; timeout 120 "${MPIRUN[@]}" -np "$np" "$SORTLAST" "$@"; }
fail() { echo "FAIL: $*"; exit 1; }
