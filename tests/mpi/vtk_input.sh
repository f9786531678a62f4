#!/usr/bin/env bash
# VTK input: the same samples as a legacy .vtk (binary, big-endian) and as a .vti (XML, ASCII)
# render exactly like the raw file, on 3 ranks (rank 0 reads and scatters the bricks).
# Usage: vtk_input.sh SORTLAST DATA_DIR
source "$(dirname "$0")/lib.sh" "$1"
raw="$2/neghip_64x64x64_uint8.raw"
python3 - "$raw" "$WORK" <<'PY'
import sys
data = open(sys.argv[1], "rb").read()
out = sys.argv[2]
with open(out + "/neghip.vtk", "wb") as f:
    f.write(b"# vtk DataFile Version 3.0\nneghip\nBINARY\nDATASET STRUCTURED_POINTS\n"
            b"DIMENSIONS 64 64 64\nORIGIN 0 0 0\nSPACING 1 1 1\nPOINT_DATA 262144\n"
            b"SCALARS density unsigned_char 1\nLOOKUP_TABLE default\n" + data + b"\n")
with open(out + "/neghip.vti", "w") as f:
    f.write('<?xml version="1.0"?>\n<VTKFile type="ImageData" version="0.1" byte_order="LittleEndian">\n'
            '<ImageData WholeExtent="0 63 0 63 0 63" Origin="0 0 0" Spacing="1 1 1">\n'
            '<Piece Extent="0 63 0 63 0 63"><PointData Scalars="density">\n'
            '<DataArray type="UInt8" Name="density" format="ascii">\n')
    f.write(" ".join(str(b) for b in data))
    f.write('\n</DataArray></PointData></Piece></ImageData></VTKFile>\n')
PY
common=(--set image.width=96 --set image.height=80 --set "camera.position=[55,38,85]" --set transfer.preset=sharp)
run_np 3 render -q -o "$WORK/raw.png" --set volume.file="$raw" --set "volume.dims=[64,64,64]" "${common[@]}" || fail "raw"
for f in neghip.vtk neghip.vti; do
  run_np 3 render -q -o "$WORK/$f.png" --set volume.file="$WORK/$f" "${common[@]}" || fail "$f"
  "$SORTLAST" compare "$WORK/raw.png" "$WORK/$f.png" --max-diff 0 || fail "$f differs from raw"
done
printf 'not a vtk file\n' >"$WORK/bad.vtk"
rc=0; run_np 2 render -q -o "$WORK/x.png" --set volume.file="$WORK/bad.vtk" 2>"$WORK/err" || rc=$?
[ "$rc" != 0 ] && [ "$rc" != 124 ] && grep -q "bad.vtk" "$WORK/err" || fail "bad .vtk accepted (rc $rc)"
echo "vtk ok"
