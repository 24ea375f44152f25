#!/bin/sh
# tools/lambda.sh OUT [AFV] -- the Lambda study (doc/reproduction/lambda.md):
# the phase diagram (clustering, confluency, dynamics) at Lambda = 0 and
# 0.5, beside the paper's 0.2, and the time-step check at Lambda = 0.
#   OUT/grid_L0, OUT/grid_L0.5  the quick grid of tools/paper_sweeps.sh
#       (N = 400, P0 4..8.8 x v0 0..2.6, 2 seeds, 3e4 steps, steady window
#       t >= 100, D_s at lag 50, Euler dt = 0.01, exact force) at that
#       Lambda; seed 1 of both grids runs first, then seed 2, so that a
#       study stopped early has each whole plane once; tabled by
#       afv collect (OUT/grid_L*/table.csv, fits.txt, missing.txt)
#   OUT/phase_L0.svg, phase_L0.5.svg  the three boundaries on one figure
#       (tools/lambda_plot; the points in OUT/boundaries_L*.csv), and
#       phase_L0.2.svg from the committed quick table
#       doc/reproduction/grid_table.csv
#   OUT/dt_L0  tools/convergence.sh at Lambda = 0, Euler with the exact
#       force only: dt 0.02, 0.01, 0.005, 0.0025, P0 4 and 8, v0 1, 1.85,
#       2.6, 2 seeds, t = 1500 (verdicts.csv: its criterion)
# Resumable: a sweep that exists is kept and its runs continue.
# JOBS=K sets make's -j (default 2); COLLECT_ONLY=1 tables and draws what
# has finished without running anything.
set -e
OUT=${1:?usage: tools/lambda.sh OUT [AFV]}
HERE=$(cd "$(dirname "$0")/.." && pwd)
AFV=${2:-$HERE/afv}
PLOT=$HERE/tools/lambda_plot
JOBS=${JOBS:-2}
LAMBDAS="0 0.5"

mkdir -p "$OUT"
# A copy of the program, so that a rebuild during the study changes nothing.
[ -x "$OUT/afv" ] || cp "$AFV" "$OUT/afv"

# The quick grid of tools/paper_sweeps.sh (SCALE=quick, its GRID and
# GRID_ANALYZE, and the integration it fixes); only Lambda differs.
QUICK_GRID="--P0 4,4.4,4.8,5.6,6.4,7.2,8,8.8
  --v0 0,0.1,0.4,0.7,1,1.3,1.6,1.85,2.1,2.6 --seeds 2 --N 400
  --steps 30000 --frame_every 100 --steady-from 100 --lag 50
  --integrator euler --dt 0.01 --cap 0 --sample_every 100 --svg_every 0
  --quiet 1"

# Each grid is written once, kept (its runs resume) if it exists.
for L in $LAMBDAS; do
  [ -d "$OUT/grid_L$L" ] && continue
  # shellcheck disable=SC2086
  "$OUT/afv" sweep --out "$OUT/grid_L$L" --afv "$OUT/afv" $QUICK_GRID \
    --Lambda "$L"
done

# The seed-1 jobs of a grid: the runs/ID/analysis/summary.txt targets of
# its Makefile for the rows of points.csv with seed 1.
seed1() {
  awk -F, 'NR > 1 && $NF == 1 { printf "runs/%s/analysis/summary.txt ", $1 }' \
    "$OUT/grid_L$1/points.csv"
}

if [ "${COLLECT_ONLY:-0}" != 1 ]; then
  # shellcheck disable=SC2046
  for L in $LAMBDAS; do make -s -C "$OUT/grid_L$L" -j "$JOBS" $(seed1 $L); done
  for L in $LAMBDAS; do make -s -C "$OUT/grid_L$L" -j "$JOBS"; done
fi

# Tables (afv collect exits 1 while jobs are missing: it lists them in
# missing.txt) and figures.
for L in $LAMBDAS; do
  st=0; "$OUT/afv" collect "$OUT/grid_L$L" > /dev/null || st=$?
  [ $st -le 1 ]
  "$PLOT" "$OUT/grid_L$L/table.csv" "$L" "$OUT/phase_L$L.svg" \
    > "$OUT/boundaries_L$L.csv"
done
"$PLOT" "$HERE/doc/reproduction/grid_table.csv" 0.2 "$OUT/phase_L0.2.svg" \
  > "$OUT/boundaries_L0.2.csv"

# The time-step check at Lambda = 0 (euler, exact force; COLLECT_ONLY is
# passed on).
LAMBDA=0 CAPS=0 sh "$HERE/tools/convergence.sh" "$OUT/dt_L0" \
  "$OUT/afv"
echo "tools/lambda.sh: $OUT/phase_L*.svg, $OUT/boundaries_L*.csv, $OUT/grid_L*/table.csv, $OUT/dt_L0/verdicts.csv"
