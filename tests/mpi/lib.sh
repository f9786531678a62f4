# Shared by the MPI test scripts: how to launch ranks on localhost, and a scratch folder.
# Usage: source lib.sh SORTLAST_BINARY
set -euo pipefail
SORTLAST=$1
MPIRUN=(mpirun --oversubscribe --bind-to none)
if [ "$(id -u)" = 0 ]; then MPIRUN+=(--allow-run-as-root); fi
export OMPI_MCA_btl_vader_single_copy_mechanism=none  # containers often forbid CMA
# Launch costs, not behaviour (measured on the 2-core test machine, Open MPI 4.1): the ob1 messaging
# layer for ranks on one machine, since probing UCX for a network that is not there doubles
# MPI_Init (0.30 s against 0.15 s); and no grace second before SIGKILL once a job has failed:
# mpirun otherwise waits 2 s after every failing run even when every rank has already exited
# (2.4 s against 0.4 s for a bad key on 1 rank). Tests that watch ranks die or stop on SIGTERM
# (killed_ranks.sh, the service's) put the grace back: KILL_GRACE=1 before sourcing.
export OMPI_MCA_pml=ob1
export OMPI_MCA_odls_base_sigkill_timeout=${KILL_GRACE:-0}
# A one-process run without mpirun (the in-situ driver, the examples; `sortlast` sets this itself,
# app/singleton_start.h) would fork Open MPI's orted daemon first: a third of a small frame's CPU.
export OMPI_MCA_ess_singleton_isolated=1
# Ranks waiting on a message yield the core instead of spinning (Open MPI does so by itself only
# when a job has more ranks than cores): 2-rank jobs spun ~15 % of their CPU in opal_progress
# (perf), taken from the test running beside them.
export OMPI_MCA_mpi_yield_when_idle=1
# Page faults, not rendering, are most of a test process's CPU on the test machines (a VM where a
# fault costs ~20 us: a 160x128 render takes ~10,000 of them, ~40 % of its CPU; perf, 2026-12-06):
# - PMIx's shared-memory key-value store makes mpirun create and memset two segments at every
#   launch (40 % of an MPI hello world's faults); its hash store does without them.
# - glibc's malloc asks for transparent huge pages on its heap (the machine's THP mode is
#   `madvise`): one fault per 2 MiB instead of per 4 KiB page of fresh heap.
# Seven tests on 2 cores (golden_set, fields, projection, ...): 183 -> 140 s of CPU, 110 -> 87 s.
# Launch costs only: the images, the ranks' messages and what the tests check do not change.
export PMIX_MCA_gds=hash
export GLIBC_TUNABLES=${GLIBC_TUNABLES:+$GLIBC_TUNABLES:}glibc.malloc.hugetlb=1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
# The helpers run Debian's python3 (scripts/install-deps installs it), found first on PATH: a
# pyenv shim ahead of it costs 0.2-0.6 s a call where Debian's starts in 0.04 s (measured), and
# a service test calls it about a hundred times.
if [ -x /usr/bin/python3 ]; then
  mkdir -p "$WORK/.bin" && ln -sf /usr/bin/python3 "$WORK/.bin/python3" && export PATH="$WORK/.bin:$PATH"
fi
# Every run is bounded: a hang is a failure, not a stuck test suite.
run_np() { local np=$1; shift; timeout 120 "${MPIRUN[@]}" -np "$np" "$SORTLAST" "$@"; }
fail() { echo "FAIL: $*"; exit 1; }

# The particle and surface tests (particles.sh, particles_slices.sh, surfaces.sh): the CPU
# reference of scene $1 (options after it) into $WORK/ref.png and $WORK/ref.exr.
reference() {
  "$SORTLAST" reference "$1" -q -o "$WORK/ref.png" --surface-out "$WORK/ref.exr" "${@:2}" ||
    fail "reference $1"
}
# The mixed scene $1 (a volume with particles inside) on one rank against its reference: the
# frame within $2 dB PSNR, the surface with no hole and no extra hit away from the silhouettes and
# within the depth bounds given after $2 (compare-surface options). Renders with the calling
# script's render function (which writes $WORK/gl.png and gl.exr); leaves the frame in
# $WORK/one.png for the rank comparisons that follow.
mixed_vs_reference() {
  local scene=$1 min_psnr=$2; shift 2
  reference "$scene"
  render 1 "$scene"
  mv "$WORK/gl.png" "$WORK/one.png"
  "$SORTLAST" compare "$WORK/ref.png" "$WORK/one.png" --min-psnr "$min_psnr" ||
    fail "mixed scene against the reference"
  "$SORTLAST" compare-surface "$WORK/ref.exr" "$WORK/gl.exr" --ignore-edges --max-holes 0 \
    --max-extra 0 "$@" || fail "mixed scene surface"
}
