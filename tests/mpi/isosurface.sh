#!/usr/bin/env bash
# Isosurfaces (render.blend: isosurface, render.isovalues; render/volume/raycast_isosurface.frag.glsl)
# over MPI against the exact CPU reference (reference/isosurface_reference.h).
# Usage: isosurface.sh SORTLAST MODE
#   reference  the sphere field (two values, the outer one semi-transparent, so the inner one
#              shows through it) and the default scene's blobs (three values) vs the reference,
#              >= 45 dB each; the sphere's surface image (--surface-out: the opaque value's t and
#              normal) vs the reference's exact crossings within 1e-3 voxel and 0.5 degree; with the particles of tests/data/mixed.yaml inside the sphere's
#              surfaces (the rays end at the particle surface: hits in front count, the particles
#              behind) vs the reference, >= 45 dB; with subdivision surfaces (the same opaque layer)
#              vs the reference, >= 47 dB; the sphere clipped by a slanted plane and a box across
#              3^3 bricks on 1 and 3 ranks vs the reference >= 45 dB, and 1 vs 3 within 1/255
#   ranks      the sphere's surfaces cross every brick face (3^3 bricks): 2-4 ranks with every
#              compositing strategy give the 1-rank frame within 1/255, and that the 1-brick
#              frame within 1/255 (each crossing counted once at a face; measured at most 1/255)
#   bad        no isovalues, slicing, adaptive sampling, an opacity outside [0, 1], a step over 1
#              voxel: refused naming the key; an isovalue outside the data's range: a warning
# Measured on llvmpipe: sphere 54.9 dB (one grazing pixel of 56/255: two crossings within one
# step, which the reference sees and the ray caster cannot), blobs 50.5 dB, particles 58.2 dB,
# subdivision surfaces 48.9 dB; ranks and strategies at most 1/255; the sphere's surface image
# 1.2e-4 voxel and 2e-4 degree at worst (1 hole: the grazing pixel; none away from silhouettes);
# clipped 53.3 dB on 1 and 3 ranks, identical frames. Depth and normals per pixel
# are checked in tests/unit/isosurface_gl_test.cpp.
source "$(dirname "$0")/lib.sh" "$1"
S=$SORTLAST

cat >"$WORK/sphere.yaml" <<'YAML'
volume:
  procedural: sphere
  dims: [48, 44, 52]
image:
  width: 128
  height: 128
camera:
  position: [40, 28, 70]
bricks:
  per_axis: 2
render:
  blend: isosurface
  isovalues:
    - {value: 0.3, color: [1.0, 0.6, 0.2], opacity: 0.45}
    - {value: 0.62, color: [0.3, 0.6, 1.0], opacity: 1}
YAML

render() {  # render NP SCENE OUT [args...]
  local np=$1 scene=$2 out=$3; shift 3
  run_np "$np" render "$scene" -q -o "$out" "$@" || fail "render $(basename "$scene") $*"
}
psnr_of() { "$S" compare "$1" "$2" | sed -n 's/^psnr_db=\([0-9.inf]*\).*/\1/p'; }
vs_reference() {  # vs_reference NAME SCENE|default MIN_DB [args...]
  local name=$1 scene=(); [ "$2" != default ] && scene=("$2")
  local min=$3; shift 3
  "$S" reference "${scene[@]}" -q -o "$WORK/ref_$name.png" "$@" || fail "reference $name"
  run_np 2 render "${scene[@]}" -q -o "$WORK/gl_$name.png" "$@" || fail "render $name"
  "$S" compare "$WORK/gl_$name.png" "$WORK/ref_$name.png" --min-psnr "$min" ||
    fail "$name below $min dB against the reference"
  echo "$name: $(psnr_of "$WORK/gl_$name.png" "$WORK/ref_$name.png") dB"
}
same() {  # same A B: A's frame within 1/255 of B's
  "$S" compare "$WORK/$1.png" "$WORK/$2.png" --max-diff 1 >/dev/null ||
    fail "$1 differs from $2: $("$S" compare "$WORK/$1.png" "$WORK/$2.png")"
}

case $2 in
reference)
  # The sphere, and its surface image (--surface-out): where the inner, opaque value is the first
  # opaque hit, its t and outward normal, against the reference's exact crossings.
  "$S" reference "$WORK/sphere.yaml" -q -o "$WORK/ref_sphere.png" --surface-out "$WORK/ref_sphere.exr" ||
    fail "reference sphere"
  run_np 2 render "$WORK/sphere.yaml" -q -o "$WORK/gl_sphere.png" --surface-out "$WORK/gl_sphere.exr" ||
    fail "render sphere"
  "$S" compare "$WORK/gl_sphere.png" "$WORK/ref_sphere.png" --min-psnr 45 || fail "sphere below 45 dB against the reference"
  echo "sphere: $(psnr_of "$WORK/gl_sphere.png" "$WORK/ref_sphere.png") dB"
  "$S" compare-surface "$WORK/ref_sphere.exr" "$WORK/gl_sphere.exr" --ignore-edges --max-holes 2 --max-extra 2 \
    --max-depth-error 1e-3 --max-normal-deg 0.5 || fail "sphere: the isosurface's surface image differs from the reference's"
  vs_reference blobs default 45 --set image.width=128 --set image.height=128 --set "volume.dims=[64,64,64]" \
    --set render.blend=isosurface \
    --set 'render.isovalues=[{value: 0.2, color: [0.9, 0.9, 0.9], opacity: 0.3}, {value: 0.45, color: [1, 0.5, 0.2], opacity: 0.6}, {value: 0.7, color: [0.2, 0.5, 1]}]'
  # Particles inside the semi-transparent outer surface.
  vs_reference particles "$(dirname "$0")/../data/mixed.yaml" 45 --set render.method=raycast \
    --set render.sample_spacing=0.5 --set image.width=128 --set image.height=128 --set render.blend=isosurface \
    --set 'render.isovalues=[{value: 0.15, color: [0.3, 0.8, 1.0], opacity: 0.5}]'
  # Subdivision surfaces inside and through the sphere's surfaces: they join the particles' opaque
  # layer, which ends the rays in each brick (measured 48.9 dB: the surfaces' own silhouettes).
  cat >"$WORK/surfaces.yaml" <<'YAML'
volume: {procedural: sphere, dims: [48, 48, 48]}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
render:
  blend: isosurface
  isovalues: [{value: 0.3, color: [1, 0.6, 0.2], opacity: 0.4}, {value: 0.8, color: [0.9, 0.9, 0.9]}]
surfaces:
  - {procedural: pole5, color: [0.3, 0.6, 0.9], transform: {scale: 22, rotate: [20, 30, 0], translate: [-8, 3, 4]}}
  - {procedural: torus, level: 1, transform: {scale: 14, rotate: [60, 0, 0], translate: [9, -7, -3]}}
YAML
  vs_reference surfaces "$WORK/surfaces.yaml" 47
  # Clipped: a slanted plane across brick faces (3^3 bricks) cuts both surfaces open and a box
  # trims the side facing the camera; the search starts at the cut, so where the field there is
  # already beyond a value that surface does not show on the cut face (the reference alike). 1 and
  # 3 ranks against the reference, and within 1/255 of each other (no seam where the cut meets a
  # brick face).
  clip=(--set bricks.per_axis=3 --set "clip.planes=[{normal: [1, 0.3, 0.5], offset: 4}]"
        --set "clip.box=[[-30, -30, -30], [30, 30, 18]]")
  "$S" reference "$WORK/sphere.yaml" -q -o "$WORK/ref_clip.png" "${clip[@]}" || fail "reference clip"
  for np in 1 3; do
    render "$np" "$WORK/sphere.yaml" "$WORK/clip_$np.png" "${clip[@]}" --set compositing.strategy=radix-k
    "$S" compare "$WORK/clip_$np.png" "$WORK/ref_clip.png" --min-psnr 45 ||
      fail "clipped isosurfaces on $np ranks below 45 dB against the reference"
    echo "clipped, $np ranks: $(psnr_of "$WORK/clip_$np.png" "$WORK/ref_clip.png") dB"
  done
  same clip_3 clip_1
  ;;
ranks)
  render 1 "$WORK/sphere.yaml" "$WORK/one.png" --set bricks.per_axis=1
  render 1 "$WORK/sphere.yaml" "$WORK/d3_1.png" --set bricks.per_axis=3
  same d3_1 one
  # Each strategy on one or two rank counts (every pair cost 59 s; the brick images do not depend
  # on the rank count, the compositing does, and tests/mpi/strategies.sh covers its schedules).
  for run in "2 direct" "2 binary-swap" "3 radix-k" "4 auto"; do
    read -r np strategy <<<"$run"
    render "$np" "$WORK/sphere.yaml" "$WORK/d3_${np}_$strategy.png" --set bricks.per_axis=3 \
      --set compositing.strategy=$strategy
    same "d3_${np}_$strategy" d3_1
  done
  echo "1-4 ranks, every strategy, 1 and 27 bricks: within 1/255"
  ;;
bad)
  expect_error() {  # expect_error NP WHAT MESSAGE-PART args...
    local np=$1 what=$2 want=$3; shift 3
    local rc=0
    run_np "$np" render "$WORK/sphere.yaml" -q -o "$WORK/out.png" "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
    [ "$rc" != 0 ] || fail "$what: exit code 0"
    [ "$rc" != 124 ] || fail "$what: timed out (hang)"
    grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
    echo "ok: $what"
  }
  expect_error 2 "no isovalues" "needs at least one isovalue in render.isovalues" --set 'render.isovalues=[]'
  expect_error 2 "slicing" "render.method: raycast" --set render.method=slicing
  expect_error 1 "adaptive sampling" "'render.blend' and 'adaptive.tolerance'" --set adaptive.tolerance=1
  expect_error 1 "opacity above 1" "render.isovalues[1].opacity': must be in [0, 1], got 1.5" \
    --set 'render.isovalues=[{value: 0.3}, {value: 0.5, opacity: 1.5}]'
  expect_error 1 "negative opacity" "render.isovalues[0].opacity': must be in [0, 1]" \
    --set 'render.isovalues=[{value: 0.3, opacity: -0.1}]'
  expect_error 1 "no value" "render.isovalues[0].value': missing" --set 'render.isovalues=[{opacity: 1}]'
  expect_error 1 "unknown entry key" "unknown key 'colour'" --set 'render.isovalues=[{value: 0.3, colour: [1, 1, 1]}]'
  expect_error 1 "step over 1 voxel" "render.sample_spacing <= 1 voxel" --set render.sample_spacing=2
  expect_error 1 "isovalues without the blend" "drawn only with render.blend: isosurface" --set render.blend=composite
  # Outside the data's range [0, 1]: a warning, and the frame has the other surface only.
  render 2 "$WORK/sphere.yaml" "$WORK/warn.png" --set 'render.isovalues=[{value: 0.62}, {value: 1.5}]' \
    2>"$WORK/stderr" || fail "an isovalue outside the range must render"
  grep -qF "warning: render.isovalues[1].value 1.5 is outside the data's range" "$WORK/stderr" ||
    { cat "$WORK/stderr"; fail "no warning for an isovalue outside the data's range"; }
  echo "ok: an isovalue outside the range warns"
  ;;
*) fail "unknown mode $2" ;;
esac
