#!/usr/bin/env bash
# A build configured without optional features (cmake/features.cmake) refuses what needs them by
# the option that builds them, on 2 ranks, with a non-zero exit and no hang: a volume or particle
# file of a missing format, an .exr output, `sortlast serve`, a GL backend that is not built.
# Usage: missing_features.sh SORTLAST FEATURE... (the features this build lacks: VTK HDF5 ...)
source "$(dirname "$0")/lib.sh" "$1"
shift
[ $# -gt 0 ] || fail "no missing feature given: nothing to check"

# refused "what" OPTION sortlast-args...: the job ends non-zero on every rank, within the bound, and
# rank 0 names OPTION.
refused() {
  local what=$1 option=$2; shift 2
  local rc=0
  run_np 2 "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] || fail "$what: exit code 0"
  [ "$rc" != 124 ] || fail "$what: timed out (hang)"
  local want="$what: this build has no"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  grep -qF -- "(configure with -D$option=ON)" "$WORK/stderr" ||
    { cat "$WORK/stderr"; fail "$what: message does not name -D$option=ON"; }
  echo "ok: $(grep -m1 'this build has no' "$WORK/stderr")"
}

small=(--set image.width=32 --set image.height=32 --set "volume.dims=[16,16,16]")
for feature in "$@"; do
  case $feature in
    VTK)
      : >"$WORK/v.vti" && : >"$WORK/p.vtp"
      refused "volume.file $WORK/v.vti" SORTLAST_WITH_VTK render -q -o "$WORK/o.png" --set volume.file="$WORK/v.vti"
      refused "particles.file $WORK/p.vtp" SORTLAST_WITH_VTK render -q -o "$WORK/o.png" --set particles.file="$WORK/p.vtp" ;;
    HDF5)
      : >"$WORK/v.h5"
      refused "volume.file $WORK/v.h5" SORTLAST_WITH_HDF5 render -q -o "$WORK/o.png" --set volume.file="$WORK/v.h5"
      refused "particles.file $WORK/v.h5" SORTLAST_WITH_HDF5 render -q -o "$WORK/o.png" --set particles.file="$WORK/v.h5" ;;
    NETCDF)
      : >"$WORK/v.nc"
      refused "volume.file $WORK/v.nc" SORTLAST_WITH_NETCDF render -q -o "$WORK/o.png" --set volume.file="$WORK/v.nc" ;;
    EXR)
      refused "output $WORK/o.exr" SORTLAST_WITH_EXR render -q -o "$WORK/o.exr" "${small[@]}"
      refused "surface output $WORK/s.exr" SORTLAST_WITH_EXR render -q -o "$WORK/o.png" --surface-out "$WORK/s.exr" \
        --set particles.procedural=layers "${small[@]}" ;;
    SERVICE)
      refused "sortlast serve" SORTLAST_WITH_SERVICE serve --listen 127.0.0.1:0 ;;
    OSMESA)
      refused "render.backend osmesa" SORTLAST_WITH_OSMESA render -q -o "$WORK/o.png" "${small[@]}" --set render.backend=osmesa ;;
    EGL)
      refused "render.backend egl" SORTLAST_WITH_EGL render -q -o "$WORK/o.png" "${small[@]}" --set render.backend=egl ;;
    *) fail "unknown feature $feature" ;;
  esac
done
# What the build has still renders: the default scene on 2 ranks.
run_np 2 render -q -o "$WORK/default.png" "${small[@]}" || fail "the default scene"
echo "ok: the default scene renders"
