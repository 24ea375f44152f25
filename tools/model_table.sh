#!/bin/sh
# tools/model_table.sh OUT DEST -- tables the finished runs of
# tools/model_sweeps.sh OUT into DEST (doc/reproduction/model/):
#
#   runs.csv        one row per finished run: sweep,id,P0,v0,seed,dt,cap,N and
#                   each run's observables (afv analyze's summary.txt;
#                   beta_long from tools/msd_plateau.sh)
#   dt_table.csv    the dt study: one row per state point and dt, each
#                   observable's mean and seed standard error (n_seeds
#                   runs; sem empty with one seed)
#   dt_verdicts.csv per state point and observable: dt 0.005 against
#                   0.0025 (converged: |difference| <= 2 sqrt(sem1^2 +
#                   sem2^2), the rule of convergence.md), dt 0.01 against
#                   0.0025 by the same rule, and the verdict by value and
#                   by the side of the observable's threshold: written by
#                   afv paper --dt-verdicts (the claims table's rule,
#                   cmd/dt_study.c), AFV the program (default ./afv)
#   cap_table.csv   the same as dt_table.csv for the cap sweeps (cap column)
#   deff_estimators.csv  the D_eff estimators side by side (single lag,
#                   slope, fit, the per-step reading) for every finished
#                   run of the glass states (dt_G*: v0 0.4, three dt, two
#                   seeds), by tools/deff_estimators.sh on a copy of each
#                   run analysed again by AFV with the sweep's analysis
#                   options (so that MSD_rel's standard error is given
#                   for runs analysed before afv 0.5.0; the other figures
#                   are the same bits); run names the sweep and id
#   progress.txt    how many runs of each sweep are in
# then tools/model_cap.sh OUT DEST: the capped model's record (cap/), its
# dt check and cap sequence (cap_dt_table.csv, cap_seq_table.csv), the
# finite-size tables (fss_table.csv, fss_crossing.csv) and their figures.
#
# Observables: ngc_frac, n_clusters, omega (steady means), D_eff (the
# summary's, lag 5000), msd_beta, beta_long, t1_rate (T1 events per cell
# per time unit in the steady window), csd_exponent (each run's cluster
# sizes fitted as afv paper fits Fig. 2(c): tools/csd_exponent).  Runs without analysis/summary.txt
# are left out.  Safe to run while the queue runs.
set -e
OUT=${1:?usage: tools/model_table.sh OUT DEST}
DEST=${2:?usage: tools/model_table.sh OUT DEST}
HERE=$(cd "$(dirname "$0")/.." && pwd)
AFV=${AFV:-$HERE/afv}
[ -x "$AFV" ] || { echo "tools/model_table.sh: no $AFV (make afv)" >&2; exit 2; }
mkdir -p "$DEST"
OBS="ngc_frac_mean n_clusters_mean omega_mean D_eff msd_beta beta_long t1_rate csd_exponent"

# runs.csv
{
  printf 'sweep,id,P0,v0,seed,dt,cap,N'
  for o in $OBS; do printf ',%s' "$o"; done; echo
  for dir in "$OUT"/*/; do
    s=$(basename "$dir")
    [ -f "$dir/points.csv" ] || continue
    sh "$HERE/tools/msd_plateau.sh" "$dir" 2>/dev/null | tail -n +2 \
      | cut -d, -f1,11 > "$DEST/.beta_long.$$" || true
    tail -n +2 "$dir/points.csv" | cut -d, -f1 | while read -r id; do
      run=$dir/runs/$id
      [ -f "$run/analysis/summary.txt" ] || continue
      csd=nan
      [ -x "$HERE/tools/csd_exponent" ] \
        && csd=$("$HERE/tools/csd_exponent" "$run/analysis/csd.csv" \
                   "$(awk '$1 == "N" { print $2 }' "$run/params.txt")")
      awk -v csd="$csd" -v sweep="$s" -v id="$id" -v obs="$OBS" '
        FILENAME ~ /params.txt$/ { p[$1] = $2 }
        FILENAME ~ /summary.txt$/ { v[$1] = $2 }
        FILENAME ~ /beta_long/ { split($0, f, ","); if (f[1] == id) v["beta_long"] = f[2] }
        END {
          v["csd_exponent"] = csd
          printf "%s,%s,%s,%s,%s,%s,%s,%s", sweep, id, p["P0"] + 0, p["v0"] + 0,
            p["seed"], p["dt"] + 0, p["cap"] + 0, p["N"]
          n = split(obs, o, " ")
          for (k = 1; k <= n; k++) printf ",%s", v[o[k]]
          printf "\n"
        }' "$run/params.txt" "$run/analysis/summary.txt" "$DEST/.beta_long.$$"
    done
    rm -f "$DEST/.beta_long.$$"
  done
} > "$DEST/runs.csv.tmp"
mv "$DEST/runs.csv.tmp" "$DEST/runs.csv"

# mean_table FILTER: rows of runs.csv whose sweep matches FILTER, grouped by
# (P0, v0, dt, cap, N): n_seeds, then each observable's mean and sem.
mean_table() {
  awk -F, -v filter="$1" '
    NR == 1 { nobs = NF - 8; for (k = 9; k <= NF; k++) name[k - 8] = $k; next }
    $1 ~ filter {
      key = $3 "," $4 "," $6 "," $7 "," $8
      if (!(key in n)) order[++nk] = key
      n[key]++
      for (k = 1; k <= nobs; k++) {    # a nan or empty value is left out
        if ($(k + 8) !~ /^-?[0-9.]+([eE][-+]?[0-9]+)?$/) continue
        x = $(k + 8) + 0
        c[key, k]++; s[key, k] += x; q[key, k] += x * x
      }
    }
    END {
      printf "P0,v0,dt,cap,N,n_seeds"
      for (k = 1; k <= nobs; k++) printf ",%s_mean,%s_sem", name[k], name[k]
      printf "\n"
      for (i = 1; i <= nk; i++) {
        key = order[i]
        printf "%s,%d", key, n[key]
        for (k = 1; k <= nobs; k++) {
          m = c[key, k]
          if (m == 0) { printf ",nan,"; continue }
          mu = s[key, k] / m
          if (m > 1) {
            var = (q[key, k] - m * mu * mu) / (m - 1); if (var < 0) var = 0
            printf ",%.6g,%.6g", mu, sqrt(var / m)
          } else printf ",%.6g,", mu
        }
        printf "\n"
      }
    }' "$DEST/runs.csv" | { read -r head; echo "$head"; sort -t, -k5,5n -k4,4n -k1,1n -k2,2n -k3,3gr; }
}
mean_table '^dt_' > "$DEST/dt_table.csv.tmp"
mv "$DEST/dt_table.csv.tmp" "$DEST/dt_table.csv"
mean_table '^cap_' > "$DEST/cap_table.csv.tmp"
mv "$DEST/cap_table.csv.tmp" "$DEST/cap_table.csv"

# deff_estimators.csv: the glass states' finished runs, each copied to
# COPY/SWEEP/runs/ID (what afv analyze reads) and analysed there by AFV
COPY=$(mktemp -d "${TMPDIR:-/tmp}/model_table.XXXXXX")
trap 'rm -rf "$COPY"' EXIT; trap 'exit 130' INT; trap 'exit 143' TERM
set --
for run in "$OUT"/dt_G*/runs/*/; do
  [ -f "$run/analysis/summary.txt" ] || continue
  run=${run%/} sweep=$(basename "$(dirname "$(dirname "$run")")")
  copy=$COPY/$sweep/runs/$(basename "$run")
  mkdir -p "$copy"
  cp "$run/params.txt" "$run/checkpoint.txt" "$run/final.svg" "$copy/"
  # the trajectory is only read: linked, not copied (8 MB or more a run)
  ln -s "$(cd "$run" && pwd)/trajectory.dat" "$copy/trajectory.dat"
  # shellcheck disable=SC2046
  "$AFV" analyze "$copy" $(cat "$OUT/$sweep/analysis.txt") > /dev/null
  set -- "$@" "$copy"
done
if [ $# -gt 0 ]; then
  sh "$HERE/tools/deff_estimators.sh" "$@" \
    | awk -F, -v OFS=, -v copy="$COPY/" 'NR > 1 && index($1, copy) == 1 { $1 = substr($1, length(copy) + 1) } { print }' \
    > "$DEST/deff_estimators.csv.tmp"
else   # no glass run in yet: the header alone, no earlier table kept
  sh "$HERE/tools/deff_estimators.sh" --header > "$DEST/deff_estimators.csv.tmp"
fi
mv "$DEST/deff_estimators.csv.tmp" "$DEST/deff_estimators.csv"

# dt_verdicts.csv: the rule of the claims table, applied by the same code
# (cmd/dt_study.c) to every state point and observable
"$AFV" paper --dt-verdicts "$DEST/dt_table.csv" "$DEST/dt_verdicts.csv" \
  > /dev/null
# figures/: each observable against dt (tools/model_plot), the glass
# states' observables at v0 0.4, the dispersal states' at the others
PLOT=$HERE/tools/model_plot
if [ -x "$PLOT" ] && [ "$(wc -l < "$DEST/dt_table.csv")" -gt 1 ]; then
  mkdir -p "$DEST/figures"
  for o in msd_beta beta_long D_eff t1_rate omega_mean; do
    "$PLOT" "$DEST/dt_table.csv" dt "$o" v0=0.4 "$DEST/figures/dt_glass_$o.svg" \
      "v0 0.4: $o against dt (seed mean, markers +- sem)" || true
  done
  for o in ngc_frac_mean n_clusters_mean omega_mean csd_exponent; do
    "$PLOT" "$DEST/dt_table.csv" dt "$o" 'v0!=0.4' "$DEST/figures/dt_dispersal_$o.svg" \
      "dispersal states: $o against dt (seed mean, markers +- sem)" || true
  done
fi
AFV="$AFV" sh "$HERE/tools/model_cap.sh" "$OUT" "$DEST"
# progress.txt: how many runs of each sweep are in, and who ran them
{
  for dir in "$OUT"/*/; do
    [ -f "$dir/points.csv" ] || continue
    s=$(basename "$dir")
    total=$(($(wc -l < "$dir/points.csv") - 1))
    done_=$(awk -F, -v s="$s" '$1 == s' "$DEST/runs.csv" | wc -l)
    echo "$s: $done_ of $total runs finished and analysed"
  done
  echo "runs by: $("$OUT/afv" --version 2>/dev/null | head -1 | cut -d" " -f1,2)"
  echo "tabled: $(date -u +%Y-%m-%d)"
} > "$DEST/progress.txt.tmp"
mv "$DEST/progress.txt.tmp" "$DEST/progress.txt"
echo "tools/model_table.sh: $(($(wc -l < "$DEST/runs.csv") - 1)) runs tabled into $DEST"
