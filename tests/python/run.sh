# The Python module's tests (python/, docs/python.md): pytest on NP ranks under mpirun, each rank
# running the same tests (they are collective), with Debian's python3 (lib.sh puts it first on
# PATH) and the module from the build tree. References from the command-line programs are made
# first, on the same ranks, into $WORK (the tests read SORTLAST_TEST_WORK).
# Usage: run.sh SORTLAST_BINARY GRAY_SCOTT_BINARY BUILD_PYTHON_DIR NP TEST_FILE... [-- pytest args]
source "$(dirname "$0")/../mpi/lib.sh" "$1"
GS=$2 PYDIR=$3 NP=$4
shift 4
tests=() args=()
while [ $# -gt 0 ] && [ "$1" != -- ]; do tests+=("$1"); shift; done
[ $# -gt 0 ] && shift && args=("$@")
HERE=$(cd "$(dirname "$0")" && pwd)
export PYTHONPATH="$PYDIR:$HERE/../../examples/python${PYTHONPATH:+:$PYTHONPATH}"
export SORTLAST_TEST_WORK=$WORK SORTLAST=$SORTLAST SORTLAST_TEST_NP=$NP
cd "$WORK"
files=()
for t in "${tests[@]}"; do
  files+=("$HERE/$t")
  case $t in
  test_render.py)
    # A small default scene, frame 0, PNG (with --stats) and EXR. The step pinned, as in
    # test_render.py: a batch job of one frame takes a still image's step, a session's frame the
    # probes' (session/auto_spacing.h).
    small=(--set image.width=96 --set image.height=64 --set "volume.dims=[32,32,32]" --set render.sample_spacing=1)
    run_np "$NP" render -q "${small[@]}" -o ref_default.png --stats ref_default.json || fail "render"
    run_np "$NP" render -q "${small[@]}" -o ref_default.exr || fail "render exr"
    ;;
  test_insitu.py)
    # The C++ example: 24^3, steps 0 and 10 drawn at 64x64.
    timeout 120 "${MPIRUN[@]}" -np "$NP" "$GS" --size 24 --steps 10 --every 10 --width 64 --out cpp \
      > /dev/null || fail "gray_scott (C++)"
    ;;
  esac
done
status=0
timeout 120 "${MPIRUN[@]}" -np "$NP" python3 -m pytest -q -p no:cacheprovider --color=no -x "${files[@]}" \
  "${args[@]}" || status=$?
if [ -n "${KEEP_WORK:-}" ]; then cp -r "$WORK" "$KEEP_WORK"; fi  # the images, to look at
[ "$status" = 0 ] || fail "pytest ${tests[*]} on $NP ranks"
