#!/bin/sh
# examples/mixture.sh -- a mixture of two cell types in a periodic box:
# 200 cells, half epithelial-like (P0 = 4, v0 = 0.2: cohesive, slow) and
# half mesenchymal-like (P0 = 7, v0 = 1: soft, motile), given to afv run
# as a CELLS file of per-cell columns; then afv analyze and a picture
# coloured by cell type.  A few seconds.
#
#   sh examples/mixture.sh OUTDIR        (afv from PATH)
set -eu
out=${1:?usage: mixture.sh OUTDIR}
mkdir -p "$out"

# one row per cell: the types alternate, so they start mixed
awk 'BEGIN { print "# v0 P0";
  for (i = 0; i < 200; i++) print (i % 2 ? "1 7" : "0.2 4") }' \
  > "$out/types.txt"
afv run --out "$out/mixture" --cells "$out/types.txt" --steps 3000 \
  --frame_every 100 --svg_every 0 --quiet --continue
afv analyze "$out/mixture" --steady-from 10 --lag 1 >/dev/null
grep -E '^(ngc_frac|omega)' "$out/mixture/analysis/summary.txt"
afv draw "$out/mixture/trajectory.dat" --color-by P0 > "$out/mixture.svg"
echo "picture: $out/mixture.svg (cells coloured by P0)"
