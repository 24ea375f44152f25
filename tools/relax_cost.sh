#!/bin/sh
# relax_cost.sh -- evidence for doc/performance.md ("Relaxation: cost
# against N"): the CPU time and peak memory of relaxing the authors' start
# (init cluster, the default) at v0 = 0, at each N and P0, one process at a
# time, each capped at LIMIT seconds of wall time.
#
#   sh tools/relax_cost.sh [AFV] [NS] [P0S] [LIMIT]
#   (defaults: ./afv, "400 1600 6400", "4 8", 600; make relax-cost)
#
# Each measurement is `afv run --steps 0` with every optional output off
# (no samples, frames or snapshots: the step-0 files and final.svg only),
# so it is the start, its relaxation and the run's fixed writes; GNU time
# gives the user + system CPU time and the max RSS.  Columns: relaxation
# steps (dt 0.01) and the time t they span, how the relaxation stopped,
# CPU seconds, CPU per cell and step (= per cell and 0.01 of relaxed time)
# and its ratio to the first N's at that P0, CPU per cell for the whole
# relaxation, peak RSS and RSS per cell.  A run that reaches LIMIT is
# reported as "timeout" with the last step log.txt had reached.
AFV=${1:-./afv}
NS=${2:-400 1600 6400}
P0S=${3:-4 8}
LIMIT=${4:-600}
TIME=/usr/bin/time
[ -x "$TIME" ] || { echo "relax_cost.sh: needs GNU time at $TIME" >&2; exit 2; }
TMP=$(mktemp -d /tmp/afv_relax_cost.XXXXXX)
trap 'rm -rf "$TMP"' EXIT INT TERM

printf '%-6s %-3s %-7s %-6s %-9s %-8s %-12s %-6s %-11s %-8s %s\n' N P0 steps t stop \
       cpu_s us/cell-step ratio ms/cell rss_MB kB/cell
for p0 in $P0S; do
  base=
  for n in $NS; do
    dir=$TMP/r_${n}_$p0
    status=0
    $TIME -f "%U %S %M" -o "$TMP/time" timeout "$LIMIT" "$AFV" run --N "$n" \
          --P0 "$p0" --steps 0 --sample_every 0 --frame_every 0 \
          --svg_every 0 --quiet --out "$dir" > /dev/null 2> "$TMP/err" \
      || status=$?
    # GNU time writes "Command exited with non-zero status" first on failure
    read -r user sys kb <<EOF
$(tail -n 1 "$TMP/time")
EOF
    line=$(grep '^relaxation at v0' "$dir/log.txt" 2>/dev/null)
    if [ "$status" -eq 124 ]; then
      steps=$(grep '^relaxing: step' "$dir/log.txt" | tail -n 1 \
              | sed 's/^relaxing: step \([0-9]*\).*/\1/')
      stop=timeout
    elif [ "$status" -ne 0 ] || [ -z "$line" ]; then
      echo "relax_cost.sh: N $n P0 $p0 failed (exit $status):" >&2
      cat "$TMP/err" >&2
      exit 1
    else
      steps=$(echo "$line" | sed 's/.*: \([0-9]*\) steps (t = .*/\1/')
      stop=$(grep '^relaxation:' "$dir/log.txt" | sed \
        -e 's/^relaxation: stopped at a kink.*/kink/' \
        -e 's/^relaxation: converged.*/converged/' \
        -e 's/^relaxation: NOT reached.*/max_steps/' \
        -e 's/^relaxation: stopped at step.*/refused/' | cut -c1-9)
    fi
    [ -n "$steps" ] || steps=0
    # stdin of awk: the figures; one line of the table out
    echo "$n $p0 $steps $user $sys $kb ${base:--}" | awk -v stop="$stop" '{
      cpu = $4 + $5; per = $3 > 0 ? cpu / ($3 * $1) * 1e6 : 0
      ratio = ($7 == "-" || $7 == 0) ? 1 : per / $7
      printf "%-6d %-3s %-7d %-6g %-9s %-8.2f %-12.3f %-6.2f %-11.3f %-8.1f %.2f\n",
             $1, $2, $3, $3 * 0.01, stop, cpu, per, ratio, cpu / $1 * 1e3,
             $6 / 1024, $6 / $1 }' | tee "$TMP/row"
    [ -n "$base" ] || base=$(awk '{print $7}' "$TMP/row")
    rm -rf "$dir"
  done
done
