#!/bin/sh
# tools/model_cap.sh OUT DEST -- the regularised (capped) model and the
# finite-size study of tools/model_sweeps.sh OUT, from what has finished,
# into DEST (doc/reproduction/model/); tools/model_table.sh runs it after
# writing DEST/runs.csv, which it reads.  Writes
#
#   cap/            the capped model's record, as the exact model's
#                   (doc/reproduction/paper/): tools/paper_record.sh on a
#                   copy of cap_grid's finished runs (afv collect, then afv
#                   paper --grid-only; collected by the sweep's own afv,
#                   which ran the runs): grid_table.csv, grid_fits.txt,
#                   claims.csv (the same rules; a claim whose runs are not
#                   all in says missing), figures/fig*.svg, runs.csv,
#                   plateau.csv, progress.txt; and figures/compare_*.svg:
#                   the exact record (EXACT) and the capped one side by
#                   side on one colour scale (afv paper --compare), and
#                   compare.csv: both tables point by point (N_GC/N, Omega
#                   and their labels; n_cap 0 where no capped run is in)
#   cap_dt_table.csv  per point of cap_dt and observable: the capped model
#                   at dt 0.01 (cap_grid) and 0.005 (cap_dt), converged by
#                   the rule of README.md, and each phase label at both
#   cap_seq_table.csv  N_GC/N, clusters, Omega, D_eff at cap_seq's points
#                   against cap: cap 0 the exact model (dt_D3), 0.45 the
#                   cap grid (and cap_dt where it has the point), the
#                   others cap_seq (each also at dt 0.00125: cap_seq_dt
#                   and cap_seq_dt--caps); `finest` marks each cap's
#                   finest dt in
#   fss_table.csv   N_GC/N, clusters, Omega against N: N 400 from the exact
#                   record's grid_table.csv (EXACT), the others fss_*
#   fss_crossing.csv  per N, where the lowest P0's N_GC/N curve falls
#                   below the highest's (tools/model_plot --crossing)
#   figures/cap_seq_*.svg, figures/fss_*.svg (against v0, and at v0 1.85
#                   against N: fss_*_vs_N.svg)
#
# Every state point of a sweep's design is in the tables, with n_seeds 0
# (and nan) where no run has finished: nothing is left out silently.
# Reads OUT only: afv collect and afv paper write into a copy (mktemp).
# EXACT (default doc/reproduction/paper) is the exact model's record; AFV
# the afv program (default ./afv).
set -e
OUT=${1:?usage: tools/model_cap.sh OUT DEST}
DEST=${2:?usage: tools/model_cap.sh OUT DEST}
HERE=$(cd "$(dirname "$0")/.." && pwd)
AFV=${AFV:-$HERE/afv}
EXACT=${EXACT:-$HERE/doc/reproduction/paper}
PLOT=$HERE/tools/model_plot
RUNS=$DEST/runs.csv
[ -f "$RUNS" ] || { echo "tools/model_cap.sh: no $RUNS (run tools/model_table.sh)" >&2; exit 2; }
WORK=$(mktemp -d "${TMPDIR:-/tmp}/model_cap.XXXXXX")
trap 'rm -rf "$WORK"' EXIT; trap 'exit 130' INT; trap 'exit 143' TERM
mkdir -p "$DEST/figures"

# commit FILE: FILE.tmp replaces FILE (every table is written whole, then moved)
commit() { mv "$1.tmp" "$1"; }
# sort_below_header KEYS: the first line as it is, the others sorted (sort -t,)
sort_below_header() { read -r head; echo "$head"; sort -t, "$@"; }

# $WORK/design.csv: every job of every sweep (its keys from jobs/ID.conf):
# sweep,id,P0,v0,seed,dt,cap,N.  A sweep NAME--PART adds runs (another
# seed, other caps) to NAME's design: its jobs are listed as NAME's.
for dir in "$OUT"/*/; do
  [ -f "$dir/points.csv" ] || continue
  s=$(basename "$dir"); s=${s%%--*}
  for conf in "$dir"jobs/*.conf; do
    [ -f "$conf" ] || continue
    awk -v s="$s" -v id="$(basename "$conf" .conf)" '
      { p[$1] = $2 }
      END { printf "%s,%s,%s,%s,%s,%s,%s,%s\n", s, id, p["P0"] + 0, p["v0"] + 0,
              p["seed"], p["dt"] + 0, p["cap"] + 0, p["N"] }' "$conf"
  done
done > "$WORK/design.csv"

# design_means SWEEPS: per state point (sweep, P0, v0, dt, cap, N) of the
# sweeps named (an awk regular expression; NAME--PART counts as NAME), n_design (its jobs), n_seeds
# (its runs in runs.csv) and each observable's mean and standard error over
# those runs (sem empty with one run; nan and empty with none).
design_means() {
  awk -F, -v want="$1" '
    FILENAME ~ /design.csv$/ {
      if ($1 !~ want) next
      key = $1 "," $3 "," $4 "," $6 "," $7 "," $8
      if (!(key in nd)) order[++nk] = key
      nd[key]++; next }
    FNR == 1 { nobs = NF - 8; for (k = 9; k <= NF; k++) name[k - 8] = $k; next }
    { sweep = $1; sub(/--.*$/, "", sweep)      # NAME--PART: NAME
      key = sweep "," $3 "," $4 "," $6 "," $7 "," $8
      if (!(key in nd)) next
      n[key]++
      for (k = 1; k <= nobs; k++) {
        if ($(k + 8) !~ /^-?[0-9.]+([eE][-+]?[0-9]+)?$/) continue
        x = $(k + 8) + 0; c[key, k]++; s[key, k] += x; q[key, k] += x * x } }
    END {
      printf "sweep,P0,v0,dt,cap,N,n_design,n_seeds"
      for (k = 1; k <= nobs; k++) printf ",%s_mean,%s_sem", name[k], name[k]
      printf "\n"
      for (i = 1; i <= nk; i++) {
        key = order[i]; printf "%s,%d,%d", key, nd[key], n[key]
        for (k = 1; k <= nobs; k++) {
          m = c[key, k]
          if (m == 0) { printf ",nan,"; continue }
          mu = s[key, k] / m
          var = m > 1 ? (q[key, k] - m * mu * mu) / (m - 1) : 0
          if (var < 0) var = 0
          if (m > 1) printf ",%.6g,%.6g", mu, sqrt(var / m)
          else printf ",%.6g,", mu
        }
        printf "\n"
      } }' "$WORK/design.csv" "$RUNS"
}

# ---- cap_dt_table.csv ------------------------------------------------------
# The rule of README.md: converged when the seed means differ by at most
# 2 sqrt(sem_1^2 + sem_2^2), missing without two seeds at both dt.  Where
# dt 0.005 has one seed (cap_dt; its seed 2 is cap_dt--seed2), beside the
# rule: within_one_run, the same test with the dt 0.005 run's error taken
# as one run's scatter at dt 0.01 (sem_0.01 sqrt(n)) -- weaker, stated as
# such.  Labels at the paper's
# thresholds where the observable has one.
design_means '^cap_(grid|dt)$' > "$WORK/cap_dt_means.csv"
awk -F, '
  NR == 1 { for (k = 9; k <= NF; k += 2) { nm = $k; sub(/_mean$/, "", nm); obs[(k - 7) / 2] = nm }
            nobs = (NF - 8) / 2; next }
  $1 == "cap_dt" { pt[++np] = $2 "," $3; fine[$2 "," $3] = $0; next }
  $1 == "cap_grid" { coarse[$2 "," $3] = $0 }
  function label(o, x) {
    if (x == "nan" || x == "") return ""
    if (o == "ngc_frac_mean") return x >= 0.99 ? "clustered" : "dispersed"
    if (o == "omega_mean") return x >= 0.5 ? "epithelial" : "mesenchymal"
    if (o == "msd_beta") return x < 0.5 ? "glassy" : "fluid"
    if (o == "D_eff") return x < 1e-8 ? "glassy" : "fluid"
    return ""
  }
  END {
    print "P0,v0,observable,n_0.01,mean_0.01,sem_0.01,n_0.005,mean_0.005,sem_0.005,diff,bound,converged,bound_one_run,within_one_run,label_0.01,label_0.005,same_label"
    for (i = 1; i <= np; i++) for (o = 1; o <= nobs; o++) {
      split(coarse[pt[i]], C, ","); split(fine[pt[i]], F, ",")
      nc = C[8] + 0; nf = F[8] + 0
      mc = nc ? C[7 + 2 * o] : "nan"; sc = nc ? C[8 + 2 * o] : ""
      mf = nf ? F[7 + 2 * o] : "nan"; sf = nf ? F[8 + 2 * o] : ""
      d = ""; b = ""; conv = "missing"; b1 = ""; w1 = "missing"
      if (nc && nf && mc != "nan" && mf != "nan") {
        d = mc - mf; if (d < 0) d = -d
        if (nc >= 2 && nf >= 2) { b = 2 * sqrt(sc ^ 2 + sf ^ 2); conv = d <= b ? "yes" : "no" }
        if (nc >= 2 && nf == 1) { b1 = 2 * sqrt(sc ^ 2 + nc * sc ^ 2); w1 = d <= b1 ? "yes" : "no" }
      }
      lc = label(obs[o], mc); lf = label(obs[o], mf)
      same = lc == "" || lf == "" ? "" : lc == lf ? "yes" : "no"
      printf "%s,%s,%d,%s,%s,%d,%s,%s,%s,%s,%s,%s,%s,%s,%s,%s\n", pt[i], obs[o], nc, mc, sc,
        nf, mf, sf, d == "" ? "" : sprintf("%.4g", d), b == "" ? "" : sprintf("%.4g", b), conv,
        b1 == "" ? "" : sprintf("%.4g", b1), w1, lc, lf, same
    } }' "$WORK/cap_dt_means.csv" > "$DEST/cap_dt_table.csv.tmp"
commit "$DEST/cap_dt_table.csv"

# ---- cap_seq_table.csv and its figures -------------------------------------
# Rows at cap_seq's points (P0, v0): the exact model (dt_D3, cap 0), the
# cap grid and cap_dt (cap 0.45), cap_seq and its dt check; finest = 1 on the row of each
# (P0, v0, cap) with runs in at the smallest dt: the figures' points.
design_means '^(dt_D3|cap_grid|cap_dt|cap_seq|cap_seq_dt)$' > "$WORK/cap_seq_means.csv"
awk -F, '
  FILENAME ~ /design.csv$/ { if ($1 == "cap_seq") at[$3 "," $4] = 1; next }
  FNR == 1 { printf "P0,v0,cap,dt,source,n_design,n_seeds,finest"
             for (k = 9; k <= 16; k++) printf ",%s", $k; printf "\n"; next }
  ($2 "," $3) in at {
    row[++n] = $0; key = $2 "," $3 "," $5
    if ($8 > 0 && (!(key in best) || $4 < best[key])) best[key] = $4 }
  END {
    for (i = 1; i <= n; i++) {
      split(row[i], f, ","); key = f[2] "," f[3] "," f[5]
      finest = f[8] > 0 && (key in best) && f[4] == best[key]
      printf "%s,%s,%s,%s,%s,%s,%s,%d", f[2], f[3], f[5], f[4], f[1], f[7], f[8],
        finest
      for (k = 9; k <= 16; k++) printf ",%s", f[k]
      printf "\n"
    } }' "$WORK/design.csv" "$WORK/cap_seq_means.csv" \
  | sort_below_header -k1,1n -k2,2n -k3,3g -k4,4g > "$DEST/cap_seq_table.csv.tmp"
commit "$DEST/cap_seq_table.csv"
if [ -x "$PLOT" ] && [ "$(awk -F, '$8 == 1' "$DEST/cap_seq_table.csv" | wc -l)" -gt 0 ]; then
  for o in ngc_frac_mean n_clusters_mean omega_mean D_eff; do
    "$PLOT" "$DEST/cap_seq_table.csv" cap "$o" finest=1 \
      "$DEST/figures/cap_seq_$o.svg" "$o against cap (0: exact; each cap's finest dt)" \
      || true
  done
fi

# ---- fss_table.csv, fss_crossing.csv and their figures ----------------------
# N 400: the exact record's grid at the finite-size study's P0, from its
# smallest v0 up (the grid has no v0 2.3); the others: the fss sweeps.
design_means '^fss_' > "$WORK/fss_means.csv"
awk -F, '
  BEGIN { print "N,P0,v0,source,dt,n_design,n_seeds,ngc_frac_mean_mean,ngc_frac_mean_sem,n_clusters_mean_mean,n_clusters_mean_sem,omega_mean_mean,omega_mean_sem" }
  FILENAME ~ /design.csv$/ { if ($1 ~ /^fss_/) { p0[$3 + 0] = 1; if (!vmin || $4 < vmin) vmin = $4 } next }
  FILENAME ~ /grid_table.csv$/ {
    if (FNR == 1) { for (k = 1; k <= NF; k++) col[$k] = k; next }
    if (!(($1 + 0) in p0) || $2 < vmin) next
    printf "400,%s,%s,exact record,0.01,%s,%s", $1, $2, $(col["n_seeds"]), $(col["n_seeds"])
    split("ngc_frac n_clusters omega", o, " ")
    for (k = 1; k <= 3; k++) printf ",%s,%s", $(col[o[k] "_mean"]), $(col[o[k] "_sem"])
    printf "\n"; next }
  FNR == 1 { next }
  { printf "%s,%s,%s,%s,%s,%s,%s", $6, $2, $3, $1, $4, $7, $8
    for (k = 9; k <= 14; k++) printf ",%s", $k
    printf "\n" }' "$WORK/design.csv" "$EXACT/grid_table.csv" "$WORK/fss_means.csv" \
  | sort_below_header -k1,1n -k2,2n -k3,3n > "$DEST/fss_table.csv.tmp"
commit "$DEST/fss_table.csv"
lo=$(awk -F, 'NR > 1 { print $2 }' "$DEST/fss_table.csv" | sort -g | head -1)
hi=$(awk -F, 'NR > 1 { print $2 }' "$DEST/fss_table.csv" | sort -g | tail -1)
if [ -x "$PLOT" ] && [ -n "$lo" ] && [ "$lo" != "$hi" ]; then
  "$PLOT" --crossing "$DEST/fss_table.csv" ngc_frac_mean P0 "$lo" "$hi" \
    | awk -F, -v lo="$lo" -v hi="$hi" 'NR == 1 { print $0 ",P0_low,P0_high"; next } { print $0 "," lo "," hi }' \
    > "$DEST/fss_crossing.csv.tmp"
  commit "$DEST/fss_crossing.csv"
  for o in ngc_frac_mean omega_mean n_clusters_mean; do
    "$PLOT" "$DEST/fss_table.csv" v0 "$o" all "$DEST/figures/fss_$o.svg" \
      "Finite size: $o against v0 (N 400: the exact record)" \
      N,P0 || true
  done
  for o in ngc_frac_mean n_clusters_mean; do
    "$PLOT" "$DEST/fss_table.csv" N "$o" v0=1.85 "$DEST/figures/fss_${o}_vs_N.svg" \
      "Finite size: $o against N at v0 1.85 (N 400: the exact record)" \
      P0 || true
  done
  "$PLOT" "$DEST/fss_crossing.csv" N v0_cross all "$DEST/figures/fss_crossing.svg" \
    "Where N_GC/N at P0 $lo falls below P0 $hi, against N" \
    P0_low || true
fi

# ---- cap/: the capped model's record -----------------------------------------
# A copy of cap_grid with its finished runs' small files (collect checks
# params, checkpoint, final.svg and the analysis; afv paper reads the
# analysis and final.svg), times kept (collect compares the analysis's
# with analysis.txt's); trajectories are not copied.
if [ -f "$OUT/cap_grid/points.csv" ] \
   && [ "$(awk -F, '$1 == "cap_grid"' "$RUNS" | wc -l)" -gt 0 ]; then
  g=$WORK/record/grid
  mkdir -p "$g/runs"
  cp -p "$OUT/cap_grid/points.csv" "$OUT/cap_grid/analysis.txt" "$g/"
  cp -pR "$OUT/cap_grid/jobs" "$g/"
  for run in "$OUT"/cap_grid/runs/*/; do
    [ -f "$run/analysis/summary.txt" ] || continue
    id=$(basename "$run")
    mkdir -p "$g/runs/$id"
    cp -p "$run/params.txt" "$run/checkpoint.txt" "$g/runs/$id/"
    [ -f "$run/final.svg" ] && cp -p "$run/final.svg" "$g/runs/$id/"
    cp -pR "$run/analysis" "$g/runs/$id/"
  done
  # from the top folder, so that the claims' notes name the dt study by
  # its path in the repository (not this machine's)
  dest=$(cd "$DEST" && pwd) afv=$(cd "$(dirname "$AFV")" && pwd)/$(basename "$AFV")
  # collected by the program that ran and analysed the runs (the sweep's
  # copy: a later afv refuses an older one's summaries), drawn by AFV
  # (the first word of its Makefile's run lines, a path from the sweep)
  collect=$(awk '/ run --config / { print $1; exit }' "$OUT/cap_grid/Makefile")
  case $collect in /*) ;; *) collect=$(cd "$OUT/cap_grid" && pwd)/$collect ;; esac
  [ -x "$collect" ] || collect=$AFV
  (cd "$HERE" && DT_TABLE=doc/reproduction/model/dt_table.csv \
     COLLECT_AFV=$collect sh tools/paper_record.sh "$WORK/record" "$dest/cap" \
     "$afv" > /dev/null)
  "$AFV" paper --compare "$EXACT" "$DEST/cap" "$DEST/cap" > /dev/null
  # cap/compare.csv: the two tables side by side, point by point, on the
  # exact record's grid (n_cap 0 and nan where the capped point is not in)
  awk -F, '
    FNR == 1 { for (k = 1; k <= NF; k++) col[FILENAME, $k] = k; next }
    { key = $1 "," $2; row[FILENAME, key] = $0
      if (FILENAME == exact) order[++n] = key }
    function get(file, key, name,   f) {
      if (!((file, key) in row)) return name == "n_seeds" ? 0 : "nan"
      split(row[file, key], f, ","); return f[col[file, name]] }
    function label(x, level, hi, lo) { return x == "nan" ? "" : x >= level ? hi : lo }
    BEGIN { print "P0,v0,n_exact,n_cap,ngc_exact,ngc_exact_sem,ngc_cap,ngc_cap_sem,omega_exact,omega_exact_sem,omega_cap,omega_cap_sem,cluster_exact,cluster_cap,confluency_exact,confluency_cap" }
    END {
      for (i = 1; i <= n; i++) {
        k = order[i]; ge = get(exact, k, "ngc_frac_mean"); gc = get(cap, k, "ngc_frac_mean")
        oe = get(exact, k, "omega_mean"); oc = get(cap, k, "omega_mean")
        print k "," get(exact, k, "n_seeds") "," get(cap, k, "n_seeds") "," ge "," \
          get(exact, k, "ngc_frac_sem") "," gc "," get(cap, k, "ngc_frac_sem") "," oe "," \
          get(exact, k, "omega_sem") "," oc "," get(cap, k, "omega_sem") "," \
          label(ge, 0.99, "clustered", "dispersed") "," label(gc, 0.99, "clustered", "dispersed") "," \
          label(oe, 0.5, "epithelial", "mesenchymal") "," label(oc, 0.5, "epithelial", "mesenchymal")
      } }' exact="$EXACT/grid_table.csv" cap="$DEST/cap/grid_table.csv" \
    "$EXACT/grid_table.csv" "$DEST/cap/grid_table.csv" > "$DEST/cap/compare.csv.tmp"
  commit "$DEST/cap/compare.csv"
  echo "tools/model_cap.sh: $DEST/cap: $(head -1 "$DEST/cap/progress.txt")"
fi
