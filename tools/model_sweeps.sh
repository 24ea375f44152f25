#!/bin/sh
# tools/model_sweeps.sh OUT [AFV] -- the paper-length runs that decide which
# of the paper's conclusions are properties of the AFV model and which are
# properties of dt = 0.01 (doc/reproduction/model/README.md):
#
#   dt_D{1,2,3}   the dispersal claims' states, P0 4 and 8 x v0 1.4, 1.85,
#                 2.6, 2 seeds, at dt 0.01, 0.005, 0.0025 (t = 10^4 each)
#   dt_G{1,2,3}   the glass claims' states, v0 0.4 x P0 4, 5.6, 6.4, 7.2,
#                 8.8, 2 seeds, at the same three dt
#   cap_grid      the record's grid (8 P0 x 9 v0 x 2 seeds, 10^6 steps of
#                 dt 0.01) with PyAFV's contact cap 0.45
#   cap_dt        its dt check: dt 0.005 at 8 of its points
#   cap_seq       caps 0.2, 0.1, 0.05 at P0 4 and 8, v0 1.85, dt 0.0025
#   cap_seq_dt    its dt check at the stiffest cap: 0.05 at dt 0.00125, seed 1
#   cap_dt--seed2     cap_dt's seed 2
#   cap_seq_dt--caps  cap_seq_dt at caps 0.2 and 0.1
#   fss_1600      N 1600, P0 4, 8 x v0 1.4, 1.85, 2.3, 2 seeds, 10^6 steps
#   fss_6400      N 6400, P0 4, 8 x v0 1.85, 1 seed, 10^6 steps
#
# A sweep NAME--PART adds runs (another seed, other caps) to NAME's design:
# tools/model_cap.sh tables them as NAME's.
#
# Every run: the authors' start (init cluster), relaxed at v0 = 0, then
# Euler steps; steady window t >= 1000, D_s at lag 5000 (as the record).
# The sweeps are written once (kept if they exist: their runs resume);
# the jobs then run one at a time (JOBS=K runs K queues) in the order of
# their use (the comment above the queue below; every dt of a point
# before the next point).  Stop it at any moment;
# run it again and it goes on where it stopped.  QUEUE_ONLY=1 writes the
# sweeps and OUT/queue.txt and runs nothing.  About 15 CPU hours in all.
set -e
OUT=${1:?usage: tools/model_sweeps.sh OUT [AFV]}
HERE=$(cd "$(dirname "$0")/.." && pwd)
AFV=${2:-$HERE/afv}
JOBS=${JOBS:-1}
mkdir -p "$OUT"
# A copy of the program, so that a rebuild during the study changes nothing.
[ -x "$OUT/afv" ] || cp "$AFV" "$OUT/afv"

ANALYZE="--steady-from 1000 --lag 5000"
COMMON="--integrator euler --svg_every 0 --quiet 1"

sweep() {
  name=$1; shift
  if [ -d "$OUT/$name" ]; then return 0; fi
  # shellcheck disable=SC2086
  "$OUT/afv" sweep --out "$OUT/$name" --afv "$OUT/afv" $COMMON $ANALYZE "$@" \
    > /dev/null
}

# steps for t = 10^4, frames every 10 time units, checkpoints every 1000
at_dt() {
  dt=$1
  steps=$(awk -v dt="$dt" 'BEGIN { printf "%d", 1e4 / dt + 0.5 }')
  frame=$(awk -v dt="$dt" 'BEGIN { printf "%d", 10 / dt + 0.5 }')
  echo "--dt $dt --steps $steps --frame_every $frame --checkpoint_every $((frame * 100))"
}

i=0
for dt in 0.01 0.005 0.0025; do
  i=$((i + 1))
  # shellcheck disable=SC2046
  sweep dt_D$i --N 400 --P0 4,8 --v0 1.4,1.85,2.6 --seeds 2 --cap 0 $(at_dt $dt)
  # shellcheck disable=SC2046
  sweep dt_G$i --N 400 --P0 4,5.6,6.4,7.2,8.8 --v0 0.4 --seeds 2 --cap 0 $(at_dt $dt)
done
# shellcheck disable=SC2046
sweep cap_grid --N 400 --P0 4,4.4,4.8,5.6,6.4,7.2,8,8.8 \
  --v0 0.1,0.4,0.7,1,1.4,1.6,1.85,2.1,2.6 --seeds 2 --cap 0.45 $(at_dt 0.01)
# shellcheck disable=SC2046
sweep cap_dt --N 400 --P0 4,8.8 --v0 0.4,1.4,1.85,2.6 --seeds 1 --cap 0.45 \
  $(at_dt 0.005)
# shellcheck disable=SC2046
sweep cap_seq --N 400 --P0 4,8 --v0 1.85 --seeds 2 --cap 0.2,0.1,0.05 \
  $(at_dt 0.0025)
# shellcheck disable=SC2046
sweep cap_seq_dt --N 400 --P0 4,8 --v0 1.85 --seeds 1 --cap 0.05 \
  $(at_dt 0.00125)
# shellcheck disable=SC2046
sweep cap_dt--seed2 --N 400 --P0 4,8.8 --v0 0.4,1.4,1.85,2.6 --seed 2 \
  --cap 0.45 $(at_dt 0.005)
# shellcheck disable=SC2046
sweep cap_seq_dt--caps --N 400 --P0 4,8 --v0 1.85 --seeds 1 --cap 0.2,0.1 \
  $(at_dt 0.00125)
# shellcheck disable=SC2046
sweep fss_1600 --N 1600 --P0 4,8 --v0 1.4,1.85,2.3 --seeds 2 --cap 0 $(at_dt 0.01)
# shellcheck disable=SC2046
sweep fss_6400 --N 6400 --P0 4,8 --v0 1.85 --seeds 1 --cap 0 $(at_dt 0.01)

# The queue: one line "SWEEP ID" per job, in the order of use: the dt
# table's glass states, both seeds (point by point: job k of dt_G1, dt_G2,
# dt_G3 is the same state at the three dt); the dispersal states at v0
# 1.85 (v0*, the CSD exponents), both seeds; the cap grid's seed 1, a
# coarse diagram first; the other dispersal states, both seeds (every
# claim's dt verdict); the cap grid's dt check; the cap sequence's seed 1
# and its dt check; N 1600 (both seeds); the cap sequence's seed 2; then
# N 6400 and the cap grid's seed 2; then cap_dt's seed 2 and the cap
# sequence's dt check at caps 0.2 and 0.1.
dt_set() { # G|D SEED: each state of that seed at the three dt, point by point
  for id in $(jobs_of "dt_${1}1" "$2"); do
    for i in 1 2 3; do echo "dt_$1$i $id"; done
  done
}
# SWEEP SEED: the grid's jobs of that seed, every other P0 and the v0 0.1,
# 0.7, 1.4, 1.85, 2.6 first, then the rest: a queue stopped half-way
# leaves a coarse diagram whole rather than half a fine one.
coarse_first() {
  awk -F, -v seed="$2" '
    NR == 1 { for (c = 1; c <= NF; c++) col[$c] = c; next }
    $col["seed"] == seed {
      p = $col["P0"]; v = $col["v0"]
      if (!(p in rank)) rank[p] = np++
      coarse = rank[p] % 2 == 0 && (v == 0.1 || v == 0.7 || v == 1.4 || v == 1.85 || v == 2.6)
      if (coarse) print "'"$1"' " $1; else rest[n++] = "'"$1"' " $1
    }
    END { for (k = 0; k < n; k++) print rest[k] }' "$OUT/$1/points.csv"
}
dt_at_v0() { # G|D V0: the states at that v0, both seeds, at the three dt
  for id in $(awk -F, -v v0="$2" 'NR == 1 { for (c = 1; c <= NF; c++) col[$c] = c; next }
                $col["v0"] == v0 { print $1 }' "$OUT/dt_${1}1/points.csv"); do
    for i in 1 2 3; do echo "dt_$1$i $id"; done
  done
}
jobs_of() { # SWEEP SEED: the ids of SWEEP's jobs with that seed
  awk -F, -v seed="$2" 'NR == 1 { for (c = 1; c <= NF; c++) if ($c == "seed") s = c; next }
                        $s == seed { print $1 }' "$OUT/$1/points.csv"
}
{
  for seed in 1 2; do dt_set G $seed; done
  dt_at_v0 D 1.85
  coarse_first cap_grid 1
  dt_set D 1
  dt_set D 2
  for id in $(jobs_of cap_dt 1); do echo "cap_dt $id"; done
  for id in $(jobs_of cap_seq 1); do echo "cap_seq $id"; done
  for id in $(jobs_of cap_seq_dt 1); do echo "cap_seq_dt $id"; done
  for id in $(jobs_of fss_1600 1); do echo "fss_1600 $id"; done
  for id in $(jobs_of fss_1600 2); do echo "fss_1600 $id"; done
  for id in $(jobs_of cap_seq 2); do echo "cap_seq $id"; done
  for id in $(jobs_of fss_6400 1); do echo "fss_6400 $id"; done
  for id in $(jobs_of cap_grid 2); do echo "cap_grid $id"; done
  for id in $(jobs_of cap_dt--seed2 2); do echo "cap_dt--seed2 $id"; done
  for id in $(jobs_of cap_seq_dt--caps 1); do echo "cap_seq_dt--caps $id"; done
} | awk '!seen[$0]++' > "$OUT/queue.txt.tmp"   # each job once, at its first place
mv "$OUT/queue.txt.tmp" "$OUT/queue.txt"
[ "${QUEUE_ONLY:-0}" = 1 ] && exit 0

# Run the queue: make builds one job's summary (a finished job is skipped).
xargs -P "$JOBS" -n 2 sh -c \
  'nice -n 0 make -s -C "$0/$1" "runs/$2/analysis/summary.txt" || echo "job $1 $2 failed (see $0/$1/logs/$2.log)" >&2' \
  "$OUT" < "$OUT/queue.txt"
echo "tools/model_sweeps.sh: queue done"
