#!/bin/sh
# doc/paper_states.sh -- the README tutorial's table: the paper's four
# summary states at full length (10^6 steps, 10^4 time units), one seed
# each: ngc_frac_mean, omega_mean, D_eff, msd_beta and t1_final of each.
#
#   sh doc/paper_states.sh [OUTDIR]         prints the table of the runs
#                                           in OUTDIR (runs nothing)
#   sh doc/paper_states.sh --run [OUTDIR]   runs the missing ones first
#                                           (from the repository root,
#                                           after make)
#
# OUTDIR defaults to runs/paper_states.  --run runs four simulations of
# 10^6 steps of 400 cells, one after the other: about 5 minutes of CPU
# each on one core (more on a loaded machine), 8 MB of disk each; runs
# already finished in OUTDIR are not repeated, an interrupted one resumes.
set -e
run=0
if [ "${1:-}" = --run ]; then run=1; shift; fi
out=${1:-runs/paper_states}
states="4_0.1 8.8_0.1 4.4_2.6 8.8_2.6"      # P0_v0

missing=""
for s in $states; do
  [ -e "$out/p${s%_*}_v${s#*_}/analysis/summary.txt" ] \
    || missing="$missing $s"
done
if [ -n "$missing" ] && [ "$run" = 0 ]; then
  echo "doc/paper_states.sh: no finished run in $out for P0_v0 =$missing;" \
       "sh doc/paper_states.sh --run $out runs them (about 5 minutes of" \
       "CPU each)" >&2
fi
if [ "$run" = 1 ]; then
  mkdir -p "$out"
  for s in $missing; do
    d="$out/p${s%_*}_v${s#*_}"
    echo "doc/paper_states.sh: running P0 ${s%_*}, v0 ${s#*_} into $d" >&2
    ./afv run --P0 "${s%_*}" --v0 "${s#*_}" --steps 1000000 \
              --frame_every 1000 --svg_every 250000 --quiet --continue \
              --out "$d"
    ./afv analyze "$d" --steady-from 1000 --lag 5000 >/dev/null
  done
fi
printf '%-5s %-5s %-14s %-11s %-8s %-9s %s\n' P0 v0 ngc_frac_mean \
  omega_mean D_eff msd_beta t1_final
for s in $states; do
  f="$out/p${s%_*}_v${s#*_}/analysis/summary.txt"
  if [ ! -e "$f" ]; then
    printf '%-5s %-5s (not run)\n' "${s%_*}" "${s#*_}"
    continue
  fi
  awk -v p="${s%_*}" -v v="${s#*_}" '
    {x[$1] = $2}
    END {b = ("msd_beta" in x) ? sprintf("%.2f", x["msd_beta"]) : "-"
         printf "%-5s %-5s %-14.3g %-11.3g %-8.2g %-9s %g\n", p, v,
         x["ngc_frac_mean"], x["omega_mean"], x["D_eff"], b, x["t1_final"]}' \
    "$f"
done
