# shellcheck shell=bash disable=SC2034  # SORTLAST_BACKEND is for the scripts that source this
# Sourced (not run) by the sbatch scripts in this folder. Defines
#
#   sortlast_run NRANKS COMMAND [ARGS...]   start COMMAND as NRANKS MPI ranks (empty: one per
#                                           Slurm task of the job)
#
# and picks the launcher from LAUNCHER:
#   srun    srun --mpi=pmix: Slurm starts the ranks itself. Needs an Open MPI built with PMIx (Debian
#           12's is) and Slurm's pmix plugin (`srun --mpi=list` names pmix).
#   mpirun  Open MPI's mpirun inside the allocation: it reads the nodes and tasks from Slurm and
#           starts its own daemons through srun, so it works where srun has no pmix plugin.
#   auto    (default) srun when `srun --mpi=list` names pmix, else mpirun.
#
# It also sets SORTLAST_BACKEND, the render.backend for the job: egl where Slurm gave the job GPUs
# (render.device auto then spreads each node's ranks over its GPUs), else osmesa; BACKEND
# overrides. And it exports LP_NUM_THREADS=--cpus-per-task unless set: llvmpipe's threads per rank.
#
# Both launchers give each rank its CPUs: srun binds a rank to its --cpus-per-task cores (what llvmpipe
# renders on), mpirun gets --bind-to none (Open MPI would bind each rank to one core, and llvmpipe
# would render on that one core). LP_NUM_THREADS, when set, is passed on to the ranks.

sortlast_pick_launcher() {
  SORTLAST_LAUNCHER=${LAUNCHER:-auto}
  if [ "$SORTLAST_LAUNCHER" = auto ]; then
    local plugins
    plugins=$(srun --mpi=list 2>&1 || true)  # whole, not piped: grep -q could SIGPIPE it under pipefail
    case $plugins in
      *pmix*) SORTLAST_LAUNCHER=srun ;;
      *) SORTLAST_LAUNCHER=mpirun ;;
    esac
  fi
  case $SORTLAST_LAUNCHER in
    srun | mpirun) echo "launcher: $SORTLAST_LAUNCHER" >&2 ;;
    *) echo "LAUNCHER must be auto, srun or mpirun, not '$SORTLAST_LAUNCHER'" >&2; return 2 ;;
  esac
}

sortlast_run() {
  local n=$1
  shift
  local cmd
  if [ "$SORTLAST_LAUNCHER" = srun ]; then
    # --kill-on-bad-exit: a rank that dies ends the others at once (some sites default to 0).
    # --cpus-per-task again: srun from Slurm 22.05 on does not take it from sbatch.
    cmd=(srun --mpi=pmix --kill-on-bad-exit=1 --cpus-per-task="${SLURM_CPUS_PER_TASK:-1}")
    if [ -n "$n" ]; then
      # Pack the ranks onto as few nodes as hold them (one rank per GPU stays one rank per GPU).
      local per_node=${SLURM_NTASKS_PER_NODE:-$n}
      cmd+=(--ntasks="$n" --nodes=$(((n + per_node - 1) / per_node)))
    fi
  else
    cmd=(mpirun --bind-to none)
    if [ -n "${LP_NUM_THREADS:-}" ]; then cmd+=(-x LP_NUM_THREADS); fi
    if [ -n "$n" ]; then cmd+=(-np "$n"); fi
  fi
  "${cmd[@]}" "$@"
}

sortlast_pick_launcher
if [ -n "${BACKEND:-}" ]; then
  SORTLAST_BACKEND=$BACKEND
elif [ -n "${SLURM_JOB_GPUS:-}${SLURM_GPUS_ON_NODE:-}" ]; then
  SORTLAST_BACKEND=egl
else
  SORTLAST_BACKEND=osmesa
fi
if [ -z "${LP_NUM_THREADS:-}" ] && [ -n "${SLURM_CPUS_PER_TASK:-}" ]; then
  export LP_NUM_THREADS=$SLURM_CPUS_PER_TASK
fi

# Where each rank rendered: the ranks_gl list of a --stats file, one line a rank.
sortlast_show_devices() {
  python3 - "$1" <<'PY'
import json, sys
for r in json.load(open(sys.argv[1])).get("ranks_gl", []):
    g = r.get("gpu_memory_mib") or {}
    mem = f", GPU memory {g.get('free')} MiB free of {g.get('total')}" if g else ""
    print(f"rank {r.get('rank')} on {r.get('host')}: {r.get('backend')}, device {r.get('device')}, "
          f"{r.get('renderer')}{mem}")
PY
}
