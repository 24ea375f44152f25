#!/bin/sh
# tools/msd_plateau.sh SWEEP -- the cage-relative MSD's plateau of every
# finished run of an afv sweep, against P0 and v0 (issue: the paper's
# D_eff = 10^-8 floor for glassy states).
#
# For each run with analysis/summary.txt it prints one CSV row:
#   id,P0,v0,seed,lag,msd_rel,plateau_over_v0sq,D_eff,D_eff_from_plateau,msd_beta,beta_long
# lag: D_s's lag (summary's D_s_lag); msd_rel: the relative MSD at that
# lag (analysis/msd.csv); plateau_over_v0sq = msd_rel / v0^2.  msd_beta
# is afv collect's (the slope at lags 1% - 10% of the steady window);
# beta_long is the slope of log msd_rel over the decade that ends at D_s's
# lag (from the msd.csv lag nearest lag/10 in log to lag): the exponent
# at the lags of the paper's D_s.  A caged
# state's relative MSD stops growing at a plateau set by how far a cell
# rattles in its cage, which grows as v0^2, and D_0 = v0^2 / (2 Dr) grows
# the same way, so D_eff = msd_rel / (4 lag D_0) of a caged state does not
# fall with v0: D_eff_from_plateau = plateau_over_v0sq * 2 Dr / (4 lag)
# is that value (Dr from the run's params.txt).  Rows are in points.csv's
# order; runs without a summary are left out (their count goes to stderr).
set -e
SWEEP=${1:?usage: tools/msd_plateau.sh SWEEP_DIR}
[ -f "$SWEEP/points.csv" ] || { echo "tools/msd_plateau.sh: $SWEEP/points.csv: no such file (not an afv sweep)" >&2; exit 2; }
echo "id,P0,v0,seed,lag,msd_rel,plateau_over_v0sq,D_eff,D_eff_from_plateau,msd_beta,beta_long"
missing=0
# points.csv: id first (header first); P0, v0 and seed are read from the
# run's params.txt, whichever of them the sweep varied
tail -n +2 "$SWEEP/points.csv" | cut -d, -f1 | while read -r id; do
  run=$SWEEP/runs/$id
  if [ ! -f "$run/analysis/summary.txt" ]; then
    missing=$((missing + 1)); echo "$missing" > "${TMPDIR:-/tmp}/msd_plateau.$$"
    continue
  fi
  awk -v id="$id" '
    FILENAME ~ /params.txt$/ && $1 == "Dr" { Dr = $2 }
    FILENAME ~ /params.txt$/ && $1 == "P0" { P0 = $2 + 0 }
    FILENAME ~ /params.txt$/ && $1 == "v0" { v0 = $2 + 0 }
    FILENAME ~ /params.txt$/ && $1 == "seed" { seed = $2 }
    FILENAME ~ /summary.txt$/ { s[$1] = $2 }
    FILENAME ~ /msd.csv$/ && FNR > 1 {
      split($0, f, ","); if (f[1] + 0 == s["D_s_lag"] + 0) rel = f[3]
      # the row nearest lag/10 in log: the decade before the D_s lag
      d = log(f[1] / (s["D_s_lag"] / 10)); if (d < 0) d = -d
      if (f[1] > 0 && f[3] > 0 && (near == "" || d < near)) {
        near = d; lag0 = f[1]; rel0 = f[3] } }
    END {
      if (rel == "" || v0 + 0 == 0) exit
      p = rel / (v0 * v0)
      bl = "nan"
      if (rel0 > 0 && rel > 0 && lag0 != s["D_s_lag"])
        bl = log(rel / rel0) / log(s["D_s_lag"] / lag0)
      printf "%s,%s,%s,%s,%s,%.6g,%.6g,%s,%.6g,%s,%.4g\n", id, P0, v0, seed,
             s["D_s_lag"], rel, p, s["D_eff"], p * 2 * Dr / (4 * s["D_s_lag"]),
             s["msd_beta"], bl
    }' "$run/params.txt" "$run/analysis/summary.txt" "$run/analysis/msd.csv"
done
if [ -f "${TMPDIR:-/tmp}/msd_plateau.$$" ]; then
  echo "tools/msd_plateau.sh: $(cat "${TMPDIR:-/tmp}/msd_plateau.$$") runs of $SWEEP have no analysis yet (left out)" >&2
  rm -f "${TMPDIR:-/tmp}/msd_plateau.$$"
fi
