#!/usr/bin/env bash
# Subdivision surfaces (the `surfaces` scene key, docs/subdivision.md) in the sort-last frame loop,
# against the CPU reference (reference/surface_reference.h), on 1-4 ranks and d = 1-3 bricks.
# Usage: surfaces.sh SORTLAST MODE
#   alone       two surfaces: GL against the reference (colour, depth, normals), 1-4 ranks, d = 1-3;
#               one orthographic against its reference (colour, depth, normals), 1 and 3 ranks
#   volume      the surfaces inside a semi-transparent volume: against the reference, 1-4 ranks,
#               d = 1-3 against d = 1 (seams)
#   metaballs   a surface through a metaball splash (the two layers merged by depth per brick):
#               against the reference, 1-4 ranks; the same inside a volume, 1 and 3 ranks, also
#               orthographic
#   reflection  reflection lines against the reference
#   open        open surfaces (boundaries: a saddle, and a fan round a boundary vertex of 5 faces):
#               against the reference (colour, depth, normals), 1-4 ranks, d = 1-3, and seen
#               from behind (two-sided)
#   tagged      creases, corners and boundary rules: a pawn-like lathe with infinitely sharp,
#               2.5 and 1 rims, a cube with a semi-sharp (2.7) loop, Chaikin creases, a sheet
#               under boundary interpolation `none` (holes): against the reference (colour, depth,
#               normals), 1-4 ranks, d = 1-3, inside a volume, reflection lines
#   bad         bad meshes and keys through the CLI: clear message naming the key, exit 1, no hang
#   serve       a resident session (`sortlast serve`, 2 ranks) serves the frames `render` makes, at
#               two image sizes and cameras (the surfaces' targets resize; surfaces are fixed for
#               the session: a request setting them is refused)
# Silhouettes: coverage is the coarse mesh's (GL) or the tessellated limit surface's (reference),
# a pixel or two apart at the outline, so colour comparisons against the reference leave out the
# pixels within 2 of a silhouette of either surface image (`compare --mask-silhouettes`: a hit next
# to a miss, or a depth jump of 5 % between 4-neighbours); rank and brick comparisons compare
# every pixel.
if [ "${2:-}" = serve ]; then
  source "$(dirname "$0")/../service/service_lib.sh" "$1"  # also lib.sh; start_server, frame
else
  source "$(dirname "$0")/lib.sh" "$1"
fi
S=$SORTLAST

# The scenes: small images, procedural meshes.
cat > "$WORK/alone.yaml" <<'YAML'
volume: {procedural: none}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
camera: {position: [1.6, 1.0, 2.6]}
surfaces:
  - {procedural: pole5, color: [0.9, 0.6, 0.3], transform: {translate: [-0.3, 0, 0]}}
  - {procedural: torus, level: 1, transform: {scale: 0.35, rotate: [70, 0, 20], translate: [0.6, -0.2, 0.2]}}
YAML
cat > "$WORK/volume.yaml" <<'YAML'
volume: {procedural: sphere, dims: [48, 48, 48]}
render: {sample_spacing: 0.5}  # where the bounds were measured (auto may take a coarser step)
transfer:
  preintegrated: false
  points: [[0, 1, 0.5, 0.1, 0], [1, 1, 0.5, 0.1, 0.05]]
image: {width: 128, height: 128}
bricks: {per_axis: 2}
surfaces:
  - {procedural: pole5, color: [0.3, 0.6, 0.9], transform: {scale: 22, rotate: [20, 30, 0], translate: [-8, 3, 4]}}
  - {procedural: torus, level: 1, transform: {scale: 14, rotate: [60, 0, 0], translate: [9, -7, -3]}}
YAML
cat > "$WORK/metaballs.yaml" <<'YAML'
volume: {procedural: none}
particles: {procedural: splash, count: 600, spacing: 1.2, radius: 0.8}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
surfaces:
  - {procedural: pole6, color: [0.3, 0.8, 0.4], transform: {scale: 9}}
YAML
cat > "$WORK/all_three.yaml" <<'YAML'
volume: {procedural: sphere, dims: [40, 40, 40]}
render: {sample_spacing: 0.5}  # where the bounds were measured (auto may take a coarser step)
transfer:
  preintegrated: false
  points: [[0, 1, 0.5, 0.1, 0], [1, 1, 0.5, 0.1, 0.05]]
particles: {procedural: splash, count: 600, spacing: 1.2, radius: 0.8}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
surfaces:
  - {procedural: pole6, color: [0.3, 0.8, 0.4], transform: {scale: 9}}
YAML
cat > "$WORK/reflection.yaml" <<'YAML'
volume: {procedural: none}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
camera: {position: [1.2, 1.6, 2.4]}
surfaces:
  - {procedural: pole5, shading: reflection_lines, stripes: 8, stripe_width: 0.4, stripe_direction: [0.3, 1, 0.2]}
YAML

cat > "$WORK/open.yaml" <<'YAML'
volume: {procedural: none}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
camera: {position: [0.3, -3.5, 6.0]}
surfaces:
  - {procedural: open_grid, color: [0.9, 0.6, 0.3], transform: {scale: 0.5, translate: [-1.0, 0, 0]}}
  - {procedural: fan5, color: [0.4, 0.7, 0.9], transform: {scale: 0.6, translate: [0.6, -0.4, 0.1]}}
YAML

cat > "$WORK/tagged.yaml" <<'YAML'
volume: {procedural: none}
image: {width: 128, height: 128}
bricks: {per_axis: 2}
camera: {position: [2.2, -3.4, 2.6]}
surfaces:
  - {procedural: lathe, color: [0.9, 0.6, 0.3], transform: {scale: 0.8, translate: [-0.7, 0, -0.8]}}
  - {procedural: cube_crease2.7, color: [0.4, 0.7, 0.9], transform: {scale: 0.35, rotate: [10, 20, 0], translate: [0.7, 0.4, 0.5]}}
  - {procedural: cube_chaikin, color: [0.5, 0.9, 0.5], transform: {scale: 0.3, translate: [0.8, -0.6, -0.4]}}
  - {procedural: open_grid_none, color: [0.9, 0.5, 0.8], transform: {scale: 0.25, rotate: [60, 0, 0], translate: [-0.2, 1.0, 0.9]}}
YAML

render() {  # render NP SCENE OUT [--set ...] (one rank: without mpirun, which costs seconds)
  local np=$1 scene=$2 out=$3; shift 3
  local args=(render "$WORK/$scene.yaml" -q -o "$WORK/$out.png" --surface-out "$WORK/$out.exr" "$@")
  if [ "$np" = 1 ]; then timeout 120 "$S" "${args[@]}"; else run_np "$np" "${args[@]}"; fi \
    || fail "render $scene on $np rank(s)"
}
# vs_reference_scene NP SCENE MAX_DIFF [--set ...]: SCENE, with the same settings, in the
# reference (ref.png, ref.exr: lib.sh) and on NP ranks (gl.png, gl.exr); colour within MAX_DIFF
# away from silhouettes. Leaves the images for depth_normals.
vs_reference_scene() {
  local np=$1 scene=$2 max_diff=$3; shift 3
  reference "$WORK/$scene.yaml" "$@"
  render "$np" "$scene" gl "$@"
  "$S" compare "$WORK/ref.png" "$WORK/gl.png" --max-diff "$max_diff" --mask-silhouettes "$WORK/ref.exr" \
    --mask-silhouettes "$WORK/gl.exr" --allow-pixels "${ALLOW_PIXELS:-0}" || fail "$scene${*:+ $*} against the reference"
}
depth_normals() {  # depth_normals WHAT [OPTIONS]: the last vs_reference_scene's depth and normals
  "$S" compare-surface "$WORK/ref.exr" "$WORK/gl.exr" --ignore-edges --max-depth-error 1e-3 \
    --max-normal-deg 0.05 --max-holes 0 --max-extra 0 "${@:2}" || fail "$1: depth or normals"
}
ranks() {  # ranks SCENE: 2-4 ranks give the 1-rank image within 1/255
  render 1 "$1" one
  for np in 2 3 4; do
    render "$np" "$1" many
    "$S" compare "$WORK/one.png" "$WORK/many.png" --max-diff 1 | tail -1 || fail "$1: $np ranks differ from 1"
  done
}
bricks() {  # bricks SCENE MAX_DIFF: d = 2, 3 against d = 1
  render 1 "$1" d1 --set bricks.per_axis=1
  for d in 2 3; do
    render 1 "$1" dn --set bricks.per_axis=$d
    "$S" compare "$WORK/d1.png" "$WORK/dn.png" --max-diff "$2" | tail -1 || fail "$1: $d^3 bricks differ from one brick"
  done
}

case $2 in
alone)
  # Measured: 0/255 away from silhouettes.
  vs_reference_scene 1 alone 1
  # Depth and normals of one surface (two overlap, and compare-surface's --ignore-edges leaves out
  # hit/miss edges only, not where one surface's outline lies over the other). pole5 is 2.9 across:
  # measured depth 7.7e-5, normals 0.009 degrees.
  vs_reference_scene 1 alone 1 --set "surfaces=[{procedural: pole5}]"
  depth_normals alone
  ranks alone
  # Each fragment belongs to the brick holding its exact limit point: bricks compose exactly.
  bricks alone 0
  # Orthographic (pass 2 and the reference take Camera::pixelRay's parallel rays from the eye
  # plane; pass 1 rasterises the coarse mesh orthographically): pole5 alone, measured 0/255 away
  # from silhouettes, depth 1.0e-5, normals 0.001 degree (the perspective frame of both surfaces
  # is 20 dB from the orthographic reference); 3 ranks identical to 1.
  vs_reference_scene 1 alone 1 --set camera.projection=orthographic --set "surfaces=[{procedural: pole5}]"
  depth_normals "alone, orthographic"
  mv "$WORK/gl.png" "$WORK/one.png"
  render 3 alone many --set camera.projection=orthographic --set "surfaces=[{procedural: pole5}]"
  "$S" compare "$WORK/one.png" "$WORK/many.png" --max-diff 1 | tail -1 || fail "alone, orthographic: 3 ranks differ from 1"
  ;;
volume)
  # Measured 2/255 (the volume's own ray-casting error), 63 dB away from silhouettes.
  vs_reference_scene 1 volume 3
  "$S" compare "$WORK/ref.png" "$WORK/gl.png" --min-psnr 55 --mask-silhouettes "$WORK/ref.exr" \
    --mask-silhouettes "$WORK/gl.exr" >/dev/null || fail "volume: PSNR against the reference"
  ranks volume
  bricks volume 2
  ;;
metaballs)
  # Measured 0/255 away from silhouettes and the seams where the two surfaces cross.
  vs_reference_scene 1 metaballs 1
  ranks metaballs
  # The merged layer inside a volume too (and its surface image re-cut to the volume's rectangle):
  # measured 2/255, 61 dB.
  vs_reference_scene 1 all_three 3
  render 3 all_three many
  "$S" compare "$WORK/gl.png" "$WORK/many.png" --max-diff 1 | tail -1 || fail "all three: 3 ranks differ from 1"
  # All three under the orthographic camera: measured 2/255, 61.6 dB away from silhouettes; 3
  # ranks identical to 1.
  vs_reference_scene 1 all_three 3 --set camera.projection=orthographic
  render 3 all_three many --set camera.projection=orthographic
  "$S" compare "$WORK/gl.png" "$WORK/many.png" --max-diff 1 | tail -1 || fail "all three, orthographic: 3 ranks differ from 1"
  ;;
open)
  vs_reference_scene 1 open 1
  # Depth and normals of the fan alone (its irregular boundary vertex is in view).
  vs_reference_scene 1 open 1 --set "surfaces=[{procedural: fan5}]"
  depth_normals open
  ranks open
  bricks open 0
  # From the other side: open surfaces are two-sided (both sides drawn, as the reference does).
  vs_reference_scene 3 open 1 --set "camera.position=[-0.3, 3.5, -6.0]"
  depth_normals "open, from behind"
  ;;
tagged)
  vs_reference_scene 1 tagged 1
  # Depth and normals of the lathe alone, from above and below: a crease is a normal
  # discontinuity, so a pixel on it may show either side's normal (up to 42 degrees apart here):
  # pixels whose reference normal turns by over 40 degrees to a neighbour's are left out (74 and
  # 151 of 2,600 and 1,950). Measured: depth 2.4e-5 and 1.1e-5, normals 0.0067 and 0.0077 degrees.
  # (Colour: a crease pixel may show either side's shade; 2 of them do from below.)
  for rot in "[0, 0, 0]" "[180, 0, 0]"; do
    ALLOW_PIXELS=4 vs_reference_scene 1 tagged 1 --set "surfaces=[{procedural: lathe, transform: {scale: 0.8, rotate: $rot, translate: [-0.7, 0, -0.8]}}]"
    depth_normals "tagged, lathe turned $rot" --ignore-creases 40
  done
  ranks tagged
  bricks tagged 0
  # Inside a semi-transparent volume (the volume's rays end at the creased surface).
  ALLOW_PIXELS=4 vs_reference_scene 1 volume 3 --set "surfaces=[{procedural: lathe, transform: {scale: 12, rotate: [20, 30, 0], translate: [0, 0, -10]}}]"
  "$S" compare "$WORK/ref.png" "$WORK/gl.png" --min-psnr 55 --mask-silhouettes "$WORK/ref.exr" \
    --mask-silhouettes "$WORK/gl.exr" >/dev/null || fail "tagged in a volume: PSNR against the reference"
  # Reflection lines across the creases (they break there, as a normal discontinuity should).
  vs_reference_scene 1 tagged 2 --set "surfaces=[{procedural: lathe, shading: reflection_lines, stripes: 8, stripe_width: 0.4}]"
  ;;
reflection)
  # Measured 1/255 (stripe edges, where the colour changes fastest).
  vs_reference_scene 1 reflection 2
  ;;
bad)
  # expect_error NP PATTERN SET...: exit 1 on NP ranks (0: the binary alone, for key errors that
  # take the same parsing path on every rank as the mesh errors do), PATTERN in stderr.
  expect_error() {
    local np=$1 pattern=$2; shift 2
    local sets=()
    for s in "$@"; do sets+=(--set "$s"); done
    if [ "$np" = 0 ]; then
      if timeout 60 "$S" render "$WORK/alone.yaml" -q -o "$WORK/bad.png" "${sets[@]}" 2>"$WORK/err"; then
        fail "accepted: $*"
      fi
    elif run_np "$np" render "$WORK/alone.yaml" -q -o "$WORK/bad.png" "${sets[@]}" 2>"$WORK/err"; then
      fail "accepted: $*"
    fi
    grep -q "$pattern" "$WORK/err" || { cat "$WORK/err"; fail "message for '$*' lacks '$pattern'"; }
  }
  : > "$WORK/empty.obj"
  printf "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 1\nf 1 3 2\nf 1 4 3\nf 1 2 4\nf 2 3 4\n" > "$WORK/nan.obj"
  printf "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 4 3\nf 1 2 4\nf 2 3 9\n" > "$WORK/range.obj"
  printf "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 4 3\nf 1 2 4\nf 2 3 4\nf 2 5 3\n" > "$WORK/nonmanifold.obj"
  printf "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0 0\nv -1 -1 0\nv 0 -1 0\nf 1 2 3 4\nf 1 5 6 7\n" > "$WORK/bowtie.obj"
  printf "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 4 3\nf 1 2 4\nf 2 3 4\nt bevel 2/1/0 1 2 5.0\n" > "$WORK/tag.obj"
  printf "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 4 3\nf 1 2 4\nf 2 3 4\nt crease 2/1/0 0 1 -2\n" > "$WORK/negative.obj"
  expect_error 0 "surfaces\[0\].file'.*is empty" "surfaces=[{file: $WORK/empty.obj}]"
  expect_error 0 "surfaces\[0\].file'.*'nan' is not a finite number" "surfaces=[{file: $WORK/nan.obj}]"
  expect_error 0 "surfaces\[0\].file'.*out of range" "surfaces=[{file: $WORK/range.obj}]"
  expect_error 2 "surfaces\[0\].file'.*non-manifold" "surfaces=[{file: $WORK/nonmanifold.obj}]"
  expect_error 0 "surfaces\[0\].file'.*vertex 0 is non-manifold" "surfaces=[{file: $WORK/bowtie.obj}]"
  expect_error 0 "surfaces\[0\].file'.*line 9: unknown or unsupported subdivision tag 'bevel'" "surfaces=[{file: $WORK/tag.obj}]"
  expect_error 2 "line 9: sharpness -2" "surfaces=[{file: $WORK/negative.obj}]"
  expect_error 2 "surfaces\[1\].file'.*no such file" "surfaces=[{procedural: cube}, {file: $WORK/missing.obj}]"
  expect_error 0 "surfaces\[0\].procedural'.*unknown procedural" "surfaces=[{procedural: pole2}]"
  expect_error 0 "surfaces\[0\].level'" "surfaces=[{procedural: cube, level: 4}]"
  expect_error 0 "surfaces\[0\].transform'.*singular" "surfaces=[{procedural: cube, transform: {scale: 0}}]"
  expect_error 0 "surfaces\[0\].shading'" "surfaces=[{procedural: cube, shading: phong}]"
  expect_error 0 "surfaces\[0\].colour'" "surfaces=[{procedural: cube, colour: [1, 0, 0]}]"
  # The reference refuses alike.
  if "$S" reference "$WORK/alone.yaml" -q -o "$WORK/bad.png" --set "surfaces=[{file: $WORK/nonmanifold.obj}]" \
      2>"$WORK/err"; then fail "reference accepted a non-manifold mesh"; fi
  grep -q "surfaces\[0\].file'.*non-manifold" "$WORK/err" || fail "reference: message lacks the key"
  ;;
serve)
  start_server 2 "$WORK/volume.yaml"
  for req in '{"image.width":128,"image.height":128}' \
             '{"image.width":96,"image.height":112,"camera.position":[40,-70,90],"render.method":"slicing"}'; do
    code=$(frame "$WORK/served.png" "$req")
    [ "$code" = 200 ] || { cat "$WORK/served.png"; fail "serve: $req answered $code"; }
    mapfile -t sets < <(sets_of "$req")
    render_like "$WORK/batch.png" 2 "$WORK/volume.yaml" "${sets[@]}" || fail "render ${sets[*]}"
    same "$WORK/served.png" "$WORK/batch.png" || fail "serve: the frame of $req differs from sortlast render"
  done
  code=$(frame "$WORK/refused.txt" '{"surfaces":[{"procedural":"cube"}]}')
  [ "$code" != 200 ] && grep -q "surfaces" "$WORK/refused.txt" || { cat "$WORK/refused.txt"; fail "serve: a request changing the surfaces was not refused ($code)"; }
  cat "$WORK/refused.txt"; echo
  stop_server || fail "serve: did not stop cleanly on SIGTERM"
  ;;
*)
  fail "unknown mode $2"
  ;;
esac
echo "surfaces $2: ok"
