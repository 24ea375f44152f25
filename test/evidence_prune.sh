#!/bin/sh
# evidence_prune.sh -- the cost of one cell's shape against its number of
# neighbours k (issue 22: pruning, k log k instead of k^2).
#
#   sh test/evidence_prune.sh [AFV [OLD_AFV]]
#
# For k of about 6, 50 and 700 (uniform random centres in a periodic box,
# density k / (4 pi) per l^2, l = 1), times `afv eval` (wall clock, best of
# 3) and, if valgrind is installed and the run is small enough, counts its
# instructions (callgrind); prints one line per k:
#   k=K N=N box=L wall_s=T us_per_cell=X [Ir_per_cell=I] [old_wall_s=T0]
# OLD_AFV (optional) is an afv built before the change, timed the same way.
# Wall times on a shared machine are rough; the instruction counts are not.
set -e
AFV=${1:-./afv}
OLD=${2:-}
TMP=${TMPDIR:-/tmp}/afv_prune.$$
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT

points() {   # N L SEED -> uniform random centres in [0, L)^2
  awk -v n="$1" -v L="$2" -v s="$3" 'BEGIN { srand(s);
    for (i = 0; i < n; i++) printf "%.17g %.17g\n", L * rand(), L * rand() }'
}

best_of_3() {  # PROGRAM FILE BOX -> the shortest of 3 wall times, seconds
  b=""
  for t in 1 2 3; do
    s=$(date +%s.%N)
    "$1" eval "$2" --box "$3,$3" > /dev/null
    e=$(date +%s.%N)
    b=$(awk -v s="$s" -v e="$e" -v b="$b" 'BEGIN { d = e - s;
      print (b == "" || d < b) ? d : b }')
  done
  echo "$b"
}

for spec in "6 40" "50 20" "700 12"; do
  set -- $spec
  k=$1 L=$2
  n=$(awk -v k="$k" -v L="$L" 'BEGIN { printf "%d", k * L * L / (4 * 3.14159265358979) }')
  points "$n" "$L" 22 > "$TMP/p.xy"
  w=$(best_of_3 "$AFV" "$TMP/p.xy" "$L")
  line="k=$k N=$n box=$L wall_s=$w us_per_cell=$(awk -v w="$w" -v n="$n" 'BEGIN { printf "%.2f", 1e6 * w / n }')"
  if command -v valgrind > /dev/null 2>&1 && [ "$k" -le 50 ]; then
    valgrind --tool=callgrind --callgrind-out-file="$TMP/cg" "$AFV" eval \
      "$TMP/p.xy" --box "$L,$L" > /dev/null 2> "$TMP/vg"
    ir=$(sed -n 's/.*refs: *//p' "$TMP/vg" | tr -d ,)
    line="$line Ir_per_cell=$(awk -v i="$ir" -v n="$n" 'BEGIN { printf "%d", i / n }')"
  fi
  if [ -n "$OLD" ]; then
    line="$line old_wall_s=$(best_of_3 "$OLD" "$TMP/p.xy" "$L")"
  fi
  echo "$line"
done
