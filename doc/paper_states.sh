#!/bin/sh
# doc/paper_states.sh -- reruns the README tutorial's table: the paper's
# four summary states at full length (10^4 time units), one seed each, and
# prints ngc_frac_mean, omega_mean, D_eff, msd_beta and t1_final of each.
#
#   sh doc/paper_states.sh [OUTDIR]      (from the repository root, after make)
#
# Each run takes a few minutes on one core; runs already finished in
# OUTDIR (default runs/paper_states) are not repeated.
set -e
out=${1:-runs/paper_states}
mkdir -p "$out"
for pv in "4 0.1" "8.8 0.1" "4.4 2.6" "8.8 2.6"; do
  set -- $pv
  d="$out/p$1_v$2"
  if [ ! -e "$d/final.svg" ]; then
    rm -rf "$d"
    ./afv run --P0 "$1" --v0 "$2" --steps 1000000 --frame_every 1000 \
              --svg_every 250000 --quiet --out "$d"
  fi
  [ -e "$d/analysis/summary.txt" ] \
    || ./afv analyze "$d" --steady-from 1000 --lag 5000 >/dev/null
done
printf '%-5s %-5s %-14s %-11s %-8s %-9s %s\n' P0 v0 ngc_frac_mean \
  omega_mean D_eff msd_beta t1_final
for pv in "4 0.1" "8.8 0.1" "4.4 2.6" "8.8 2.6"; do
  set -- $pv
  awk -v p="$1" -v v="$2" '
    {x[$1] = $2}
    END {b = ("msd_beta" in x) ? sprintf("%.2f", x["msd_beta"]) : "-"
         printf "%-5s %-5s %-14.3g %-11.3g %-8.2g %-9s %g\n", p, v,
         x["ngc_frac_mean"], x["omega_mean"], x["D_eff"], b, x["t1_final"]}' \
    "$out/p$1_v$2/analysis/summary.txt"
done
