#!/usr/bin/env bash
# The example simulations (examples/) against `sortlast render` of their own data.
#   gray_scott: on 1-4 ranks (slabs of 11/11/10 on 3, 2x2x1 on 4), the in-situ image of a step
#     against `sortlast render` of V dumped at that step; V published without its ghost layers
#     (strides into the array) and as a float32 copy gives the same image as the float64 array
#     with ghosts (those two on 1 and 3 ranks).
#   particles: on 1-4 ranks (slabs along x, particles migrating between them), the in-situ image
#     against `sortlast render` of the particles dumped at that step.
#   schedule: the built-in actions' --every writes the images of exactly the steps it should, and
#     every step prints its `step S sim_s X vis_s Y mem_mib Z` line.
#
# Tolerance. Particles (laid out in sortlast's own bricks in situ too) must match within 1/255, and
# so must the volume on one rank against `sortlast render` of one brick. Otherwise the volume is
# drawn as one brick per rank in situ and as 2x2x2 kd bricks by `sortlast render`, and brick images
# are RGBA8: each brick a ray crosses rounds once more, so the two differ by 2/255 on a few pixels
# (measured: 1-14 of 16384; tests/mpi/seams.sh and tests/insitu/insitu.sh allow the same between
# brick layouts). There: every pixel within 2/255, at most 0.25 % of them beyond 1/255.
# Usage: examples.sh MODE SORTLAST GRAY_SCOTT PARTICLES
source "$(dirname "$0")/../mpi/lib.sh" "$2"
MODE=$1 GS=$3 PS=$4
cd "$WORK"
run_example() { local np=$1; shift; timeout 120 "${MPIRUN[@]}" -np "$np" "$@"; }
render_one() { timeout 120 "${MPIRUN[@]}" -np 1 "$SORTLAST" render --quiet "$@"; }
same() {  # same A B: within 1/255 on every pixel
  "$SORTLAST" compare "$1" "$2" --max-diff 1 --diff "${2%.png}_diff.png" || fail "$1 and $2 differ (see above)"
}
near() {  # near A B: within 2/255, and at most 0.25 % of the pixels beyond 1/255 (see the top)
  local pixels=$3
  "$SORTLAST" compare "$1" "$2" --max-diff 2 || fail "$1 and $2 differ by more than 2/255"
  "$SORTLAST" compare "$1" "$2" --max-diff 1 --allow-pixels $((pixels / 400)) || fail "$1 and $2 differ (see above)"
}

# Both sides see the same scene: the actions' camera is in the simulation's coordinates (the grid
# spans 0 ... N-1), sortlast render's in its own (the grid centred on the origin).
N=32 STEPS=400 W=128
read -r C PX PY PZ < <(awk -v n=$N 'BEGIN { c = (n - 1) / 2; print c, c + 50, c + 45, c + 74 }')
TF='[[0, 0, 0, 0, 0], [0.25, 0.05, 0.1, 0.4, 0], [0.42, 0.15, 0.35, 0.85, 0.02], [0.55, 0.95, 0.55, 0.2, 0.12], [0.68, 1, 0.8, 0.45, 0.4], [0.85, 1, 1, 0.9, 0.7], [1, 1, 1, 1, 0.85]]'
gray_scott_actions() {
  cat <<YAML
renders:
  - name: v
    output: "$1/v_{step}.png"
    trigger: {every: 100}
    scene:
      image: {width: $W, height: $W}
      camera: {look_at: [$C, $C, $C], position: [$PX, $PY, $PZ], fov: 30}
      transfer: {range: [0, 0.5], points: $TF}
      render: {sample_spacing: 0.5}
YAML
}

# The step pinned on both sides: render.sample_spacing auto chooses against the exact model where
# the accuracy estimate applies (a batch render) and by the probes' differences where it does not
# (in situ: the simulation's arrays), so the two could take different steps.
render_dump() {  # render_dump OUT [--set ...]: V dumped on $np ranks, as the actions draw it
  render_one -o "$1" --set volume.file=np$np/f64.raw --set volume.type=float32 \
    --set "volume.dims=[$N,$N,$N]" --set image.width=$W --set image.height=$W \
    --set "camera.look_at=[0,0,0]" --set "camera.position=[50,45,74]" --set camera.fov=30 \
    --set "transfer.range=[0,0.5]" --set "transfer.points=$TF" --set render.sample_spacing=0.5 "${@:2}" ||
    fail "render np=$np"
}

case $MODE in
gray_scott)
  # Step 400: the fronts have grown across the slab faces of 2 and 3 ranks. The variants without
  # ghosts and in float32 run on 1 and 3 ranks (one slab, and odd slabs with faces), f64 on all.
  for np in 1 2 3 4; do
    variants=(f64)
    [ $np = 1 ] || [ $np = 3 ] && variants+=(noghosts f32)
    for variant in "${variants[@]}"; do
      case $variant in
        f64) flags=() ;;
        noghosts) flags=(--no-ghosts) ;;
        f32) flags=(--float32) ;;
      esac
      dir=np$np/$variant
      mkdir -p np$np
      gray_scott_actions "$dir" >"$dir.yaml"
      run_example "$np" "$GS" --size $N --steps $STEPS --actions "$dir.yaml" --dump-step $STEPS \
        --dump "$dir.raw" "${flags[@]}" >"$dir.log" || { cat "$dir.log"; fail "gray_scott np=$np $variant"; }
    done
    insitu=np$np/f64/v_000400.png
    render_dump np$np/render.png
    near np$np/render.png "$insitu" $((W * W))
    if [ $np = 1 ]; then  # the same bricks: one
      render_dump np1/render_one_brick.png --set bricks.per_axis=1
      same np1/render_one_brick.png "$insitu"
    fi
    if [ ${#variants[@]} -gt 1 ]; then
      cmp -s np$np/f64.raw np$np/noghosts.raw || fail "np=$np: --no-ghosts changed the simulation"
      same "$insitu" np$np/noghosts/v_000400.png
      same "$insitu" np$np/f32/v_000400.png
      echo "gray_scott on $np ranks: in-situ image = sortlast render of the dump; no ghosts and float32 agree"
    else
      echo "gray_scott on $np ranks: in-situ image = sortlast render of the dump"
    fi
  done
  ;;
particles)
  for np in 1 2 3 4; do
    mkdir -p np$np
    cat >np$np/actions.yaml <<YAML
renders:
  - name: p
    output: "np$np/p_{step}.png"
    trigger: {every: 50}
    scene:
      image: {width: $W, height: $W, background: [0.06, 0.07, 0.1]}
      camera: {look_at: [8, 7, 8], position: [38, 33, 56], fov: 30}
      particles: {radius: 0.6, color: [0.45, 0.7, 1.0]}
YAML
    run_example "$np" "$PS" --particles 2000 --steps 150 --actions np$np/actions.yaml --dump-step 150 \
      --dump np$np/p.raw >np$np/log || { cat np$np/log; fail "particles np=$np"; }
    [ "$(stat -c %s np$np/p.raw)" = 24000 ] || fail "np=$np: the dump does not hold 2000 particles"
    render_one -o np$np/render.png --set volume.procedural=none --set particles.file=np$np/p.raw \
      --set particles.radius=0.6 --set "particles.color=[0.45,0.7,1.0]" --set image.width=$W \
      --set image.height=$W --set "image.background=[0.06,0.07,0.1]" --set "camera.look_at=[8,7,8]" \
      --set "camera.position=[38,33,56]" --set camera.fov=30 || fail "render np=$np"
    same np$np/render.png np$np/p_000150.png
    echo "particles on $np ranks: in-situ image = sortlast render of the dump"
  done
  ;;
schedule)
  line='^step [0-9]+ sim_s [0-9.]+ vis_s [0-9.]+ mem_mib [0-9.]+( |$)'
  expect() {  # expect DIR PREFIX STEPS...: exactly these images
    local dir=$1 prefix=$2 want=""
    shift 2
    for s in "$@"; do want+=$(printf '%s_%06d.png\n' "$prefix" "$s")$'\n'; done
    got=$(ls "$dir")$'\n'
    [ "$got" = "$want" ] || fail "$dir holds [${got//$'\n'/ }], expected [${want//$'\n'/ }]"
  }
  for np in 1 2; do
    run_example $np "$GS" --size 16 --steps 7 --every 3 --width 32 --out gs$np >gs$np.log || fail "gray_scott"
    expect gs$np v 0 3 6
    [ "$(grep -Ec "$line" gs$np.log)" = 8 ] || { cat gs$np.log; fail "gray_scott: not one step line per step"; }
    awk '$2 % 3 == 0 && !($8 > 0) {exit 1}' gs$np.log || fail "gray_scott: a rendered step reports no memory"
    run_example $np "$PS" --particles 300 --steps 5 --every 2 --width 32 --out ps$np >ps$np.log || fail "particles"
    expect ps$np p 0 2 4
    [ "$(grep -Ec "$line" ps$np.log)" = 6 ] || { cat ps$np.log; fail "particles: not one step line per step"; }
  done
  # Bad options stop every rank with a message and exit code 2.
  set +e
  run_example 2 "$GS" --size 16 --every 0 >bad.log 2>&1
  rc=$?
  set -e
  if [ $rc != 2 ] || ! grep -q -- "--every" bad.log; then
    cat bad.log
    fail "gray_scott --every 0: rc $rc"
  fi
  echo "the images of exactly the --every steps; one line per step"
  ;;
*) fail "unknown mode $MODE" ;;
esac
