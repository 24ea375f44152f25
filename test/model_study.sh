#!/bin/sh
# test/model_study.sh [AFV] -- tools/model_table.sh on a mini model study:
# the sweeps of tools/model_sweeps.sh that the capped model's record, the
# D_eff estimators and the finite-size tables read (cap_grid, cap_dt and
# cap_dt--seed2, cap_seq, cap_seq_dt, dt_D3, dt_G1, fss_1600, fss_6400;
# same names and keys), each with a few runs of N 40 - 160 and a
# few hundred steps, only some of them run: a partial cap grid (two points
# with both seeds, one with one, one with none), cap_dt, cap_seq, dt_D3,
# dt_G1 and fss_1600 each with a point not run, fss_6400 not run at all.  Checks that every table has a
# row per state point of the design, that what is not run is marked
# (n_seeds 0, nan, missing; the capped claims say missing where a seed is
# short; the side-by-side map counts the points in), and that OUT is not
# written.  About 10 s; make test-model-study, .ci/run.
#
# Exit status 0 if every check passes; each failure is one line.
set -e
AFV=$(cd "$(dirname "${1:-./afv}")" && pwd)/$(basename "${1:-./afv}")
HERE=$(cd "$(dirname "$0")/.." && pwd)
WORK=$(mktemp -d "${TMPDIR:-/tmp}/model_study.XXXXXX")
trap 'rm -rf "$WORK"' EXIT; trap 'exit 130' INT; trap 'exit 143' TERM
OUT=$WORK/out DEST=$WORK/dest
fails=0
fail() { echo "test/model_study.sh: $*"; fails=$((fails + 1)); }

# ---- the mini study ------------------------------------------------------
COMMON="--integrator euler --svg_every 0 --quiet 1 --steady-from 1 --lag 1"
at() { # DT STEPS: a frame every steps/40, a checkpoint every steps/4
  echo "--dt $1 --steps $2 --frame_every $(($2 / 40)) --checkpoint_every $(($2 / 4))"
}
sweep() {
  name=$1; shift
  # shellcheck disable=SC2086
  "$AFV" sweep --out "$OUT/$name" --afv "$AFV" $COMMON "$@" > /dev/null
}
job() { make -s -C "$OUT/$1" "runs/$2/analysis/summary.txt" > /dev/null 2>&1; }
# shellcheck disable=SC2046
{
  sweep cap_grid --N 40 --P0 4,8 --v0 0.4,1.85 --seeds 2 --cap 0.45 $(at 0.01 400)
  sweep cap_dt --N 40 --P0 4,8 --v0 0.4 --seeds 1 --cap 0.45 $(at 0.005 800)
  # NAME--PART adds to NAME's design: seed 2 of (4, 0.4) and a point of its own
  sweep cap_dt--seed2 --N 40 --P0 4 --v0 0.4,1.85 --seed 2 --cap 0.45 $(at 0.005 800)
  sweep cap_seq --N 40 --P0 4,8 --v0 1.85 --seeds 1 --cap 0.2,0.1 $(at 0.0025 1600)
  sweep cap_seq_dt --N 40 --P0 4 --v0 1.85 --seeds 1 --cap 0.1 $(at 0.00125 3200)
  sweep dt_D3 --N 40 --P0 4,8 --v0 1.85 --seeds 1 --cap 0 $(at 0.0025 1600)
  sweep dt_G1 --N 40 --P0 4,8 --v0 0.4 --seeds 1 --cap 0 $(at 0.01 400)
  sweep fss_1600 --N 80 --P0 4,8 --v0 1.4,1.85 --seeds 1 --cap 0 $(at 0.01 400)
  sweep fss_6400 --N 160 --P0 4,8 --v0 1.85 --seeds 1 --cap 0 $(at 0.01 400)
}
# cap_grid ids: 0001 (4,0.4,s1) 0002 (4,0.4,s2) 0003 (4,1.85,s1)
# 0004 (4,1.85,s2) 0005 (8,0.4,s1)
for id in 0001 0002 0003 0004 0005; do job cap_grid $id; done
job cap_dt 0001                                  # (4, 0.4); (8, 0.4) not run
job cap_dt--seed2 0001                           # (4, 0.4) seed 2
job cap_dt--seed2 0002                           # (4, 1.85) seed 2 only
for id in 0001 0002 0003; do job cap_seq $id; done   # (8, cap 0.1) not run
job cap_seq_dt 0001                              # (4, cap 0.1) at dt 0.00125
job dt_D3 0001                                   # P0 4; P0 8 not run
job dt_G1 0002                                   # P0 8; P0 4 not run
# as afv 0.4.0 wrote it: msd.csv without msd_se, msd_rel_se (the table's
# copy is analysed again, which gives them back)
M=$OUT/dt_G1/runs/0002/analysis/msd.csv
cut -d, -f1-5 "$M" > "$M.tmp" && mv "$M.tmp" "$M"
for id in 0001 0002 0003; do job fss_1600 $id; done  # (8, 1.85) not run
# fss_6400: nothing run
touch "$WORK/before"
sleep 1

# ---- the command ------------------------------------------------------------
AFV="$AFV" sh "$HERE/tools/model_table.sh" "$OUT" "$DEST" > "$WORK/log" 2>&1 \
  || { cat "$WORK/log"; fail "tools/model_table.sh failed"; exit 1; }
written=$(find "$OUT" -newer "$WORK/before" | head -3)
[ -z "$written" ] || fail "OUT written: $written"

# rows FILE AWK-CONDITION: how many rows of FILE (after its header) match
rows() { awk -F, "NR > 1 && ($2)" "$1" | wc -l | tr -d ' '; }
expect() { # WHAT GOT WANT
  [ "$2" = "$3" ] || fail "$1: $2, want $3"
}

# the capped record: the grid table holds the points with a run
C=$DEST/cap
for f in grid_table.csv claims.csv progress.txt figures/fig2b_cluster_phase.svg \
         figures/compare_fig2b_cluster_phase.svg figures/compare_fig4b_omega_map.svg \
         figures/compare_fig7a_summary_phase.svg; do
  [ -s "$C/$f" ] || fail "cap/$f not written"
done
expect "cap grid_table rows" "$(rows "$C/grid_table.csv" 1)" 3
expect "cap grid_table (4, 0.4) seeds" "$(rows "$C/grid_table.csv" '$1 == 4 && $2 == 0.4 && $3 == 2')" 1
verdict() { awk -F, -v c="$1" '$1 == c { print $5 }' "$C/claims.csv"; }
expect "claim v0_star" "$(verdict v0_star)" "not measured"
expect "claim P0_omega_half_low_v0 (a partial grid)" "$(verdict P0_omega_half_low_v0)" missing
expect "claim msd_beta_P0_8_v0_0.4 (one seed)" "$(verdict msd_beta_P0_8_v0_0.4)" missing
expect "claim state_P0_8.8_v0_2.6_cluster (no run)" "$(verdict state_P0_8.8_v0_2.6_cluster)" "not measured"
v=$(verdict msd_beta_P0_4_v0_0.4)
[ "$v" = yes ] || [ "$v" = no ] || [ "$v" = undetermined ] \
  || fail "claim msd_beta_P0_4_v0_0.4 (both seeds in): '$v', want a verdict"
! grep -q -e "$HERE" -e "$WORK" "$C/claims.csv" \
  || fail "claims.csv names this machine's paths"
grep -q 'missing: 1 of 2 seeds in at (8, 0.4)' "$C/claims.csv" \
  || fail "claims: the seed count of (8, 0.4) is not given"
# on the exact record's 8 x 9 design, which holds the mini grid's P0 and v0
grep -q 'cap 0.45: N_GC/N.*(3 of 72 points)' "$C/figures/compare_fig2b_cluster_phase.svg" \
  || fail "compare figure: the capped panel does not count 3 of 72 points"
grep -q 'fill="#dddddd"' "$C/figures/compare_fig2b_cluster_phase.svg" \
  || fail "compare figure: the point without a run is not grey"

# compare.csv: the exact record's 72 points, 3 with capped runs
expect "cap/compare.csv rows" "$(rows "$C/compare.csv" 1)" 72
expect "cap/compare.csv not in" "$(rows "$C/compare.csv" '$4 == 0 && $7 == "nan" && $14 == ""')" 69
expect "cap/compare.csv (4, 0.4)" "$(rows "$C/compare.csv" '$1 == 4 && $2 == 0.4 && $4 == 2 && $14 != ""')" 1

# cap_dt with cap_dt--seed2: 3 points x 8 observables; (4, 0.4) both
# seeds at both dt, judged by the rule; (4, 1.85) one run at dt 0.005, the
# one-run test; (8, 0.4) missing
T=$DEST/cap_dt_table.csv
expect "cap_dt rows" "$(rows "$T" 1)" 24
expect "cap_dt (8, 0.4) missing" "$(rows "$T" '$1 == 8 && $7 == 0 && $12 == "missing"')" 8
expect "cap_dt (4, 0.4) seed 2 from cap_dt--seed2" \
  "$(rows "$T" '$1 == 4 && $2 == 0.4 && $4 == 2 && $7 == 2 && ($12 == "yes" || $12 == "no")')" 7
expect "cap_dt (4, 1.85) one-run test" \
  "$(rows "$T" '$1 == 4 && $2 == 1.85 && $4 == 2 && $7 == 1 && $12 == "missing" && ($14 == "yes" || $14 == "no")')" 7
expect "cap_dt labels" "$(rows "$T" '$1 == 4 && $3 == "ngc_frac_mean" && $15 != "" && $16 != ""')" 2

# cap_seq: P0 4, 8 x caps 0, 0.1, 0.2, 0.45 and its dt check (4, cap 0.1,
# dt 0.00125), the finest of that cap; cap 0.45 at (4, 1.85) also at dt
# 0.005 (cap_dt--seed2); not run: n_seeds 0, nan
T=$DEST/cap_seq_table.csv
expect "cap_seq rows" "$(rows "$T" 1)" 10
expect "cap_seq dt check finest" "$(rows "$T" '$1 == 4 && $3 == 0.1 && $4 == 0.00125 && $5 == "cap_seq_dt" && $8 == 1')" 1
expect "cap_seq dt check's coarser row" "$(rows "$T" '$1 == 4 && $3 == 0.1 && $4 == 0.0025 && $8 == 0')" 1
expect "cap_seq not run" "$(rows "$T" '$7 == 0 && $8 == 0 && $9 == "nan"')" 3
expect "cap_seq exact at P0 4" "$(rows "$T" '$1 == 4 && $3 == 0 && $5 == "dt_D3" && $8 == 1')" 1
expect "cap_seq cap 0.45 at dt 0.005 finest" "$(rows "$T" '$1 == 4 && $3 == 0.45 && $4 == 0.005 && $5 == "cap_dt" && $8 == 1')" 1
expect "cap_seq cap 0.45 at dt 0.01 not finest" "$(rows "$T" '$1 == 4 && $3 == 0.45 && $4 == 0.01 && $5 == "cap_grid" && $7 == 2 && $8 == 0')" 1

# the D_eff estimators: the glass sweep's one finished run, named by its
# sweep, with MSD_rel's error; its single-lag D_eff is the summary's
T=$DEST/deff_estimators.csv
expect "deff_estimators rows" "$(rows "$T" 1)" 1
# with no run in at all: the same header, alone
mkdir "$WORK/empty"
AFV="$AFV" sh "$HERE/tools/model_table.sh" "$WORK/empty" "$WORK/dest0" > /dev/null 2>&1 \
  || fail "tools/model_table.sh failed on a study with no run"
expect "deff_estimators with no run" "$(cat "$WORK/dest0/deff_estimators.csv")" "$(head -1 "$T")"
expect "deff_estimators run" "$(awk -F, 'NR == 2 { print $1 "," $2 }' "$T")" "dt_G1/runs/0002,8"
expect "deff_estimators msd_rel_se" "$(rows "$T" '$9 > 0')" 1
expect "deff_estimators single = D_eff" \
  "$(awk -F, 'NR == 2 { printf "%.6g", $10 }' "$T")" \
  "$(awk '$1 == "D_eff" { printf "%.6g", $2 }' "$OUT/dt_G1/runs/0002/analysis/summary.txt")"

# finite size: N 80 (4), 160 (2, not run), 400 from the exact record
T=$DEST/fss_table.csv
expect "fss N 80 rows" "$(rows "$T" '$1 == 80')" 4
expect "fss N 80 not run" "$(rows "$T" '$1 == 80 && $7 == 0 && $8 == "nan"')" 1
expect "fss N 160 not run" "$(rows "$T" '$1 == 160 && $7 == 0 && $8 == "nan"')" 2
expect "fss N 400 from the record" "$(rows "$T" '$1 == 400 && $4 == "exact record"')" 10
# a crossing needs two v0 with both P0 in: N 80 has two designed, one in
# (missing); N 160's design has one v0 (not measured, whatever is run)
crossing() { awk -F, -v n="$1" '$1 == n { print $2 "," $3 }' "$DEST/fss_crossing.csv"; }
expect "fss crossing N 80" "$(crossing 80)" "missing,1"
expect "fss crossing N 160" "$(crossing 160)" "not measured,0"
expect "fss crossing N 400" "$(crossing 400 | cut -d, -f2)" 5
for f in cap_seq_ngc_frac_mean cap_seq_omega_mean fss_ngc_frac_mean fss_ngc_frac_mean_vs_N \
         fss_crossing; do
  [ -s "$DEST/figures/$f.svg" ] || fail "figures/$f.svg not written"
done

[ $fails -eq 0 ] && echo "test/model_study.sh: every check passed" && exit 0
echo "test/model_study.sh: $fails checks failed"
exit 1
