#!/usr/bin/env bash
# Volume file formats read per brick: the neghip samples written by this test as raw
# float64, NRRD (attached raw; detached .nhdr with line and byte skips, big-endian int16; gzip
# float32; .nrrd with byte skip -1) and a .vti of two pieces in appended raw binary render exactly
# like the raw uint8 file, on 1 and 3 ranks (each rank reads only its bricks' boxes). Bad files
# end every rank with a message naming the file and the NRRD field.
# Usage: volume_formats.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
raw="$2/neghip_64x64x64_uint8.raw"
python3 - "$raw" "$WORK" <<'PY'
import gzip, struct, sys
data = open(sys.argv[1], "rb").read()
out = sys.argv[2]
n = 64
open(out + "/f64.raw", "wb").write(struct.pack("<%dd" % len(data), *data))
hdr = lambda t, enc, extra="": ("NRRD0004\n# written by volume_formats.sh\ntype: %s\ndimension: 3\n"
                                 "sizes: %d %d %d\nspacings: 1 1 1\nencoding: %s\n%s" % (t, n, n, n, enc, extra))
# Attached, raw uint8 (no endian needed for one byte), with a key/value pair and content.
open(out + "/attached.nrrd", "wb").write((hdr("uchar", "raw", "content: neghip\nmodality:=CT\n") + "\n").encode() + data)
# Detached: big-endian int16 after two text lines and 5 bytes.
be = struct.pack(">%dh" % len(data), *data)
open(out + "/detached.nhdr", "w").write(hdr("short", "raw", "endian: big\ndata file: detached.dat\nline skip: 2\nbyte skip: 5\n"))
open(out + "/detached.dat", "wb").write(b"junk line one\njunk line two\n" + b"XXXXX" + be)
# Gzip, float32 little-endian, attached, space directions instead of spacings.
g = gzip.compress(struct.pack("<%df" % len(data), *data))
open(out + "/gzip.nrrd", "wb").write(("NRRD0005\ntype: float\ndimension: 3\nsizes: 64 64 64\n"
    "space: right-anterior-superior\nspace directions: (1,0,0) (0,1,0) (0,0,1)\nspace origin: (0,0,0)\n"
    "endian: little\nencoding: gzip\n\n").encode() + g)
# Byte skip -1: the data ends the file, whatever comes before it.
open(out + "/tail.nrrd", "wb").write((hdr("uchar", "raw", "byte skip: -1\n") + "\n").encode() + b"padding" + data)
# .vti: appended raw binary, two pieces split at z = 31/32 (a brick reads the piece(s) it meets).
def piece(z0, z1):
    return data[z0 * n * n:(z1 + 1) * n * n]
p0, p1 = piece(0, 31), piece(32, 63)
blob = struct.pack("<I", len(p0)) + p0 + struct.pack("<I", len(p1)) + p1
xml = ('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian" header_type="UInt32">\n'
       '<ImageData WholeExtent="0 63 0 63 0 63" Origin="0 0 0" Spacing="1 1 1">\n'
       '<Piece Extent="0 63 0 63 0 31"><PointData Scalars="d"><DataArray type="UInt8" Name="d" format="appended" offset="0"/></PointData></Piece>\n'
       '<Piece Extent="0 63 0 63 32 63"><PointData Scalars="d"><DataArray type="UInt8" Name="d" format="appended" offset="%d"/></PointData></Piece>\n'
       '</ImageData>\n<AppendedData encoding="raw">\n_' % (4 + len(p0)))
open(out + "/pieces.vti", "wb").write(xml.encode() + blob + b"\n</AppendedData>\n</VTKFile>\n")
open(out + "/short.vti", "wb").write(xml.encode() + blob[: len(blob) // 2])
# Bad headers, each with its field.
bad = {
    "type_int": hdr("int", "raw", "endian: little\n") + "\n",
    "dimension4": hdr("uchar", "raw").replace("dimension: 3", "dimension: 4") + "\n",
    "unknown_field": hdr("uchar", "raw", "colour: red\n") + "\n",
    "rotated": hdr("uchar", "raw").replace("spacings: 1 1 1\n", "space directions: (0.7,0.7,0) (0,1,0) (0,0,1)\n") + "\n",
    "ascii": hdr("uchar", "ascii") + "\n",
    "no_endian": hdr("short", "raw") + "\n",
}
for name, text in bad.items():
    open(out + "/%s.nrrd" % name, "wb").write(text.encode() + data)
open(out + "/truncated.nrrd", "wb").write((hdr("uchar", "raw") + "\n").encode() + data[:-100])
open(out + "/truncated_gz.nrrd", "wb").write((hdr("float", "gzip", "endian: little\n") + "\n").encode() + g[: len(g) // 2])
open(out + "/missing.nhdr", "w").write(hdr("uchar", "raw", "data file: nowhere.raw\n"))
PY
common=(--set image.width=96 --set image.height=80 --set "camera.position=[55,38,85]" --set transfer.preset=sharp
        --set "transfer.range=[0,255]")
for np in 1 3; do
  run_np $np render -q -o "$WORK/raw$np.png" --set volume.file="$raw" --set "volume.dims=[64,64,64]" "${common[@]}" || fail "raw"
  for f in "f64.raw --set volume.type=float64 --set volume.dims=[64,64,64]" attached.nrrd detached.nhdr gzip.nrrd tail.nrrd pieces.vti; do
    set -- $f
    name=$1
    shift
    run_np $np render -q -o "$WORK/$name.png" --set volume.file="$WORK/$name" "$@" "${common[@]}" || fail "$name on $np rank(s)"
    "$SORTLAST" compare "$WORK/raw$np.png" "$WORK/$name.png" --max-diff 0 >/dev/null || fail "$name on $np rank(s) differs from raw"
  done
  echo "$np rank(s): float64 raw, NRRD (attached, detached, gzip, byte skip -1) and .vti pieces render like raw"
done
# volume.format overrides the extension: a NRRD file named .dat.
cp "$WORK/attached.nrrd" "$WORK/attached.dat"
run_np 1 render -q -o "$WORK/fmt.png" --set volume.file="$WORK/attached.dat" --set volume.format=nrrd "${common[@]}" || fail "volume.format=nrrd"
"$SORTLAST" compare "$WORK/raw1.png" "$WORK/fmt.png" --max-diff 0 >/dev/null || fail "volume.format=nrrd differs"

expect_error() {  # expect_error FILE PATTERN...: 2 ranks refuse FILE with a message matching every pattern
  local file=$1 rc=0
  shift
  run_np 2 render -q -o "$WORK/x.png" --set volume.file="$WORK/$file" "${common[@]}" 2>"$WORK/err" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || fail "$file: accepted (exit $rc)"
  for p in "$file" "$@"; do grep -q -- "$p" "$WORK/err" || fail "$file: the message does not say '$p': $(cat "$WORK/err")"; done
}
expect_error type_int.nrrd "field 'type'" "'int' is not supported"
expect_error dimension4.nrrd "field 'dimension'"
expect_error unknown_field.nrrd "field 'colour'" "unknown field"
expect_error rotated.nrrd "field 'space directions'" "axis-aligned"
expect_error ascii.nrrd "field 'encoding'" "ascii"
expect_error no_endian.nrrd "field 'endian'" "required"
expect_error truncated.nrrd "truncated"
expect_error truncated_gz.nrrd "gzip data ends"
expect_error missing.nhdr "field 'data file'" "nowhere.raw"
expect_error short.vti "short.vti"
echo "bad NRRD and .vti files refused with the file and field named"
