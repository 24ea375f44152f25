#!/bin/sh
# tools/deff_estimators.sh RUN_DIR... -- the D_eff estimators side by side
# for finished, analysed runs (afv analyze: RUN/analysis/msd.csv and
# summary.txt; RUN/params.txt), one CSV row per run on stdout:
#
#   run,P0,v0,seed,dt,lag,D_0,msd_rel,msd_rel_se,single,slope,fit,
#   single_per_step,slope_from,fit_from
#
# All from the relative MSD (the cage-relative displacement afv's D_s
# uses), at the run's D_s lag L (summary's D_s_lag, e.g. 5010 time units
# for the paper's lag 5000 on frames every 10), D_0 = v0^2 / (2 Dr):
#   single  MSD_rel(L) / (4 L D_0): afv's D_eff (summary.txt), the paper's
#           D_s = MSD(L) / (4 L) at one lag, in time units;
#   slope   (MSD_rel(L) - MSD_rel(L1)) / (4 (L - L1) D_0), L1 the lag of
#           msd.csv nearest L/2 (slope_from): the growth over the last
#           half, which a plateau reached early does not inflate;
#   fit     the least-squares slope of MSD_rel against lag over msd.csv's
#           lags from the one nearest L/5 (fit_from) to L, / (4 D_0);
#   single_per_step  single with the lag counted in steps (L / dt) rather
#           than in time: single x dt.  A possible reading of the paper's
#           floor D_eff < 1e-8 (a factor dt = 0.01 below the time-unit
#           one); it cannot be checked without the authors' code.
# msd_rel_se: the standard error of MSD_rel(L) across the cells (msd.csv
# of afv 0.4.0 and later; empty before).  afv's glassy label uses neither
# floor: afv collect labels a state glassy when msd_beta < 0.5 (the
# exponent of MSD_rel over lags 1%..10% of the window), which does not
# depend on the run length (doc/reproduction/paper/README.md).
# Exit status 2 (nothing written) if a RUN lacks one of its files.
# tools/deff_estimators.sh --header prints the header line alone.
set -e
HEADER="run,P0,v0,seed,dt,lag,D_0,msd_rel,msd_rel_se,single,slope,fit,single_per_step,slope_from,fit_from"
[ "${1-}" = --header ] && { echo "$HEADER"; exit 0; }
[ $# -ge 1 ] || { echo "usage: tools/deff_estimators.sh [--header] RUN_DIR..." >&2; exit 2; }
for run in "$@"; do
  for f in params.txt analysis/summary.txt analysis/msd.csv; do
    [ -f "$run/$f" ] || { echo "tools/deff_estimators.sh: $run/$f: no such file" >&2; exit 2; }
  done
done
echo "$HEADER"
for run in "$@"; do
  awk -v run="$run" '
    FILENAME ~ /params.txt$/ && NF >= 2 { p[$1] = $2 }
    FILENAME ~ /summary.txt$/ && NF >= 2 { s[$1] = $2 }
    FILENAME ~ /msd.csv$/ {
      n_ = split($0, f, ",")
      if (FNR == 1) { for (k = 1; k <= n_; k++) col[f[k]] = k; next }
      m++; lag[m] = f[col["lag"]] + 0; rel[m] = f[col["msd_rel"]] + 0
      se[m] = ("msd_rel_se" in col) ? f[col["msd_rel_se"]] : ""
    }
    # index of the lag nearest x in log
    function nearest(x,   k, b) {
      b = 1
      for (k = 2; k <= m; k++)
        if ((lag[k] > 0 && x > 0) && (log(lag[k] / x) ^ 2 < log(lag[b] / x) ^ 2)) b = k
      return b
    }
    END {
      L = s["D_s_lag"] + 0; d0 = p["v0"] ^ 2 / (2 * p["Dr"])
      e = nearest(L); a = nearest(L / 2); b = nearest(L / 5)
      single = rel[e] / (4 * lag[e] * d0)
      slope = (rel[e] - rel[a]) / (4 * (lag[e] - lag[a]) * d0)
      sx = sy = sxx = sxy = 0; c = 0
      for (k = b; k <= e; k++) { sx += lag[k]; sy += rel[k]; sxx += lag[k] ^ 2; sxy += lag[k] * rel[k]; c++ }
      fit = c >= 2 ? (c * sxy - sx * sy) / (c * sxx - sx * sx) / (4 * d0) : "nan"
      printf "%s,%g,%g,%s,%g,%g,%g,%g,%s,%g,%g,%s,%g,%g,%g\n", run, p["P0"] + 0, p["v0"] + 0,
        p["seed"], p["dt"] + 0, lag[e], d0, rel[e], se[e], single, slope, fit,
        single * p["dt"], lag[a], lag[b]
    }' "$run/params.txt" "$run/analysis/summary.txt" "$run/analysis/msd.csv"
done
