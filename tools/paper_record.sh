#!/bin/sh
# tools/paper_record.sh OUT DEST AFV -- the small, committable record of a
# `make paper` directory OUT, finished or not: collects both sweeps, runs
# `afv paper OUT`, and writes into DEST (replacing what this script wrote
# there before; anything else in DEST is kept):
#   claims.csv, fss.csv, figures/*.svg    afv paper's outputs
#   grid_table.csv, grid_fits.txt         afv collect's table of OUT/grid
#   runs.csv      one row per finished grid run: id,P0,v0,seed and every
#                 KEY of its analysis/summary.txt (what collect tables)
#   plateau.csv   tools/msd_plateau.sh OUT/grid (the relative MSD's plateau)
#   progress.txt  how many runs of each sweep are in
# Each claim is judged against dt from DT_TABLE (afv paper --dt-table;
# default the committed dt study, doc/reproduction/model/dt_table.csv, the
# paper's length as the record; DT_TABLE= leaves it out).
# Trajectories and per-run files stay in OUT.  Safe while OUT's runners
# are running (they never read what this writes); run it again as runs
# finish.  An OUT without an fss sweep (the regularised model's grid,
# tools/model_table.sh) gets the grid's record alone (afv paper --grid-only:
# no fss.csv).
set -e
OUT=${1:?usage: tools/paper_record.sh OUT DEST AFV}
DEST=${2:?usage: tools/paper_record.sh OUT DEST AFV}
AFV=${3:?usage: tools/paper_record.sh OUT DEST AFV}
# COLLECT_AFV: the afv that collects (default AFV): the runs' own version
# where a later one refuses their summaries (afv 0.5.0 ties a summary to
# its run by run_id and run_fingerprint, which 0.4.0 does not write)
COLLECT_AFV=${COLLECT_AFV:-$AFV}
here=$(dirname "$0")
DT_TABLE=${DT_TABLE-$here/../doc/reproduction/model/dt_table.csv}

sweeps="grid fss" grid_only=
[ -d "$OUT/fss" ] || { sweeps=grid; grid_only=--grid-only; }
# collect: exit 1 means jobs are missing (a partial record), 2 an error
for sweep in $sweeps; do
  st=0; "$COLLECT_AFV" collect "$OUT/$sweep" > /dev/null \
    2> "$OUT/$sweep.collect.err" \
    || st=$?
  [ $st -le 1 ] || { cat "$OUT/$sweep.collect.err" >&2; exit $st; }
done
# shellcheck disable=SC2086
"$AFV" paper $grid_only "$OUT" ${DT_TABLE:+--dt-table "$DT_TABLE"} \
  2> "$OUT/paper.err" \
  || { cat "$OUT/paper.err" >&2; exit 2; }

mkdir -p "$DEST/figures"
rm -f "$DEST"/figures/*.svg
cp "$OUT"/figures/*.svg "$DEST/figures/"
cp "$OUT/claims.csv" "$DEST/"
[ -n "$grid_only" ] || cp "$OUT/fss.csv" "$DEST/"
cp "$OUT/grid/table.csv" "$DEST/grid_table.csv"
cp "$OUT/grid/fits.txt" "$DEST/grid_fits.txt"
sh "$here/msd_plateau.sh" "$OUT/grid" > "$DEST/plateau.csv.tmp" 2> /dev/null
mv "$DEST/plateau.csv.tmp" "$DEST/plateau.csv"

# runs.csv: the keys of the first finished summary make the header (every
# summary of one afv version has the same keys, in the same order)
tail -n +2 "$OUT/grid/points.csv" | while IFS=, read -r id P0 v0 seed; do
  s=$OUT/grid/runs/$id/analysis/summary.txt
  [ -f "$s" ] || continue
  awk -v id="$id" -v P0="$P0" -v v0="$v0" -v seed="$seed" '
    /^#/ { next }
    { k[++n] = $1; v[n] = $2 }
    END {
      h = "id,P0,v0,seed"; r = id "," P0 "," v0 "," seed
      for (i = 1; i <= n; i++) { h = h "," k[i]; r = r "," v[i] }
      print h; print r
    }' "$s"
done | awk 'NR == 1 || NR % 2 == 0' > "$DEST/runs.csv.tmp"
mv "$DEST/runs.csv.tmp" "$DEST/runs.csv"

{
  for sweep in $sweeps; do
    total=$(($(wc -l < "$OUT/$sweep/points.csv") - 1))
    done_=$(ls "$OUT/$sweep"/runs/*/analysis/summary.txt 2>/dev/null | wc -l)
    echo "$sweep: $done_ of $total runs finished and analysed"
  done
  first=$(ls "$OUT"/grid/runs/*/params.txt | head -1)
  echo "runs by: $(head -1 "$first" | grep -o 'afv [0-9][0-9.]*' | head -1)"
  drawn=$("$AFV" --version | grep -o 'afv [0-9][0-9.]*')
  collected=$("$COLLECT_AFV" --version | grep -o 'afv [0-9][0-9.]*')
  if [ "$collected" = "$drawn" ]; then
    echo "collected and drawn by: $drawn"
  else
    echo "collected by: $collected (the runs' own); drawn by: $drawn"
  fi
} > "$DEST/progress.txt"
cat "$DEST/progress.txt"
