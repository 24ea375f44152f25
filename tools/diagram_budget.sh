#!/bin/sh
# diagram_budget.sh -- the paper's full (P0, v0) diagram's CPU budget,
# projected from the finished runs of any afv sweep (doc/performance.md,
# "The full diagram's budget"; make diagram-budget).
#
#   sh tools/diagram_budget.sh SWEEP [AFV]
#
# SWEEP is an afv sweep folder (runs/ID/ with params.txt, log.txt and
# analysis/summary.txt when finished); it is only read: every measurement
# works on copies in a temporary folder.  A finished run's own times are
# wall-clock times (log.txt) and so depend on the machine's load; this
# script measures CPU time instead (GNU time, user + system), one process
# at a time, with AFV (default ./afv), for each finished run:
#   relax    its start and relaxation: afv run --config params.txt --steps 0
#            with every optional output off;
#   steps    STEPS_SAMPLE (default 20000) active steps from the run's own
#            last checkpoint (its steady state; centres and angles as a
#            cells file, init file, no relaxation), outputs off: CPU per
#            step, times the full job's FULL_STEPS (default 10^6);
#   output   (once, on the first finished run) OUTPUT_STEPS (default
#            10^4) steps with the run's sample_every, frame_every and
#            checkpoint_every divided by AMPLIFY (default 100: 100 times
#            the outputs, so that their cost stands above the timing's
#            noise) against all off, REPEATS (3) times in turn, the least
#            of each: the difference / AMPLIFY per step (a direct on/off
#            comparison at the run's own intervals differs by less than
#            the noise of a loaded machine);
#   analysis afv analyze on a copy of the run, with the sweep's
#            analysis.txt (the copy's trajectory is in the run's format).
# The full diagram is tools/paper_sweeps.sh's `full` grid: P0 4:8.8:0.2 x
# v0 0:2.7:0.1 x 2 seeds = 1400 jobs; each of its state points takes the
# per-job cost of the nearest finished run (P0 scaled by 4.8, v0 by 2.7,
# the grid's spans), so an uneven sample is not averaged as if even.
# Printed: one line per sampled run, then the projection, its breakdown,
# the hours on CORES (default 2) cores, the cost per state point's spread
# (largest / smallest over the grid) and the per-cell-step figure.
set -e
SWEEP=${1:?usage: tools/diagram_budget.sh SWEEP [AFV]}
AFV=${2:-./afv}
STEPS_SAMPLE=${STEPS_SAMPLE:-20000}
OUTPUT_STEPS=${OUTPUT_STEPS:-10000}
AMPLIFY=${AMPLIFY:-100}
REPEATS=${REPEATS:-3}
FULL_STEPS=${FULL_STEPS:-1000000}
CORES=${CORES:-2}
TIME=/usr/bin/time
[ -x "$TIME" ] || { echo "diagram_budget.sh: needs GNU time at $TIME" >&2; exit 2; }
[ -d "$SWEEP/runs" ] || { echo "diagram_budget.sh: $SWEEP: not an afv sweep (no runs/)" >&2; exit 2; }
TMP=$(mktemp -d /tmp/afv_budget.XXXXXX)
trap 'rm -rf "$TMP"' EXIT; trap 'exit 130' INT; trap 'exit 143' TERM

# key VALUE of params.txt ($1) for key $2
key() { awk -v k="$2" '$1 == k { print $2; exit }' "$1"; }

# cpu SECONDS of one command (user + system), or exit on its failure
cpu() {
  if ! $TIME -f "%U %S" -o "$TMP/time" "$@" > /dev/null 2> "$TMP/err"; then
    echo "diagram_budget.sh: failed: $*" >&2
    cat "$TMP/err" >&2
    exit 1
  fi
  awk '{ print $1 + $2 }' "$TMP/time"
}

# an output interval $1 / AMPLIFY, at least 1 (0 stays 0: off)
div() { awk -v e="$1" -v a="$AMPLIFY" 'BEGIN { q = int(e / a); print e == 0 ? 0 : q < 1 ? 1 : q }'; }

# least OLD NEW MODE WANTED: NEW if MODE is WANTED and NEW < OLD (or OLD
# empty), else OLD
least() {
  if [ "$3" != "$4" ]; then echo "$1"
  else awk -v o="$1" -v t="$2" 'BEGIN { print (o == "" || t + 0 < o + 0) ? t : o }'; fi
}

# the checkpoint's centres and angles ($1) as a cells file ($2)
cells_from_checkpoint() {
  { echo "# x y theta"; awk 'NF == 3 && $1 !~ /^#/ && $1 != "cells" \
      && $1 != "step" && $1 != "time" && $1 != "seed" && $1 != "bytes"' "$1"; } > "$2"
}

OFF="--sample_every 0 --frame_every 0 --svg_every 0 --checkpoint_every 0 --quiet"
analysis_args=$(cat "$SWEEP/analysis.txt" 2>/dev/null || true)
finished=0; total=0; out_per_step=
: > "$TMP/sample"
printf '%-6s %-5s %-5s %-6s %-8s %-10s %-9s %-10s %-10s %-9s %s\n' run P0 v0 relax relax_s \
       steps_us/cs steps_s analysis_s job_cpu_s wall_s "(log.txt)"
for run in "$SWEEP"/runs/*/; do
  run=${run%/}; id=${run##*/}
  [ -d "$run" ] || continue           # no runs yet: the pattern itself
  total=$((total + 1))
  if [ ! -f "$run/analysis/summary.txt" ] || [ ! -f "$run/checkpoint.txt" ]; then
    continue                         # not finished
  fi
  grep -q "steps 0\.\." "$run/log.txt" 2>/dev/null || continue
  finished=$((finished + 1))
  p="$run/params.txt"
  n=$(key "$p" N); p0=$(key "$p" P0); v0=$(key "$p" v0)
  relax_steps=$(sed -n 's/^relaxation at v0.*: \([0-9]*\) steps.*/\1/p' "$run/log.txt" | tail -n 1)
  wall=$(sed -n 's/.* steps 0\.\.[0-9]* (t = [^)]*) in \([0-9.e+]*\) s .*/\1/p' "$run/log.txt" | tail -n 1)
  rm -rf "$TMP/r"
  # shellcheck disable=SC2086  # $OFF: several options
  relax=$(cpu "$AFV" run --config "$p" --steps 0 $OFF --out "$TMP/r")
  rm -rf "$TMP/r"
  cells_from_checkpoint "$run/checkpoint.txt" "$TMP/cells.txt"
  # shellcheck disable=SC2086
  steps=$(cpu "$AFV" run --config "$p" --init file --cells "$TMP/cells.txt" \
          --relax_max_steps 0 --steps "$STEPS_SAMPLE" $OFF --out "$TMP/r")
  if [ -z "$out_per_step" ]; then
    # output: OUTPUT_STEPS steps with the run's sample, frame and
    # checkpoint intervals divided by AMPLIFY, against all off (alternated
    # REPEATS times, the least of each kept): the difference / AMPLIFY
    # is the outputs' cost per step of the run
    se=$(key "$p" sample_every); fe=$(key "$p" frame_every); ce=$(key "$p" checkpoint_every)
    on_args="--sample_every $(div "$se") --frame_every $(div "$fe") --checkpoint_every $(div "$ce") --svg_every 0 --quiet"
    out_on=; out_off=
    rep=0
    while [ "$rep" -lt "$REPEATS" ]; do
      rep=$((rep + 1))
      for mode in on off; do
        rm -rf "$TMP/o"
        if [ $mode = on ]; then args=$on_args; else args=$OFF; fi
        # shellcheck disable=SC2086
        t=$(cpu "$AFV" run --config "$p" --init file --cells "$TMP/cells.txt" \
            --relax_max_steps 0 --steps "$OUTPUT_STEPS" $args --out "$TMP/o")
        [ $mode = on ] && out_bytes=$(cat "$TMP/o"/* | wc -c)
        out_on=$(least "$out_on" "$t" $mode on); out_off=$(least "$out_off" "$t" $mode off)
      done
    done
    out_per_step=$(echo "$out_on $out_off $OUTPUT_STEPS $AMPLIFY" | awk '{ print ($1 - $2) / $3 / $4 }')
    echo "output: $OUTPUT_STEPS steps at P0 $p0 v0 $v0 N $n with sample_every," \
         "frame_every, checkpoint_every / $AMPLIFY ($on_args): $out_on s CPU" \
         "($out_bytes bytes written), $out_off s with outputs off (least of $REPEATS each):" \
         "$(echo "$out_per_step $n" | awk '{ printf "%.4f us per cell-step of the run", $1 / $2 * 1e6 }')" >&2
  fi
  rm -rf "$TMP/a"
  mkdir "$TMP/a"
  for f in "$run"/*; do [ -f "$f" ] && cp "$f" "$TMP/a/"; done
  # shellcheck disable=SC2086
  analysis=$(cpu "$AFV" analyze "$TMP/a" $analysis_args)
  rm -rf "$TMP/a" "$TMP/r" "$TMP/o"
  echo "$id $p0 $v0 $n ${relax_steps:-0} $relax $steps ${wall:-0} $analysis" \
    | awk -v S="$STEPS_SAMPLE" -v F="$FULL_STEPS" -v O="$out_per_step" '{
        us = $7 / S / $4 * 1e6; job = $6 + $7 / S * F + O * F + $9
        printf "%-6s %-5g %-5g %-6d %-8.2f %-10.3f %-9.1f %-10.2f %-10.1f %s\n",
               $1, $2, $3, $5, $6, us, $7 / S * F, $9, job, $8
        print $2, $3, $4, $6, $7 / S * F, O * F, $9 > "/dev/stderr" }' \
    2>> "$TMP/sample"
done
[ "$finished" -gt 0 ] || { echo "diagram_budget.sh: $SWEEP: no finished run yet ($total runs)" >&2; exit 1; }

# The projection: the full grid, each state point from its nearest sample.
awk -v runs="$finished" -v total="$total" -v cores="$CORES" -v F="$FULL_STEPS" '
  { P[NR] = $1; V[NR] = $2; N[NR] = $3; R[NR] = $4; S[NR] = $5; O[NR] = $6; A[NR] = $7 }
  END {
    m = 0
    for (i = 0; i <= 24; i++) for (j = 0; j <= 27; j++) {
      p = 4 + 0.2 * i; v = 0.1 * j; best = 1e300
      for (k = 1; k <= NR; k++) {
        d = ((P[k] - p) / 4.8) ^ 2 + ((V[k] - v) / 2.7) ^ 2
        if (d < best - 1e-12) { best = d; b = k }
      }
      job = R[b] + S[b] + O[b] + A[b]
      if (m == 0 || job > hi) { hi = job; hip = p; hiv = v }
      if (m == 0 || job < lo) { lo = job; lop = p; lov = v }
      r += 2 * R[b]; s += 2 * S[b]; o += 2 * O[b]; a += 2 * A[b]; m += 2
      cells += 2 * N[b]
    }
    all = r + s + o + a
    printf "\nprojection of the full diagram (%d jobs of %d steps, 25 P0 x 28 v0 x 2 seeds)\n", m, F
    printf "from %d finished runs of %d in the sweep\n", runs, total
    printf "  relaxation %8.2f CPU h  %5.1f%%\n", r / 3600, 100 * r / all
    printf "  steps      %8.2f CPU h  %5.1f%%\n", s / 3600, 100 * s / all
    printf "  output     %8.2f CPU h  %5.1f%%\n", o / 3600, 100 * o / all
    printf "  analysis   %8.2f CPU h  %5.1f%%\n", a / 3600, 100 * a / all
    printf "  total      %8.2f CPU h = %.1f h on %d cores (goal: 16 h on 2)\n", all / 3600, all / 3600 / cores, cores
    printf "  per job    %.1f s mean, %.1f s at P0 %g v0 %g to %.1f s at P0 %g v0 %g: spread %.2fx (goal: 1.5x)\n",
           all / m, lo, lop, lov, hi, hip, hiv, hi / lo
    printf "  everything included: %.3f us per cell-step (goal: about 0.2)\n", all / (cells * F) * 1e6
  }' "$TMP/sample"
