#!/usr/bin/env bash
# Glow emitters on the GL path (docs/glow.md) against `sortlast reference`, all within
# one 8-bit level (the float GL integral is within ~1e-6 of the double one, half-float bricks
# within 2^-11 relative, both far under 1/255 after the tone map): glow alone on 1-4 ranks and
# d = 1, 2, 3 bricks, every compositing strategy, the hard cameras (rays through the centre M,
# along the axis, in the dividing planes of the emitter and of the bricks), an orbit that moves
# the emitters, glow behind a metaball surface, glow inside a volume (ray caster), with metaballs
# in the volume; the refusals.
# Usage: glow.sh SORTLAST DATA_DIR [MODE]
#   alone     sections 1-4: against the reference on 1-4 ranks, bricks, strategies, orthographic,
#             hard cameras, orbit
#   surfaces  section 5: behind metaballs and around a subdivision surface
#   volume    section 6: inside a ray-cast volume (clipped, dense, far emitter, with metaballs,
#             also orthographic)
#   bad       section 7: the refusals
#   (no MODE: all four)
source "$(dirname "$0")/lib.sh" "$1"
data=$2
mode=${3:-all}
want() { [ "$mode" = all ] || [ "$mode" = "$1" ]; }
scene="$data/glow.yaml"
S=$SORTLAST

# near A B what [extra compare args]: every channel within one level (MAXD=n: n levels).
near() {
  local a=$1 b=$2 what=$3; shift 3
  out=$("$S" compare "$a" "$b" --max-diff "${MAXD:-1}" "$@") || { echo "$out"; fail "$what"; }
  echo "ok: $what: $(echo "$out" | head -1)"
}

if want alone; then
# 1. Glow alone vs the reference, d = 1, 2, 3 (2 ranks; d = 3: 27 bricks over 3 ranks).
for d in 1 2 3; do
  "$S" reference "$scene" --set bricks.per_axis=$d -o "$WORK/ref$d.png" -q
  run_np 2 render -q "$scene" --set bricks.per_axis=$d -o "$WORK/gl$d.png"
  near "$WORK/gl$d.png" "$WORK/ref$d.png" "d = $d vs reference"
done
# bricks.per_axis: auto is one brick for glow alone (the same image as d = 1).
run_np 1 render -q "$scene" --set bricks.per_axis=auto -o "$WORK/glauto.png" --stats "$WORK/auto.json"
grep -Eq '"bricks_per_axis": *1([^0-9]|$)' "$WORK/auto.json" || fail "bricks.per_axis: auto did not give one brick for glow alone"
near "$WORK/glauto.png" "$WORK/ref1.png" "d = auto vs reference"
# 2. Rank invariance, 1-4 ranks and the swap strategies (d = 2), against 1 rank.
run_np 1 render -q "$scene" -o "$WORK/one.png"
for np in 2 3 4; do
  run_np $np render -q "$scene" -o "$WORK/np$np.png"
  near "$WORK/np$np.png" "$WORK/one.png" "$np ranks vs 1"
done
for st in binary-swap radix-k; do
  run_np 4 render -q "$scene" --set compositing.strategy=$st -o "$WORK/$st.png"
  near "$WORK/$st.png" "$WORK/one.png" "$st on 4 ranks vs direct send on 1"
done
near "$WORK/one.png" "$WORK/ref2.png" "1 rank vs reference"
# tone_map none: radiance above 1 travels between ranks unclamped until the final clamp.
"$S" reference "$scene" --set glow.tone_map=none --set glow.intensity=0.6 -o "$WORK/ref_none.png" -q
run_np 3 render -q "$scene" --set glow.tone_map=none --set glow.intensity=0.6 -o "$WORK/gl_none.png"
near "$WORK/gl_none.png" "$WORK/ref_none.png" "tone_map none, glow above 1, 3 ranks vs reference"

# Orthographic (the glow pass and the reference take Camera::pixelRay's parallel rays from the eye
# plane): measured within 1 level (72.7 dB; the perspective frame is 31 dB from this reference),
# 3 ranks identical to 1.
"$S" reference "$scene" --set camera.projection=orthographic -o "$WORK/ortho_ref.png" -q
run_np 1 render -q "$scene" --set camera.projection=orthographic -o "$WORK/ortho1.png"
near "$WORK/ortho1.png" "$WORK/ortho_ref.png" "orthographic, 1 rank vs reference"
run_np 3 render -q "$scene" --set camera.projection=orthographic -o "$WORK/ortho3.png"
MAXD=0 near "$WORK/ortho3.png" "$WORK/ortho1.png" "orthographic, 3 ranks vs 1"

# 3. Hard cameras, odd sizes so the centre pixel's ray is exactly the camera's axis: one emitter
# at the origin along +x (its plane x = 0 is also a brick plane; y = 0 and z = 0 too).
one="glow.emitters=[{center: [0, 0, 0], direction: [1, 0, 0], a: 1, b: 1, color: [1, 0.8, 0.5]}]"
hard() {  # hard what position up
  local what=$1 pos=$2 up=$3
  local args=(--set "$one" --set glow.core_radius=0.02 --set glow.intensity=0.1 --set image.width=97
              --set image.height=97 --set "camera.position=$pos" --set "camera.look_at=[0, 0, 0]"
              --set "camera.up=$up")
  # Float frames (.exr): reading them refuses any NaN or Inf value (the 8-bit conversion would
  # hide one as 0 or 255).
  "$S" reference "$scene" "${args[@]}" -o "$WORK/href.exr" -q
  run_np 3 render -q "$scene" "${args[@]}" -o "$WORK/hgl.exr"
  near "$WORK/hgl.exr" "$WORK/href.exr" "hard camera: $what (float frames, all finite)"
}
hard "rays through M" "[0.7, 1.3, 3.1]" "[0, 1, 0]"
hard "along the axis into the beam (in the y = 0 and z = 0 brick planes)" "[4, 0, 0]" "[0, 1, 0]"
hard "along the axis from behind" "[-4, 0, 0]" "[0, 1, 0]"
hard "along the dividing plane x = 0" "[0, 0.6, 4]" "[0, 1, 0]"

# 4. An orbit moving the emitters: frame 1 (moved) vs the reference's frame 1.
orbit=(--set camera.orbit.frames=4 --set "glow.emitters=[{center: [-0.3, 0, 0], velocity: [0.2, 0.05, 0], turn: [0, 0.3, 0], a_rate: 0.1, color: [0.4, 1, 0.6]}]")
"$S" reference "$scene" "${orbit[@]}" -o "$WORK/oref.png" -q
run_np 2 render -q "$scene" "${orbit[@]}" -o "$WORK/ogl.png"
near "$WORK/ogl_0001.png" "$WORK/oref_0001.png" "orbit frame 1 (emitter moved) vs reference"
near "$WORK/ogl_0003.png" "$WORK/oref_0003.png" "orbit frame 3 vs reference"

fi

if want surfaces; then
# 5. Behind a metaball surface: the glow stops at the surface's depth. The surface's own pixels
# off the reference (silhouettes: measured with the glow off) are all that may differ.
balls=(--set particles.procedural=layers --set particles.count=64 --set glow.box=auto
       --set "glow.emitters=[{center: [0.1, 0.05, -0.3], direction: [0, 1, 1], a: 1, b: 1, color: [1, 0.6, 0.2]}]"
       --set glow.intensity=0.2 --set glow.core_radius=0.03)
for g in off on; do
  extra=(); [ $g = off ] && extra=(--set "glow.emitters=[]")
  "$S" reference "$scene" "${balls[@]}" "${extra[@]}" -o "$WORK/b${g}_ref.png" -q
  run_np 3 render -q "$scene" "${balls[@]}" "${extra[@]}" -o "$WORK/b${g}_gl.png"
done
surface_px=$("$S" compare "$WORK/boff_gl.png" "$WORK/boff_ref.png" --max-diff 1 --allow-pixels 1000000 | sed -n 's/pixels_over_1=//p')
near "$WORK/bon_gl.png" "$WORK/bon_ref.png" "glow behind metaballs (the surface's own $surface_px pixels aside)" --allow-pixels "$surface_px"
# The glow is there: the image differs from the one without it.
"$S" compare "$WORK/bon_gl.png" "$WORK/boff_gl.png" --max-diff 8 >/dev/null && fail "metaball scene: no visible glow"

# 5b. Behind and around a subdivision surface (the `surfaces` key): the glow stops at the limit
# surface's depth in every brick it crosses (3 ranks, 2^3 bricks). Pixels within 2 of the surface's
# silhouettes are left out (coverage is the coarse mesh's: docs/subdivision.md); measured 1 level.
surf=(--set bricks.per_axis=2 --set "surfaces=[{procedural: pole5, color: [0.5, 0.7, 0.5], transform: {scale: 0.5, translate: [0.3, -0.2, 0.4]}}]")
"$S" reference "$scene" "${surf[@]}" -o "$WORK/sref.png" --surface-out "$WORK/sref.exr" -q
run_np 3 render -q "$scene" "${surf[@]}" -o "$WORK/sgl.png" --surface-out "$WORK/sgl.exr"
near "$WORK/sgl.png" "$WORK/sref.png" "glow around a subdivision surface vs reference" \
  --mask-silhouettes "$WORK/sref.exr" --mask-silhouettes "$WORK/sgl.exr"

fi

if want volume; then
# 6. Inside a semi-transparent volume (ray caster): per step, the step's exact glow times the
# transmittance, as the reference. The volume alone is 2-3 levels off the reference here (its own
# sampling: PSNR 61 dB), so the bound is that: 3 levels, 60 dB (measured with glow: 2, 64-65 dB).
# (The volume's step pinned at 0.5 voxel, where these bounds were measured: `auto` may take 2.)
vol=(--set volume.procedural=blobs --set "volume.dims=[32,32,32]" --set render.sample_spacing=0.5
     --set glow.box=auto --set glow.intensity=0.02
     --set glow.core_radius=0.03 --set "glow.emitters=[{center: [0.1, 0, 0.05], direction: [1, 0.3, 0], color: [1, 0.6, 0.2]}]")
"$S" reference "$scene" "${vol[@]}" -o "$WORK/vref.png" -q
run_np 2 render -q "$scene" "${vol[@]}" -o "$WORK/vgl.png"
MAXD=3 near "$WORK/vgl.png" "$WORK/vref.png" "glow in a volume vs reference" --min-psnr 60
run_np 4 render -q "$scene" "${vol[@]}" --set transfer.preintegrated=true -o "$WORK/vpre.png"
MAXD=3 near "$WORK/vpre.png" "$WORK/vref.png" "glow in a volume, pre-integrated, 4 ranks vs reference" --min-psnr 60
for d in 1 3; do
  run_np 3 render -q "$scene" "${vol[@]}" --set bricks.per_axis=$d -o "$WORK/vgl$d.png"
  near "$WORK/vgl$d.png" "$WORK/vgl.png" "glow in a volume, d = $d vs d = 2"
done
# The glow is there: the image differs from the volume alone.
run_np 2 render -q "$scene" "${vol[@]}" --set "glow.emitters=[]" -o "$WORK/vgl0.png"
"$S" compare "$WORK/vgl.png" "$WORK/vgl0.png" --max-diff 8 >/dev/null && fail "volume scene: no visible glow"
# Clipped (clip.planes, clip.box cut the volume only): the glow in front of and behind the cut is
# seen as through empty space, in the reference as in the ray caster, whose span's end segments
# reach the cut. An oblique plane through the emitter's core, 3 ranks on 27 bricks: measured 3
# levels, 66.0 dB (with whole steps at the cut, 2 ranks on 8 bricks: 8 levels, 64.9 dB); 1 rank on 8 bricks within 1
# of it. A box keeping x < -0.05: the bricks beyond x = 0, which hold the core and the beam, have no
# volume left and still draw their glow; measured 3 levels, 66.0 dB.
cut=(--set "clip.planes=[{normal: [1, 0.2, -0.3], offset: 0.05}]")
"$S" reference "$scene" "${vol[@]}" "${cut[@]}" -o "$WORK/cref.png" -q
run_np 3 render -q "$scene" "${vol[@]}" "${cut[@]}" --set bricks.per_axis=3 -o "$WORK/cgl3.png"
MAXD=3 near "$WORK/cgl3.png" "$WORK/cref.png" "glow in a clipped volume, 3 ranks vs reference" --min-psnr 62
run_np 1 render -q "$scene" "${vol[@]}" "${cut[@]}" -o "$WORK/cgl1.png"
near "$WORK/cgl1.png" "$WORK/cgl3.png" "glow in a clipped volume, 1 rank vs 3"
crop=(--set "clip.box=[[-20, -20, -20], [-0.05, 20, 20]]")
"$S" reference "$scene" "${vol[@]}" "${crop[@]}" -o "$WORK/bref.png" -q
run_np 2 render -q "$scene" "${vol[@]}" "${crop[@]}" -o "$WORK/bgl.png"
MAXD=3 near "$WORK/bgl.png" "$WORK/bref.png" "glow in a cropped volume (bricks without volume), 2 ranks vs reference" --min-psnr 62
"$S" compare "$WORK/bgl.png" "$WORK/vgl.png" --max-diff 8 >/dev/null && fail "clip.box: the volume was not cropped"

# An emitter core inside a dense absorbing volume (black, transmittance about 0.15 across it), its
# axis and dividing plane through it (a != b): the rays grazing the core are where the ray caster's
# pieces (weighted by their mean transmittance, corrected to first order) must shrink to single
# segments, and its plane is where they must be split (render/volume/raycast_glow.frag.glsl: at
# most 1/1024 of radiance per pixel against the reference's rule). Measured 1 level, 71.2 dB (2
# levels, 57.2 dB while the span's end samples kept whole steps at the box's faces, step 1/4
# voxel); pieces as long as between planes, with no bound from the ray's distance to the core and
# axis: 124 levels, 42.5 dB (measured then).
dense=(--set volume.procedural=sphere --set "volume.dims=[32,32,32]" --set render.method=raycast
       --set "transfer.points=[[0, 0, 0, 0, 0.06], [1, 0, 0, 0, 0.06]]" --set render.sample_spacing=0.25
       --set glow.box=auto --set glow.tone_map=none --set glow.intensity=1 --set glow.core_radius=0.01
       --set "glow.emitters=[{center: [0.5, 0.3, 0.6], direction: [1, 0.2, 0.1], a: 1, b: 0.3, color: [1, 0.6, 0.2]}]")
"$S" reference "$scene" "${dense[@]}" -o "$WORK/dref.png" -q
run_np 2 render -q "$scene" "${dense[@]}" -o "$WORK/dgl.png"
MAXD=3 near "$WORK/dgl.png" "$WORK/dref.png" "emitter core in a dense volume vs reference" --min-psnr 55
# A far emitter (30 units off, b = 0: its field falls from a / r to 0 across its plane, which cuts
# the volume) through the same black volume on a black background: its field curves so little that
# pieces run across whole bricks, so each must be split at the plane (the case above does not see
# that rule: its pieces are short). Measured 1 level, 74.3 dB (2 levels, 62.0 dB with whole steps
# at the box's faces); with no plane split after a ray's first piece, 8 levels (68 pixels over 2),
# 56.5 dB (measured then). Dropping the slope
# term instead stays within 2 levels here too (61.9 dB): no case found shows it in 8 bits
# (docs/glow.md, "What is left").
far=("${dense[@]}" --set "image.background=[0, 0, 0]" --set glow.intensity=12
     --set "glow.emitters=[{center: [30, 0, 0], direction: [0, 1, 0.3], a: 1, b: 0, color: [1, 1, 1]}]")
"$S" reference "$scene" "${far[@]}" -o "$WORK/fref.png" -q
run_np 2 render -q "$scene" "${far[@]}" -o "$WORK/fgl.png"
MAXD=2 near "$WORK/fgl.png" "$WORK/fref.png" "far emitter's plane across a dense volume vs reference" --min-psnr 58

# Volume, metaballs and glow in the same bricks (tests/data/mixed.yaml, ray caster): the glow stops
# at the surface inside the volume's rays too. That scene alone is 4 levels, 56 dB off the
# reference (its metaball silhouettes and volume sampling); the glow may not make it worse.
mixed=(--set render.method=raycast --set image.width=128 --set image.height=128 --set glow.intensity=0.05
       --set glow.core_radius=0.03 --set "glow.emitters=[{center: [0, 0, 0], direction: [0, 1, 0], color: [1, 0.6, 0.2]}]")
"$S" reference "$data/mixed.yaml" "${mixed[@]}" -o "$WORK/mref.png" -q
run_np 3 render -q "$data/mixed.yaml" "${mixed[@]}" -o "$WORK/mgl.png"
MAXD=4 near "$WORK/mgl.png" "$WORK/mref.png" "glow in a volume with metaballs vs reference" --min-psnr 55
# The same seen orthographically (the ray caster's GLOW variant and the metaball passes on parallel
# rays): measured 57.0 dB, one pixel over 4 levels (59, a metaball silhouette pixel that is as far
# off without the glow, tests/mpi/particles.sh mixed).
"$S" reference "$data/mixed.yaml" "${mixed[@]}" --set camera.projection=orthographic -o "$WORK/moref.png" -q
run_np 3 render -q "$data/mixed.yaml" "${mixed[@]}" --set camera.projection=orthographic -o "$WORK/mogl.png"
MAXD=4 near "$WORK/mogl.png" "$WORK/moref.png" "orthographic glow in a volume with metaballs vs reference" \
  --min-psnr 55 --allow-pixels 2

fi

if want bad; then
# 7. Refusals, naming both keys; every rank exits non-zero.
refuse() {
  local what=$1 want=$2; shift 2
  local rc=0
  run_np 2 render -q "$scene" -o "$WORK/x.png" "$@" >"$WORK/stdout" 2>"$WORK/stderr" || rc=$?
  [ "$rc" != 0 ] && [ "$rc" != 124 ] || fail "$what: exit code $rc"
  grep -qF -- "$want" "$WORK/stderr" || { cat "$WORK/stderr"; fail "$what: message lacks '$want'"; }
  echo "ok: refused $what"
}
refuse "compositing.precision rgba8" "'glow.emitters' and 'compositing.precision: rgba8'" --set compositing.precision=rgba8
refuse "render.method slicing in a volume" "'glow.emitters' and 'render.method: slicing'" \
  --set volume.procedural=blobs --set "volume.dims=[16,16,16]" --set render.method=slicing --set glow.box=auto
refuse "adaptive blocks" "'glow.emitters' and 'adaptive.tolerance'" \
  --set volume.procedural=blobs --set "volume.dims=[16,16,16]" --set adaptive.tolerance=0.01 --set glow.box=auto
fi
echo "glow ($mode): all cases passed"
