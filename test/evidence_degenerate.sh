#!/bin/sh
# evidence_degenerate.sh -- afv eval's time and memory on degenerate dense
# inputs (issue 38 item 9), each of which was superlinear before the dense
# search's stop became the cut test (neighbours.c, DENSE):
#   line    N centres evenly on a line of 8 l (open space)
#   circle  N centres evenly on a circle of radius 1 l (cocircular)
#   square  N uniform random centres in a square of side 0.01 l
#
#   sh test/evidence_degenerate.sh [AFV [TIMEOUT_S]]
#
# prints one line per case and N:
#   case=CASE N=N status=S cpu_s=T max_rss_kb=K
# (user + system CPU seconds and the peak resident memory, from GNU time
# if installed, else from the shell's times; status 124 = timed out after
# TIMEOUT_S seconds, default 60).  The targets: N = 8000 (line, square) and
# 2000 (circle) each under 1 s and 100 MB.
set -e
AFV=${1:-./afv}
LIMIT=${2:-60}
TMP=${TMPDIR:-/tmp}/afv_degenerate.$$
mkdir -p "$TMP"
trap 'rm -rf "$TMP"' EXIT

points() {   # CASE N -> the centres
  awk -v c="$1" -v n="$2" 'BEGIN { srand(38); pi = 3.14159265358979324;
    for (i = 0; i < n; i++) {
      if (c == "line") printf "%.17g 0\n", 8 * i / n;
      else if (c == "circle") printf "%.17g %.17g\n", cos(2 * pi * i / n), sin(2 * pi * i / n);
      else printf "%.17g %.17g\n", 0.01 * rand(), 0.01 * rand();
    } }'
}

for spec in "line 1000" "line 8000" "circle 500" "circle 2000" \
            "square 1000" "square 8000"; do
  set -- $spec
  points "$1" "$2" > "$TMP/p.xy"
  st=0
  if [ -x /usr/bin/time ]; then
    timeout "$LIMIT" /usr/bin/time -f "%U %S %M" -o "$TMP/t" "$AFV" eval \
      "$TMP/p.xy" > /dev/null 2>&1 || st=$?
    set -- "$1" "$2" $(cat "$TMP/t" 2>/dev/null | tail -1)
    echo "case=$1 N=$2 status=$st cpu_s=$(awk -v u="${3:-0}" -v s="${4:-0}" 'BEGIN { printf "%.2f", u + s }') max_rss_kb=${5:-?}"
  else
    timeout "$LIMIT" "$AFV" eval "$TMP/p.xy" > /dev/null 2>&1 || st=$?
    echo "case=$1 N=$2 status=$st (no /usr/bin/time: install GNU time for CPU and memory)"
  fi
done
