#!/usr/bin/env bash
# HDF5 and NetCDF input, the data written by this test with h5py and netCDF4-python
# (Debian's python3-h5py, python3-netcdf4) from the neghip samples and the dam-break particles.
#   hdf5:      contiguous uint8 (the only 3-D dataset, found), chunked+gzip float32 in a file of
#              two 3-D datasets (volume.dataset), float64 written transposed (volume.axis_order
#              xyz), uint16 with spacing and origin attributes, a series (/step_{step}/density,
#              time.step 1), render exactly like the raw file
#              on 1 and 3 ranks (chunked also on 4; attributes on 3), read collectively through
#              MPI-IO (collective transfers where volume.mpi_io says so, and independent under auto on
#              one node); the CPU reference (independent reads) of the transposed, the chunked and a
#              .dat with volume.format hdf5 equals raw's. Bad files are refused naming the file,
#              the dataset and the problem (a NaN met by one of 3 ranks ends all three; so does a
#              damaged gzip chunk met by one of 2 inside the collective read).
#   netcdf:    float32 with uniform coordinate variables (spacing from them) on 1 and 3 ranks,
#              missing samples (_FillValue, missing_value) transparent on 1, 3 and 4 ranks, and
#              a 4-D ubyte variable of one record on 1 and 4 ranks, one of 3 records (a time
#              series: time.step picks the record) on 3; bad files refused.
#   particles: /PartType0/Coordinates (float32 on 1, 2 and 3 ranks, each rank reading a share of
#              the rows; float64 on 1) render like the raw particle file; bad snapshots (a NaN in
#              one rank's share) and particles.radius_dataset refused.
# Scope `short` (the sanitizer build): for hdf5, the chunked file and the NaN on 3 ranks, the damaged
# chunk on 2, the transposed file through the reference; for netcdf, the coordinates file on 3
# ranks and the missing samples on 3.
# Usage: hdf5_netcdf.sh SORTLAST DATA_DIR hdf5|netcdf|particles [full|short]
source "$(dirname "$0")/lib.sh" "$1"
data=$2
mode=$3
scope=${4:-full}
short() { [ "$scope" = short ]; }
raw="$data/neghip_64x64x64_uint8.raw"
common=(--set image.width=96 --set image.height=80 --set "camera.position=[55,38,85]" --set transfer.preset=sharp
        --set "transfer.range=[0,255]")

# expect_error "SETS" PATTERN...: 2 ranks refuse the scene (--set options in SETS) with a message
# matching every pattern. refused "SETS" PATTERN...: the same from the CPU reference (one process,
# the same validateVolume; a tenth of the time of two ranks): for the refusals found before any
# rank reads a brick, which every rank meets alike.
expect_error() { check_refusal "run_np 2 render" "$@"; }
refused() { check_refusal "$SORTLAST reference" "$@"; }
check_refusal() {
  local how=$1 sets=$2 rc=0
  shift 2
  # shellcheck disable=SC2086
  $how -q -o "$WORK/x.png" $sets "${common[@]}" 2>"$WORK/err" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || fail "$sets: accepted (exit $rc)"
  for p in "$@"; do grep -qF -- "$p" "$WORK/err" || fail "$sets: the message does not say '$p': $(cat "$WORK/err")"; done
}
# same NP NAME SETS...: renders NAME on NP ranks and compares it with raw$NP.png, bit for bit.
same() {
  local np=$1 name=$2
  shift 2
  run_np "$np" render -q -o "$WORK/$name$np.png" "$@" "${common[@]}" || fail "$name on $np rank(s)"
  "$SORTLAST" compare "$WORK/raw$np.png" "$WORK/$name$np.png" --max-diff 0 >/dev/null ||
    fail "$name on $np rank(s) differs from the raw file's image"
}
raw_images() {  # raw_images SPACING NP...: the raw file's images, raw$NP.png
  local spacing=$1
  shift
  for np in "$@"; do
    run_np "$np" render -q -o "$WORK/raw$np.png" --set volume.file="$raw" --set "volume.dims=[64,64,64]" \
      --set "volume.spacing=$spacing" "${common[@]}" || fail "raw on $np rank(s)"
  done
}
# missing NP...: fill.nc (samples missing in a box and at one voxel) on each NP, under a transfer
# function that fogs the empty space (so a missing sample drawn as the lowest value would show):
# the same image on every rank count, within 44 dB of the CPU reference (NaN where a trilinear
# stencil touches a missing sample: transparent; measured 49.2 dB, and 36.5-39.4 with the GLSL's
# NaN checks taken out), pre-integrated (the default here) and not, slicing on the first NP; and
# the reference more than 4 dB from the raw file's, whose box is drawn (measured 34.2 dB).
fog=(--set "transfer.points=[[0,0.2,0.4,0.9,0.05],[0.3,0.2,0.4,0.9,0],[0.6,1,0.8,0.6,0],[0.7,1,0.8,0.6,0.8],[1,1,1,1,0.8]]")
missing() {
  local first="" np pre
  for pre in auto false; do
    "$SORTLAST" reference -q -o "$WORK/fillref.png" --set volume.file="$WORK/fill.nc" "${common[@]}" "${fog[@]}" \
      --set transfer.preintegrated=$pre || fail "reference of fill.nc"
    for np in "$@"; do
      run_np "$np" render -q -o "$WORK/fill$np.png" --set volume.file="$WORK/fill.nc" "${common[@]}" "${fog[@]}" \
        --set transfer.preintegrated=$pre || fail "fill.nc on $np rank(s)"
      "$SORTLAST" compare "$WORK/fill$np.png" "$WORK/fillref.png" --min-psnr 44 >/dev/null ||
        fail "fill.nc on $np rank(s), pre-integrated $pre: below 44 dB against the reference: $("$SORTLAST" compare "$WORK/fill$np.png" "$WORK/fillref.png")"
      if [ -z "$first" ]; then first=$np; else
        "$SORTLAST" compare "$WORK/fill$first.png" "$WORK/fill$np.png" --max-diff 0 >/dev/null ||
          fail "fill.nc differs between $first and $np rank(s)"
      fi
    done
    first=""
    run_np "$1" render -q -o "$WORK/fills.png" --set volume.file="$WORK/fill.nc" "${common[@]}" "${fog[@]}" \
      --set transfer.preintegrated=$pre --set render.method=slicing || fail "fill.nc sliced"
    "$SORTLAST" compare "$WORK/fills.png" "$WORK/fillref.png" --min-psnr 44 >/dev/null ||
      fail "fill.nc sliced, pre-integrated $pre: below 44 dB against the reference: $("$SORTLAST" compare "$WORK/fills.png" "$WORK/fillref.png")"
  done
  "$SORTLAST" reference -q -o "$WORK/rawref.png" --set volume.file="$raw" --set "volume.dims=[64,64,64]" "${common[@]}" "${fog[@]}" ||
    fail "reference of the raw file"
  ! "$SORTLAST" compare "$WORK/rawref.png" "$WORK/fillref.png" --min-psnr 40 >/dev/null ||
    fail "the reference of fill.nc is within 40 dB of the raw file's: the missing box is drawn"
}

case $mode in
hdf5)
  python3 - "$raw" "$WORK" <<'PY'
import sys, numpy as np, h5py
a = np.fromfile(sys.argv[1], dtype=np.uint8).reshape(64, 64, 64)  # [z, y, x]
out = sys.argv[2]
with h5py.File(out + "/u8.h5", "w") as f:
    f["neghip"] = a
    f["notes"] = np.arange(10)  # 1-D: not a candidate
with h5py.File(out + "/two.h5", "w") as f:
    # chunks that bricks cut through, gzip; and a second 3-D dataset
    f.create_dataset("fields/density", data=a.astype(np.float32), chunks=(10, 12, 16), compression="gzip")
    f["fields/other"] = np.zeros((4, 4, 4), np.float32)
with h5py.File(out + "/xyz.h5", "w") as f:
    f["v"] = a.astype(np.float64).transpose(2, 1, 0).copy()  # [x, y, z]
with h5py.File(out + "/attrs.h5", "w") as f:
    d = f.create_dataset("v", data=a.astype(np.uint16))
    d.attrs["element_size"] = [2.0, 1.0, 1.0]  # dz, dy, dx
    f.attrs["origin"] = [-5.0, 0.0, 3.0]
with h5py.File(out + "/series.h5", "w") as f:  # a time series: /step_{step}/density, 0 ... 2
    for k, v in enumerate([a, np.flip(a, 2), a]):
        f["step_%d/density" % k] = v
np.flip(a, 2).tofile(out + "/flip.raw")
with h5py.File(out + "/rank2.h5", "w") as f: f["v"] = np.zeros((8, 8), np.float32)
with h5py.File(out + "/int32.h5", "w") as f: f["v"] = a.astype(np.int32)
nan = a.astype(np.float32)
nan[50, 40, 30] = np.nan  # voxel [x, y, z] = [30, 40, 50]
with h5py.File(out + "/nan.h5", "w") as f: f["v"] = nan
open(out + "/text.h5", "w").write("not HDF5\n" * 100)
# A damaged gzip chunk (the last of four slabs of 16 z planes): the ranks reading it fail inside
# the collective H5Dread, the others do not.
with h5py.File(out + "/bad_chunk.h5", "w") as f:
    offset = f.create_dataset("v", data=a.astype(np.float32), chunks=(16, 64, 64), compression="gzip").id.get_chunk_info(3).byte_offset
b = bytearray(open(out + "/bad_chunk.h5", "rb").read())
for i in range(offset + 20, offset + 200):
    b[i] ^= 0x5A
open(out + "/bad_chunk.h5", "wb").write(b)
b = open(out + "/u8.h5", "rb").read()
open(out + "/truncated.h5", "wb").write(b[: len(b) // 2])
PY
  w=$WORK
  if short; then
    raw_images "[1,1,1]" 3
    same 3 two --set volume.file="$w/two.h5" --set volume.dataset=/fields/density --set volume.mpi_io=collective
    "$SORTLAST" reference -q -o "$w/ref_raw.png" --set volume.file="$raw" --set "volume.dims=[64,64,64]" "${common[@]}" || fail "reference raw"
    "$SORTLAST" reference -q -o "$w/ref.png" --set volume.file="$w/xyz.h5" --set volume.axis_order=xyz "${common[@]}" || fail "reference xyz"
    "$SORTLAST" compare "$w/ref_raw.png" "$w/ref.png" --max-diff 0 >/dev/null || fail "reference of xyz.h5 differs"
    expect_error "--set volume.file=$w/bad_chunk.h5 --set volume.mpi_io=collective" "$w/bad_chunk.h5" "dataset /v" "read of a brick failed" "inflate"
    rc=0
    run_np 3 render -q -o "$w/x.png" --set volume.file="$w/nan.h5" --set volume.mpi_io=collective "${common[@]}" 2>"$w/err" || rc=$?
    [ "$rc" != 0 ] && [ "$rc" != 124 ] && grep -qF "NaN at voxel [30, 40, 50]" "$w/err" || fail "NaN on 3 ranks: exit $rc: $(cat "$w/err")"
    echo "short scope: chunked+gzip on 3 ranks, xyz through the reference, a damaged chunk and a NaN refused"
    exit 0
  fi
  raw_images "[1,1,1]" 1 3 4
  for np in 1 3; do
    same $np u8 --set volume.file="$WORK/u8.h5"
    same $np two --set volume.file="$WORK/two.h5" --set volume.dataset=/fields/density
    same $np xyz --set volume.file="$WORK/xyz.h5" --set volume.axis_order=xyz
  done
  same 4 two --set volume.file="$WORK/two.h5" --set volume.dataset=/fields/density --set volume.mpi_io=collective
  same 3 two_collective --set volume.file="$WORK/two.h5" --set volume.dataset=/fields/density --set volume.mpi_io=collective
  # volume.mpi_io auto (the default): independent on one node, as --stats says.
  run_np 2 render -q -o "$WORK/x.png" --stats "$WORK/stats.json" --set volume.file="$WORK/two.h5" \
    --set volume.dataset=/fields/density "${common[@]}" || fail "two.h5 with --stats"
  grep -q '"hdf5_transfers": *"independent"' "$WORK/stats.json" || fail "auto on one node: not independent: $(cat "$WORK/stats.json")"
  # The CPU reference reads the whole volume with readSamples (the sec2 driver, no MPI-IO);
  # volume.format overrides the extension.
  cp "$WORK/u8.h5" "$WORK/u8.dat"
  "$SORTLAST" reference -q -o "$WORK/ref_raw.png" --set volume.file="$raw" --set "volume.dims=[64,64,64]" "${common[@]}" || fail "reference raw"
  for f in "xyz.h5 --set volume.axis_order=xyz" "two.h5 --set volume.dataset=/fields/density" "u8.dat --set volume.format=hdf5"; do
    set -- $f
    "$SORTLAST" reference -q -o "$WORK/ref.png" --set volume.file="$WORK/$1" "${@:2}" "${common[@]}" || fail "reference $1"
    "$SORTLAST" compare "$WORK/ref_raw.png" "$WORK/ref.png" --max-diff 0 >/dev/null || fail "reference of $1 differs"
  done
  echo "HDF5 contiguous uint8, chunked+gzip float32 (4 ranks too; collective transfers on 3 and 4, auto independent on one node), float64 xyz render like raw; the reference too"
  raw_images "[1,1,2]" 3
  same 3 attrs --set volume.file="$WORK/attrs.h5" --set volume.spacing_attribute=element_size \
    --set volume.origin_attribute=origin
  echo "HDF5 uint16 with spacing from an attribute (zyx order) renders like raw with volume.spacing [1, 1, 2] on 3 ranks"
  w=$WORK
  # A series in one file: volume.dataset with {step}; step 1 is the mirrored volume.
  run_np 3 render -q -o "$w/flip3.png" --set volume.file="$w/flip.raw" --set "volume.dims=[64,64,64]" \
    "${common[@]}" || fail "raw flip on 3 ranks"
  run_np 3 render -q -o "$w/series3.png" --set volume.file="$w/series.h5" --set "volume.dataset=/step_{step}/density" \
    --set time.step=1 "${common[@]}" || fail "series.h5 time.step 1 on 3 ranks"
  "$SORTLAST" compare "$w/flip3.png" "$w/series3.png" --max-diff 0 >/dev/null ||
    fail "series.h5 time.step 1 differs from the raw file of step 1"
  refused "--set volume.file=$w/series.h5 --set volume.dataset=/step_{step}/density --set time.step=3" \
    "time.step" "3 is out of range" "3 time step(s)"
  refused "--set volume.file=$w/series.h5 --set volume.dataset=/s{step}/density" "$w/series.h5" "no dataset /s0/density"
  echo "HDF5 series /step_{step}/density: time.step 1 renders step 1 like its raw file on 3 ranks; step 3 refused"
  expect_error "--set volume.file=$w/two.h5" "$w/two.h5" "2 3-D datasets" "/fields/density, /fields/other" "volume.dataset"
  expect_error "--set volume.file=$w/truncated.h5" "$w/truncated.h5" "truncated"
  expect_error "--set volume.file=$w/bad_chunk.h5 --set volume.mpi_io=collective" "$w/bad_chunk.h5" "dataset /v" "read of a brick failed" "inflate"
  refused "--set volume.file=$w/two.h5 --set volume.dataset=/fields/nope" "$w/two.h5" "dataset /fields/nope" "no such dataset"
  refused "--set volume.file=$w/rank2.h5" "$w/rank2.h5" "no 3-D dataset"
  refused "--set volume.file=$w/rank2.h5 --set volume.dataset=/v" "dataset /v" "2 dimension(s), not 3"
  refused "--set volume.file=$w/int32.h5" "$w/int32.h5" "dataset /v" "type int32 are not supported"
  refused "--set volume.file=$w/text.h5" "$w/text.h5" "not an HDF5 file"
  refused "--set volume.file=$w/nan.h5" "$w/nan.h5" "dataset /v" "NaN at voxel [30, 40, 50]"
  refused "--set volume.file=$w/attrs.h5 --set volume.spacing_attribute=spacing" "$w/attrs.h5" \
    "volume.spacing_attribute 'spacing'" "no such attribute"
  # A NaN on one rank's brick only, read collectively on 3 ranks: every rank ends, none hangs.
  rc=0
  run_np 3 render -q -o "$WORK/x.png" --set volume.file="$w/nan.h5" --set volume.mpi_io=collective "${common[@]}" 2>"$WORK/err" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] && grep -qF "NaN at voxel [30, 40, 50]" "$WORK/err" || fail "NaN on 3 ranks: exit $rc: $(cat "$WORK/err")"
  ! grep -q "HDF5-DIAG" "$WORK/err" || fail "HDF5 printed its error stack"
  echo "bad HDF5 files refused with the file, the dataset and the problem named"
  ;;
netcdf)
  python3 - "$raw" "$WORK" <<'PY'
import sys, numpy as np, netCDF4
a = np.fromfile(sys.argv[1], dtype=np.uint8).reshape(64, 64, 64)  # [z, y, x]
out = sys.argv[2]
def new(name, dims=("z", "y", "x"), coords={}):
    f = netCDF4.Dataset(out + "/" + name, "w")
    for n in dims:
        f.createDimension(n, None if n == "time" else 64)
    for n, step in coords.items():
        c = f.createVariable(n, "f8", (n,))
        c[:] = -7.0 + step * np.arange(64)
    return f
with new("coords.nc", coords={"z": 2.0, "y": 1.0, "x": 1.0}) as f:
    f.createVariable("density", "f4", ("z", "y", "x"))[:] = a.astype(np.float32)
with new("record.nc", ("time", "z", "y", "x"), {"z": 2.0}) as f:
    f.createVariable("density", "u1", ("time", "z", "y", "x"))[0] = a
with new("records.nc", ("time", "z", "y", "x")) as f:
    v = f.createVariable("density", "u1", ("time", "z", "y", "x"))
    v[0] = a; v[1] = np.flip(a, 2); v[2] = a  # step 1: mirrored in x
np.flip(a, 2).tofile(out + "/flip.raw")
with new("uneven.nc") as f:
    f.createVariable("x", "f8", ("x",))[:] = np.concatenate([np.arange(32), 32.5 + np.arange(32)])
    f.createVariable("density", "u1", ("z", "y", "x"))[:] = a
with new("fill.nc") as f:  # missing samples: a box through the middle and one voxel
    v = f.createVariable("density", "f4", ("z", "y", "x"), fill_value=-999.0)
    v.missing_value = np.float32(-1.0)
    b = a.astype(np.float32)
    b[20:44, 24:40, 16:34] = -999.0
    b[10, 20, 30] = -1.0  # voxel [x, y, z] = [30, 20, 10]
    v[:] = b
with new("allfill.nc") as f:
    f.createVariable("density", "f4", ("z", "y", "x"), fill_value=-999.0)[:] = np.full(a.shape, -999.0, np.float32)
with new("two.nc") as f:
    f.createVariable("a", "u1", ("z", "y", "x"))[:] = a
    f.createVariable("b", "u1", ("z", "y", "x"))[:] = a
with new("int.nc") as f:
    f.createVariable("density", "i4", ("z", "y", "x"))[:] = a
open(out + "/text.nc", "w").write("not NetCDF\n" * 100)
PY
  w=$WORK
  if short; then
    raw_images "[1,1,2]" 3
    same 3 coords --set volume.file="$w/coords.nc"
    missing 3
    echo "short scope: coordinates file on 3 ranks, missing samples on 3"
    exit 0
  fi
  raw_images "[1,1,2]" 1 3 4
  for np in 1 3; do same $np coords --set volume.file="$WORK/coords.nc"; done
  echo "NetCDF float32 with uniform coordinate variables (z step 2) renders like raw with volume.spacing [1, 1, 2]"
  for np in 1 4; do same $np record --set volume.file="$WORK/record.nc" --set volume.variable=density; done
  echo "NetCDF 4-D ubyte of one record (a z coordinate variable only) renders like raw on 1 and 4 ranks"
  w=$WORK
  missing 1 3 4
  echo "NetCDF missing samples (_FillValue, missing_value) transparent: equal on 1, 3 and 4 ranks, within 44 dB of the reference (ray cast and sliced, pre-integrated or not), the hole shown"
  expect_error "--set volume.file=$w/allfill.nc" "$w/allfill.nc" "every sample is missing"
  expect_error "--set volume.file=$w/fill.nc --set adaptive.tolerance=0.01" "render.adaptive" "missing samples"
  refused "--set volume.file=$w/uneven.nc" "$w/uneven.nc" "coordinate variable x" "not uniform"
  refused "--set volume.file=$w/two.nc" "$w/two.nc" "2 3-D variables (a, b)" "volume.variable"
  refused "--set volume.file=$w/two.nc --set volume.variable=c" "$w/two.nc" "variable c" "no such variable"
  refused "--set volume.file=$w/int.nc" "$w/int.nc" "variable density" "int (int32)" "not supported"
  # A 4-D variable of 3 records is a series: time.step 1 reads record 1 (the mirrored volume).
  run_np 3 render -q -o "$w/flip3.png" --set volume.file="$w/flip.raw" --set "volume.dims=[64,64,64]" \
    "${common[@]}" || fail "raw flip on 3 ranks"
  run_np 3 render -q -o "$w/records3.png" --set volume.file="$w/records.nc" --set time.step=1 "${common[@]}" ||
    fail "records.nc time.step 1 on 3 ranks"
  "$SORTLAST" compare "$w/flip3.png" "$w/records3.png" --max-diff 0 >/dev/null ||
    fail "records.nc time.step 1 differs from the raw file of record 1"
  refused "--set volume.file=$w/records.nc --set time.step=3" "time.step" "3 is out of range" "3 time step(s)"
  echo "NetCDF 4-D of 3 records: time.step 1 renders record 1 like its raw file on 3 ranks; step 3 refused"
  refused "--set volume.file=$w/text.nc" "$w/text.nc" "cannot open as NetCDF"
  echo "bad NetCDF files refused with the file, the variable and the problem named"
  ;;
particles)
  nan_at=$(python3 - "$data/dam_break_xyz_float32.raw" "$WORK" <<'PY'
import sys, numpy as np, h5py
p = np.fromfile(sys.argv[1], dtype="<f4").reshape(-1, 3)
out = sys.argv[2]
for name, t in (("f32", np.float32), ("f64", np.float64)):
    with h5py.File(out + "/%s.hdf5" % name, "w") as f:
        f["PartType0/Coordinates"] = p.astype(t)
        h = f.create_group("Header")
        h.attrs["BoxSize"] = 1.0
        h.attrs["Time"] = 0.25
with h5py.File(out + "/flat.hdf5", "w") as f: f["PartType0/Coordinates"] = p[:, :2].copy()
q = p.copy()
q[len(q) - 5, 1] = np.nan  # in the last rank's share on any rank count
with h5py.File(out + "/nan.hdf5", "w") as f: f["PartType0/Coordinates"] = q
print(len(q) - 5)
PY
)
  scene="$data/../../configs/dam_break.yaml"
  sizes=(--set image.width=96 --set image.height=80)
  for np in 1 2; do
    bricks=(--set bricks.per_axis=$np)
    run_np $np render "$scene" -q -o "$WORK/raw$np.png" "${sizes[@]}" "${bricks[@]}" || fail "raw particles on $np rank(s)"
    for f in f32 $([ $np = 1 ] && echo f64); do
      run_np $np render "$scene" -q -o "$WORK/$f$np.png" --set particles.file="$WORK/$f.hdf5" "${sizes[@]}" "${bricks[@]}" ||
        fail "$f.hdf5 on $np rank(s)"
      "$SORTLAST" compare "$WORK/raw$np.png" "$WORK/$f$np.png" --max-diff 0 >/dev/null || fail "$f.hdf5 on $np rank(s) differs"
    done
  done
  # 3 ranks, each reading a third of the rows and exchanging them (8 bricks: 3, 3 and 2 a rank).
  run_np 3 render "$scene" -q -o "$WORK/raw3.png" "${sizes[@]}" --set bricks.per_axis=2 || fail "raw particles on 3 ranks"
  run_np 3 render "$scene" -q -o "$WORK/f32_3.png" --set particles.file="$WORK/f32.hdf5" "${sizes[@]}" \
    --set bricks.per_axis=2 || fail "f32.hdf5 on 3 ranks"
  "$SORTLAST" compare "$WORK/raw3.png" "$WORK/f32_3.png" --max-diff 0 >/dev/null || fail "f32.hdf5 on 3 ranks (shares) differs"
  echo "/PartType0/Coordinates (float32 on 1, 2 and 3 ranks: read in shares, float64 on 1) render like the raw particle file"
  pcommon=(--set volume.procedural=none --set particles.radius=0.025 "${sizes[@]}")
  perr() {  # perr FILE_SETS PATTERN...
    local sets=$1 rc=0
    shift
    # shellcheck disable=SC2086
    run_np 2 render -q -o "$WORK/x.png" $sets "${pcommon[@]}" 2>"$WORK/err" || rc=$?
    [ "$rc" != 0 ] && [ "$rc" != 124 ] || fail "$sets: accepted (exit $rc)"
    for p in "$@"; do grep -qF -- "$p" "$WORK/err" || fail "$sets: the message does not say '$p': $(cat "$WORK/err")"; done
  }
  perr "--set particles.file=$WORK/flat.hdf5" "$WORK/flat.hdf5" "/PartType0/Coordinates" "N x 3"
  perr "--set particles.file=$WORK/f32.hdf5 --set particles.dataset=/PartType1/Coordinates" "/PartType1/Coordinates" "no such dataset"
  perr "--set particles.file=$WORK/f32.hdf5 --set particles.radius_dataset=/PartType0/SmoothingLength" \
    "particles.radius_dataset" "not supported"
  # A NaN in the last rank's share: every rank ends, the file's index named.
  rc=0
  run_np 3 render -q -o "$WORK/x.png" --set particles.file="$WORK/nan.hdf5" "${pcommon[@]}" 2>"$WORK/err" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] && grep -qF "NaN position at particle $nan_at" "$WORK/err" ||
    fail "a NaN in rank 2's share on 3 ranks: exit $rc: $(cat "$WORK/err")"
  echo "bad snapshots (a NaN in one rank's share too) and particles.radius_dataset refused"
  ;;
*) fail "unknown mode '$mode' (hdf5, netcdf, particles)" ;;
esac
