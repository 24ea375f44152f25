#!/bin/sh
# tools/paper_sweeps.sh SCALE OUT AFV -- writes the sweeps of `make paper`
# (afv sweep) into OUT/grid (the (P0, v0) plane, N = 400) and OUT/fss (the
# finite-size study: N_GC/N against v0 at P0 = 4 and 8 for growing N).
# A sweep that already exists is kept as it is (its runs resume), unless
# it was written for another SCALE: then this script stops (exit 2) and
# names it, so results of two scales never mix.
#
# SCALE   grid (P0 x v0, seeds, steps)              finite-size (N x P0 x v0)
# smoke   P0 4,8 x v0 0.1,1.85 (+ the panels' states), 1 seed ... numbers mean nothing
# quick   8 x 10, 2 seeds, 3e4 steps                N 6400,1600,400 x 4,8 x 4 v0, 1 seed
# paper   8 x 9, 2 seeds, 1e6 steps (the paper's length)  as quick
# full    the paper's: P0 4:8.8:0.2 x v0 0:2.7:0.1, 2 seeds, 1e6 steps
#
# Every run starts from afv run's default start (init cluster: the
# authors' protocol) and relaxes at v0 = 0 before the active steps.  Every
# run integrates as the paper did: Euler steps of dt = 0.01 with the exact
# force (integrator euler, cap 0), whatever afv run's defaults; how the
# results move with dt: doc/reproduction/convergence.md.
set -e
SCALE=${1:?usage: tools/paper_sweeps.sh SCALE OUT AFV}
OUT=${2:?usage: tools/paper_sweeps.sh SCALE OUT AFV}
AFV=${3:?usage: tools/paper_sweeps.sh SCALE OUT AFV}

case $SCALE in
smoke)
  # Tiny: every figure and claim is produced, the numbers mean nothing.
  GRID="--P0 4,4.4,5.6,8,8.8 --v0 0.1,0.4,1,1.85,2.6 --seeds 2 --N 100
        --steps 600 --frame_every 20 --relax_max_steps 400"
  GRID_ANALYZE="--steady-from 2 --lag 1"
  FSS="--N 200,100 --P0 4,8 --v0 1.4,1.85 --seeds 1 --steps 400
       --frame_every 20 --init lattice --relax_max_steps 400"
  FSS_ANALYZE="--steady-from 2 --lag 1"
  ;;
quick)
  # N = 400, 8 P0 x 10 v0 x 2 seeds = 160 jobs of 3e4 steps (t = 300),
  # steady window t >= 100, a frame every time unit, D_s at lag 50.
  GRID="--P0 4,4.4,4.8,5.6,6.4,7.2,8,8.8
        --v0 0,0.1,0.4,0.7,1,1.3,1.6,1.85,2.1,2.6 --seeds 2 --N 400
        --steps 30000 --frame_every 100"
  GRID_ANALYZE="--steady-from 100 --lag 50"
  # Finite size: N = 6400, 1600, 400 (the largest first: they take
  # longest, the runner starts them while the grid runs beside), P0 4, 8,
  # v0 1, 1.4, 1.85, 2.3, 1 seed, 3e4 steps as the grid, from the paper's
  # start at every N (the authors' square, relaxed by Euler steps at
  # v0 = 0): at N = 6400 the relaxation takes 38000 (P0 4) and 53000
  # (P0 8) steps, 210 s and 156 s of CPU (doc/performance.md, make
  # relax-cost), about 3 times a job's active steps.
  FSS="--N 6400,1600,400 --P0 4,8 --v0 1,1.4,1.85,2.3 --seeds 1
       --steps 30000 --frame_every 100"
  FSS_ANALYZE="--steady-from 100 --lag 50"
  ;;
paper)
  # The paper's run length on a grid that decides its claims: N = 400,
  # P0 4, 4.4 (the paper's dispersed-epithelial panel), 4.8, 5.6, 6.4, 7.2,
  # 8, 8.8 x v0 0.1, 0.4, 0.7, 1, 1.4, 1.6, 1.85, 2.1, 2.6 (the dispersal
  # line v_s(P0) lies between 1.6 and 2.1) x 2 seeds = 144 jobs of 1e6
  # steps (t = 10^4), steady window t >= 1000, D_s at lag 5000 as in the
  # paper.  The finite-size study is the quick one (t = 300, the paper's
  # start at every N).
  GRID="--P0 4,4.4,4.8,5.6,6.4,7.2,8,8.8
        --v0 0.1,0.4,0.7,1,1.4,1.6,1.85,2.1,2.6 --seeds 2 --N 400
        --steps 1000000 --frame_every 1000 --checkpoint_every 100000"
  GRID_ANALYZE="--steady-from 1000 --lag 5000"
  FSS="--N 6400,1600,400 --P0 4,8 --v0 1,1.4,1.85,2.3 --seeds 1
       --steps 30000 --frame_every 100"
  FSS_ANALYZE="--steady-from 100 --lag 50"
  ;;
full)
  # The paper's grid and length (25 x 28 x 2 = 1400 jobs of 1e6 steps):
  # steady window t >= 1000, D_s at lag 5000 as in the paper.
  GRID="--P0 4:8.8:0.2 --v0 0:2.7:0.1 --seeds 2 --N 400 --steps 1000000
        --frame_every 1000 --checkpoint_every 100000"
  GRID_ANALYZE="--steady-from 1000 --lag 5000"
  FSS="--N 6400,1600,400 --P0 4,8 --v0 1:2.5:0.15 --seeds 2
       --steps 1000000 --frame_every 1000 --checkpoint_every 100000"
  FSS_ANALYZE="--steady-from 1000 --lag 5000"
  ;;
*)
  echo "tools/paper_sweeps.sh: SCALE must be smoke, quick, paper or full, not '$SCALE'" >&2
  exit 2
  ;;
esac

# One sweep: written once; kept if it exists for the same scale.
sweep() {
  dir=$OUT/$1; shift
  if [ -d "$dir" ]; then
    if [ "$(cat "$dir/scale" 2>/dev/null)" != "$SCALE" ]; then
      echo "tools/paper_sweeps.sh: $dir holds a sweep of scale '$(cat "$dir/scale" 2>/dev/null)', not $SCALE: remove it or choose another OUT" >&2
      exit 2
    fi
    echo "$dir: kept (its runs resume)"
    return 0
  fi
  # shellcheck disable=SC2086
  "$AFV" sweep --out "$dir" "$@" --integrator euler --dt 0.01 --cap 0 \
    --sample_every 100 --svg_every 0 --quiet 1
  echo "$SCALE" > "$dir/scale"
}

mkdir -p "$OUT"
# shellcheck disable=SC2086
sweep grid $GRID $GRID_ANALYZE
# shellcheck disable=SC2086
sweep fss $FSS $FSS_ANALYZE
