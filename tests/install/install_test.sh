#!/usr/bin/env bash
# What a simulation's build gets: `cmake --install` into a scratch prefix, then
# tests/install/consumer (a C++ program on the C++ API and a C program on the C API) configured in a
# fresh build directory with find_package(sortlast), the C program also compiled with `pkg-config
# sortlast`, and each of the three run on 2 ranks against the installed library, writing one 64x64
# image.
# Usage: install_test.sh CMAKE BUILD_DIR C_COMPILER CXX_COMPILER
set -euo pipefail
CMAKE=$1 BUILD=$2 CC=$3 CXX=$4
HERE=$(cd "$(dirname "$0")" && pwd)
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
# Runs a command quietly; on failure shows its output and fails with the message $1.
quiet() { local what=$1; shift; "$@" >"$TMP/log" 2>&1 || { cat "$TMP/log"; fail "$what"; }; }
MPIRUN=(mpirun --oversubscribe --bind-to none -np 2)
if [ "$(id -u)" = 0 ]; then MPIRUN+=(--allow-run-as-root); fi
export OMPI_MCA_btl_vader_single_copy_mechanism=none  # containers often forbid CMA

# Install, and find what went where (the library directory follows GNUInstallDirs).
PREFIX=$TMP/prefix
quiet "cmake --install" "$CMAKE" --install "$BUILD" --prefix "$PREFIX"
pc=$(find "$PREFIX" -name sortlast.pc)
[ -n "$pc" ] || fail "no sortlast.pc installed"
LIBDIR=$(dirname "$(dirname "$pc")")
for f in "$LIBDIR/libsortlast.so" "$PREFIX/include/sortlast/insitu.h" \
    "$PREFIX/include/sortlast/insitu_c.h" "$LIBDIR/cmake/sortlast/sortlastConfig.cmake" \
    "$LIBDIR/cmake/sortlast/sortlastConfigVersion.cmake" "$PREFIX/bin/sortlast"; do
  [ -e "$f" ] || fail "not installed: ${f#$PREFIX/}"
done
soname=$(objdump -p "$LIBDIR/libsortlast.so" | awk '$1 == "SONAME" {print $2}')
[[ $soname == libsortlast.so.* ]] || fail "SONAME '$soname'"
[ -e "$LIBDIR/$soname" ] || fail "$soname not installed"
# Only the API is exported (cmake/sortlast_insitu.map).
api='^(sortlast_insitu_|sortlast::InSitu(::|Error::)|_init$|_fini$'
api+='|(typeinfo|typeinfo name|vtable) for sortlast::InSituError$)'
extra=$(nm -DC --defined-only "$LIBDIR/libsortlast.so" | cut -d' ' -f3- | grep -Ev "$api" || true)
[ -z "$extra" ] || fail "libsortlast.so exports more than its API: $(head -5 <<<"$extra")"
nm -D --defined-only "$LIBDIR/libsortlast.so" | grep -q ' sortlast_insitu_execute$' ||
  fail "sortlast_insitu_execute not exported"

# find_package in a fresh build directory; the programs must use the installed library.
quiet "consumer configure" "$CMAKE" -S "$HERE/consumer" -B "$TMP/consumer" \
  -DCMAKE_PREFIX_PATH="$PREFIX" -DCMAKE_C_COMPILER="$CC" -DCMAKE_CXX_COMPILER="$CXX"
quiet "consumer build" "$CMAKE" --build "$TMP/consumer" -j2
# pkg-config, the way a Makefile-built C code links it.
export PKG_CONFIG_PATH=$LIBDIR/pkgconfig
flags=$(pkg-config --cflags --libs sortlast) || fail "pkg-config sortlast"
quiet "pkg-config build" \
  "$CC" -Wall -Werror "$HERE/consumer/consumer.c" -o "$TMP/consumer_pc" $flags

export LD_LIBRARY_PATH=$LIBDIR${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
for prog in cxx c pc; do
  case $prog in
    pc) exe=$TMP/consumer_pc ;;
    *) exe=$TMP/consumer/consumer_$prog ;;
  esac
  [[ $(ldd "$exe") == *"$LIBDIR/libsortlast.so"* ]] ||
    fail "$prog: not linked to the installed library"
  cat >"$TMP/actions_$prog.yaml" <<EOF
renders:
  - name: test
    output: "$TMP/out_${prog}_{step}.png"
    scene:
      image: {width: 64, height: 64}
EOF
  timeout 120 "${MPIRUN[@]}" "$exe" "$TMP/actions_$prog.yaml" || fail "$prog: run"
  images=("$TMP"/out_"${prog}"_*.png)
  [ ${#images[@]} = 1 ] && [ -s "${images[0]}" ] || fail "$prog: no image ($(ls "$TMP"))"
  [ "$(head -c 4 "${images[0]}" | tail -c 3)" = PNG ] || fail "$prog: ${images[0]} is not a PNG"
  echo "$prog: ok (${images[0]##*/})"
done
echo "install_package: ok"
