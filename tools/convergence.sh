#!/bin/sh
# tools/convergence.sh OUT [AFV] -- the detachment convergence study
# (doc/reproduction/convergence.md): how N_GC/N, the number of clusters and
# Omega depend on the integration of Eq. (4), at N = 400, P0 4 and 8,
# v0 1, 1.85 and 2.6, 2 seeds, t = 1500 (steady window t >= 500), from the
# authors' start (init cluster):
#   euler      dt 0.02, 0.01, 0.005, 0.0025, exact force (cap 0) and PyAFV's
#              contact cap 0.45 (one sweep per dt: steps = 1500 / dt)
# (The committed study, doc/reproduction/convergence.md, also has the
# sub-steps, `integrator substeps` at max_move 0.1 to 0.0125, measured
# with afv 0.2.0; afv 0.3.0 removed them, and this script no longer runs
# or tables them.)
# Writes the sweeps into OUT/ (afv sweep), runs their jobs (make -j2; a run
# stopped and started again continues where it stopped), tables them
# (afv collect) and writes OUT/convergence.csv (one row per scheme,
# setting and state point), OUT/verdicts.csv (the finest two settings
# compared), OUT/tables.md (the same as markdown tables) and
# OUT/figures/*.svg (tools/convergence_plot).
# JOBS=K sets make's -j (default 2); COLLECT_ONLY=1 tables what has
# finished without running anything.  Cost: about 1.5 CPU-hours.
# LAMBDA=X runs the study at Lambda = X (default 0.2, the paper's);
# CAPS=LIST the euler schemes' caps (default 0,0.45) (tools/lambda.sh:
# Lambda 0, cap 0).
set -e
OUT=${1:?usage: tools/convergence.sh OUT [AFV]}
HERE=$(cd "$(dirname "$0")/.." && pwd)
AFV=${2:-$HERE/afv}
PLOT=$HERE/tools/convergence_plot
JOBS=${JOBS:-2}
LAMBDA=${LAMBDA:-0.2}
CAPS=${CAPS:-0,0.45}
COMMON="--N 400 --P0 4,8 --v0 1,1.85,2.6 --seeds 2 --Lambda $LAMBDA
        --sample_every 0 --svg_every 0 --quiet 1 --steady-from 500 --lag 50"

mkdir -p "$OUT"
# A copy of the program, so that a rebuild during the study changes nothing.
[ -x "$OUT/afv" ] || cp "$AFV" "$OUT/afv"

# sweep NAME ARGS: written once, kept (its runs resume) if it exists.
sweep() {
  name=$1; shift
  if [ -d "$OUT/$name" ]; then echo "$OUT/$name: kept"; return 0; fi
  # shellcheck disable=SC2086
  "$OUT/afv" sweep --out "$OUT/$name" --afv "$OUT/afv" $COMMON "$@"
}
# Frames every 2 time units; checkpoints every 100 time units.
sweep euler_dt0.02   --integrator euler --dt 0.02   --cap "$CAPS" \
  --steps 75000  --frame_every 100 --checkpoint_every 5000
sweep euler_dt0.01   --integrator euler --dt 0.01   --cap "$CAPS" \
  --steps 150000 --frame_every 200 --checkpoint_every 10000
sweep euler_dt0.005  --integrator euler --dt 0.005  --cap "$CAPS" \
  --steps 300000 --frame_every 400 --checkpoint_every 20000
sweep euler_dt0.0025 --integrator euler --dt 0.0025 --cap "$CAPS" \
  --steps 600000 --frame_every 800 --checkpoint_every 40000

# COLLECT_ONLY=1: no job is run; what has finished is tabled (collect
# lists the rest in each sweep's missing.txt).
for s in euler_dt0.0025 euler_dt0.005 euler_dt0.01 euler_dt0.02; do
  if [ "${COLLECT_ONLY:-0}" = 1 ]; then
    "$OUT/afv" collect "$OUT/$s" > /dev/null || true
  else
    make -s -C "$OUT/$s" -j "$JOBS"
    "$OUT/afv" collect "$OUT/$s" > /dev/null
  fi
done

# convergence.csv: scheme,setting,P0,v0,n_seeds and the three observables
# (mean and seed standard error), from each sweep's table.csv.
{
  echo "scheme,setting,P0,v0,n_seeds,ngc_frac_mean,ngc_frac_sem,n_clusters_mean,n_clusters_sem,omega_mean,omega_sem"
  for s in euler_dt0.02 euler_dt0.01 euler_dt0.005 euler_dt0.0025; do
    [ -f "$OUT/$s/table.csv" ] || continue
    awk -F, -v sweep="$s" -v caps="$CAPS" '
      NR == 1 { for (k = 1; k <= NF; k++) col[$k] = k; next }
      {
        # cap is a column when swept, else the one value of CAPS
        cap = ("cap" in col) ? $col["cap"] : caps
        scheme = cap + 0 > 0 ? "euler_cap0.45" : "euler"
        set = substr(sweep, 9)
        print scheme "," set "," $col["P0"] "," $col["v0"] "," $col["n_seeds"] \
          "," $col["ngc_frac_mean"] "," $col["ngc_frac_sem"] \
          "," $col["n_clusters_mean"] "," $col["n_clusters_sem"] \
          "," $col["omega_mean"] "," $col["omega_sem"]
      }' "$OUT/$s/table.csv"
  done
} > "$OUT/convergence.csv.tmp"
mv "$OUT/convergence.csv.tmp" "$OUT/convergence.csv"

# verdicts.csv: for each scheme, state point and observable, the finest
# two settings (dt 0.005 and 0.0025), their
# difference and 2 sqrt(sem1^2 + sem2^2): converged if the difference is
# not larger (the criterion stated in convergence.md; equal values, such as
# N_GC/N = 1 at both, are converged); "missing" if one has not finished
# for both seeds.
awk -F, '
  NR == 1 { next }
  {
    fine = $2 == "0.0025"
    next_ = $2 == "0.005"
    key = $1 "," $3 "," $4
    if (fine) { f[key] = $0; keys[key] = 1 }
    if (next_) n[key] = $0
  }
  END {
    print "scheme,P0,v0,observable,finest,next,difference,bound,converged"
    split("ngc_frac n_clusters omega", obs, " ")
    for (key in keys) {
      if (!(key in n)) {               # the next setting has not finished
        for (o = 1; o <= 3; o++) printf "%s,%s,,,,,missing\n", key, obs[o]
        continue
      }
      split(f[key], a, ","); split(n[key], b, ",")
      if (a[5] < 2 || b[5] < 2) {      # a standard error needs 2 seeds
        for (o = 1; o <= 3; o++) printf "%s,%s,,,,,missing\n", key, obs[o]
        continue
      }
      for (o = 1; o <= 3; o++) {
        m = 4 + 2 * o; e = m + 1
        d = a[m] - b[m]; if (d < 0) d = -d
        bound = 2 * sqrt(a[e] * a[e] + b[e] * b[e])
        printf "%s,%s,%.6g,%.6g,%.6g,%.6g,%s\n", key, obs[o], a[m], b[m], d, \
          bound, (d <= bound) ? "yes" : "no"
      }
    }
  }' "$OUT/convergence.csv" | { read -r head; echo "$head"; sort; } \
  > "$OUT/verdicts.csv.tmp"
mv "$OUT/verdicts.csv.tmp" "$OUT/verdicts.csv"

# tables.md: the observables as markdown tables, a row per state point
# and scheme, a column per setting (coarse to fine), mean +- sem.
awk -F, '
  NR == 1 { next }
  {
    key = $3 "," $4 "," $1
    if (!(key in seen)) { seen[key] = 1; order[++nk] = key }
    v[key, $2, 1] = sprintf("%.3f +- %.3f", $6, $7)
    v[key, $2, 2] = sprintf("%.2f +- %.2f", $8, $9)
    v[key, $2, 3] = sprintf("%.3f +- %.3f", $10, $11)
  }
  END {
    split("N_GC/N,number of clusters,Omega", name, ",")
    for (o = 1; o <= 3; o++) {
      printf "\n### %s\n\n", name[o]
      print "| P0 | v0 | scheme | coarsest | | | finest |"
      print "|---|---|---|---|---|---|---|"
      for (k = 1; k <= nk; k++) {
        split(order[k], p, ",")
        split("0.02 0.01 0.005 0.0025", set, " ")
        line = "| " p[1] " | " p[2] " | " p[3]
        for (q = 1; q <= 4; q++) line = line " | " v[order[k], set[q], o]
        print line " |"
      }
    }
  }' "$OUT/convergence.csv" > "$OUT/tables.md"

mkdir -p "$OUT/figures"
"$PLOT" "$OUT/convergence.csv" "$OUT/figures"
echo "tools/convergence.sh: $OUT/convergence.csv, $OUT/verdicts.csv, $OUT/tables.md, $OUT/figures/"
