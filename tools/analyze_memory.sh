#!/bin/sh
# analyze_memory.sh -- evidence for doc/performance.md ("afv analyze:
# memory"): the peak memory (max RSS, GNU time) of `afv analyze` on runs of
# N cells with more and more frames, beside what holding every frame would
# take (24 bytes a cell and frame), and the trajectory's size.
#
#   sh tools/analyze_memory.sh [AFV] [N]      (default ./afv, N = 1000)
#   OLD=/path/to/older/afv sh tools/analyze_memory.sh   # the same with it
#
# Each run: N cells from the lattice start, no relaxation, a frame every 10
# steps; about a minute in all at N = 1000.
set -e
AFV=${1:-./afv}
N=${2:-1000}
TIME=/usr/bin/time
[ -x "$TIME" ] || { echo "needs GNU time at $TIME" >&2; exit 2; }
TMP=$(mktemp -d /tmp/afv_analyze_memory.XXXXXX)
trap 'rm -rf "$TMP"' EXIT
measure() {   # measure BINARY LABEL STEPS
  "$1" run --N "$N" --init lattice --P0 4.8 --v0 1 --steps "$3" --frame_every 10 \
       --relax_max_steps 0 --svg_every 0 --sample_every 1000 --quiet \
       --out "$TMP/$2_$3" > /dev/null
  bytes=$(wc -c < "$TMP/$2_$3/trajectory.dat")
  $TIME -f "%M %U" -o "$TMP/time" "$1" analyze "$TMP/$2_$3" --lag 10 \
        > /dev/null 2> "$TMP/err" || { cat "$TMP/err" >&2; exit 1; }
  read -r kb cpu < "$TMP/time"
  frames=$(($3 / 10 + 1))
  printf '%-4s N %-6s frames %-6s trajectory %6.1f MB  all frames %6.1f MB  analyze max RSS %6.1f MB  %5.1f s\n' \
         "$2" "$N" "$frames" "$(echo "$bytes / 1000000" | bc -l)" \
         "$(echo "24 * $N * $frames / 1000000" | bc -l)" \
         "$(echo "$kb / 1000" | bc -l)" "$cpu"
}
for steps in 5000 20000 40000; do
  measure "$AFV" new $steps
  [ -n "$OLD" ] && measure "$OLD" old $steps
done
