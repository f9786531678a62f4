#!/usr/bin/env bash
# The fixed scene set: one frame of every renderer, compositing strategy, particle
# method, subdivision surfaces, glow, a service frame and an in-situ step, written to OUT as float
# EXR (the unrounded frame; particle and surface scenes also their surface image, t and normal) and
# one PNG (the service sends 8-bit frames only). Renders at small sizes so the whole set takes
# about a minute on 2 cores.
# Usage: render_set.sh SORTLAST INSITU_DRIVER DATA_DIR OUT_DIR
# check.sh renders it and compares it with tests/golden/expected in float; a restructure that
# must not change behaviour renders it before and after and compares with tolerance 0.
set -euo pipefail
SL=$(realpath "$1")
DRIVER=$(realpath "$2")
DATA=$(realpath "$3")
OUT=$(mkdir -p "$4" && realpath "$4")
source "$(dirname "$0")/../service/service_lib.sh" "$SL"  # lib.sh (run_np, WORK), start_server, frame

# pin: the step of the scenes that leave it at its default (`auto`) pinned at the 0.5 voxel they
# were recorded at: `auto` chooses from probe frames, and a choice near its threshold could flip
# on another CPU's rounding (tests/mpi/auto_spacing.sh tests `auto`).
pin=(--set render.sample_spacing=0.5)
small=(--set image.width=96 --set image.height=96)
# r NAME NP SCENE [--set ...]: one frame to OUT/NAME.exr (SCENE `default`: the built-in scene)
r() {
  local name=$1 np=$2 scene=$3; shift 3
  [ "$scene" = default ] && scene=() || scene=("$scene")
  run_np "$np" render -q "${scene[@]}" -o "$OUT/$name.exr" "$@" || fail "render $name"
}
# rs: as r, with the surface image too (OUT/NAME.surface.exr)
rs() { local name=$1; r "$@" --surface-out "$OUT/$name.surface.exr"; }

# Volumes: both renderers, each compositing strategy and precision, the ray caster's options.
r volume_slicing_direct 2 default "${small[@]}" "${pin[@]}" --set render.method=slicing
r volume_raycast_binary_swap 3 default "${small[@]}" "${pin[@]}" --set compositing.strategy=binary-swap
r volume_raycast_radix_k 4 "$DATA/neghip.yaml" "${small[@]}" --set render.method=raycast \
  --set compositing.strategy=radix-k --set render.sample_spacing=0.5
r volume_slicing_preintegrated 2 "$DATA/marschner_lobb.yaml" --set transfer.preintegrated=true
r volume_raycast_adaptive_step 2 "$DATA/neghip.yaml" "${small[@]}" --set render.method=raycast \
  --set render.adaptive_step=true
r volume_adaptive_sampling 2 "$DATA/neghip.yaml" "${small[@]}" --set render.method=raycast \
  --set adaptive.tolerance=10
r volume_raycast_shading 1 "$DATA/neghip.yaml" "${small[@]}" --set render.method=raycast \
  --set render.shading=true
r volume_slicing_shading_rgba8 3 "$DATA/neghip.yaml" "${small[@]}" --set render.shading=true \
  --set compositing.precision=rgba8
r volume_colormap 2 default "${small[@]}" "${pin[@]}" --set transfer.colormap=viridis
r volume_raycast_egl 2 default "${small[@]}" "${pin[@]}" --set render.backend=egl

# Particles: every method, anisotropic smoothing, a volume around them.
rs particles_billboards 2 "$DATA/dam_break.yaml" "${small[@]}" --set particles.method=billboards
rs particles_grid 3 "$DATA/dam_break.yaml" "${small[@]}" --set particles.method=grid
rs particles_grid_egl 2 "$DATA/dam_break.yaml" "${small[@]}" --set particles.method=grid \
  --set render.backend=egl
rs particles_slices 2 "$DATA/dam_break.yaml" "${small[@]}" --set particles.method=slices
rs particles_anisotropic 2 "$DATA/dam_break.yaml" "${small[@]}" --set particles.smoothing=anisotropic
rs particles_mixed_raycast 2 "$DATA/mixed.yaml" "${small[@]}" "${pin[@]}" --set render.method=raycast

# Subdivision surfaces alone (reflection lines) and in a volume.
surf='[{procedural: pole5, color: [0.9, 0.6, 0.3], transform: {translate: [-0.3, 0, 0]}}, {procedural: torus, level: 1, shading: reflection_lines, transform: {scale: 0.35, rotate: [70, 0, 20], translate: [0.6, -0.2, 0.2]}}]'
rs surfaces 2 default "${small[@]}" --set volume.procedural=none --set "camera.position=[1.6, 1.0, 2.6]" \
  --set "surfaces=$surf"
rs surfaces_volume 3 default "${small[@]}" "${pin[@]}" --set volume.procedural=sphere --set "volume.dims=[32,32,32]" \
  --set "transfer.points=[[0, 1, 0.5, 0.1, 0], [1, 1, 0.5, 0.1, 0.05]]" \
  --set "surfaces=[{procedural: pole5, color: [0.3, 0.6, 0.9], transform: {scale: 14}}]"

# Glow: alone, and inside a ray-cast volume.
r glow_alone 2 "$DATA/glow.yaml" "${small[@]}"
r glow_volume 3 "$DATA/glow.yaml" "${small[@]}" "${pin[@]}" --set volume.procedural=blobs --set "volume.dims=[32,32,32]" \
  --set glow.box=auto --set glow.intensity=0.02 --set glow.core_radius=0.03

# A service frame (PNG: the service sends 8-bit frames) from a resident session on 2 ranks.
start_server 2 "$DATA/neghip.yaml" --set render.method=raycast
code=$(frame "$OUT/service_frame.png" '{"image.width": 96, "image.height": 96, "camera.position": [60, -30, 80], "compositing.strategy": "binary-swap"}')
[ "$code" = 200 ] || fail "service frame: HTTP $code"
rm -f "$OUT/service_frame.png.headers" "$OUT/service_frame.png.stats.json"  # dates and timings
stop_server || fail "service did not stop"

# An in-situ step: the test driver's analytic field on an uneven decomposition of 3 ranks.
cat > "$WORK/actions.yaml" <<YAML
renders:
  - name: v
    output: "$WORK/insitu_{step}.exr"
    scene: {image: {width: 96, height: 96}, render: {method: raycast, sample_spacing: 0.5}}
YAML
timeout 120 "${MPIRUN[@]}" -np 3 "$DRIVER" --size 24 --split uneven --actions "$WORK/actions.yaml" \
  > "$WORK/insitu.log" 2>&1 || { cat "$WORK/insitu.log"; fail "in-situ driver"; }
mv "$WORK/insitu_000000.exr" "$OUT/insitu_step.exr"
echo "render_set: $(ls "$OUT" | wc -l) files in $OUT"
