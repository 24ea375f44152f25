#!/usr/bin/env bash
# test/sweep_kill.sh -- a sweep run by its Makefile, killed part-way with
# SIGKILL (make and every afv it started) several times and run again,
# must end with every run byte-identical to an uninterrupted sweep
# (issue 20).  Too slow for make test (about 10 s on 2 cores); .ci/run
# calls it.
#
#   test/sweep_kill.sh [AFV]     (AFV: the afv program, default ./afv)
#
# Exit status 0 if every file matches and at least one job was really
# resumed from a checkpoint (else the kills proved nothing).
set -euo pipefail
afv=$(realpath "${1:-./afv}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

grid=(--P0 4,8 --v0 0.5,2.6 --seeds 2 --N 100 --steps 8000
      --frame_every 100 --sample_every 50 --checkpoint_every 500
      --svg_every 0 --steady-from 20 --lag 10 --afv "$afv")
"$afv" sweep --out "$work/ref" "${grid[@]}" > /dev/null
"$afv" sweep --out "$work/cut" "${grid[@]}" > /dev/null

start=$(date +%s.%N)
make -s -C "$work/ref" -j2 > /dev/null
whole=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
echo "uninterrupted sweep: ${whole} s"

# Kill the runner at a few moments spread over the sweep's length: a new
# session per attempt, so that one kill reaches make and its jobs.
for frac in 0.15 0.3 0.45 0.6 0.75; do
  setsid make -s -C "$work/cut" -j2 > /dev/null 2>&1 &
  pid=$!
  sleep "$(awk -v w="$whole" -v f="$frac" 'BEGIN { print w * f }')"
  kill -KILL -- "-$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
done
make -s -C "$work/cut" -j2 > /dev/null

resumed=$(cat "$work"/cut/runs/*/log.txt | grep -c "resuming at step" || true)
echo "jobs resumed from a checkpoint after a kill: $resumed"
bad=0
for run in "$work"/ref/runs/*; do
  id=$(basename "$run")
  for f in params.txt trajectory.dat observables.csv checkpoint.txt \
           t1_reference.txt final.svg analysis/summary.txt analysis/msd.csv \
           analysis/series.csv analysis/csd.csv; do
    if ! cmp -s "$run/$f" "$work/cut/runs/$id/$f"; then
      echo "differs: runs/$id/$f"
      bad=1
    fi
  done
done
"$afv" collect "$work/cut" > /dev/null
"$afv" collect "$work/ref" > /dev/null
cmp "$work/ref/table.csv" "$work/cut/table.csv" || bad=1
if [ "$resumed" -lt 1 ]; then
  echo "no job was resumed: the kills missed every run"
  bad=1
fi
[ "$bad" = 0 ] && echo "killed and rerun sweep: every run byte-identical"
exit "$bad"
