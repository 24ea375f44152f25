#!/bin/sh
# examples/spreading.sh -- a cluster spreading in open space: 100 cells
# start as a compact lattice patch (no periodic box: the tissue has a free
# edge), become motile (v0 = 2.5) and soft (P0 = 7, above the mean-field
# P0* = 5.73), and spread; then examples/analysis.c (built against the
# installed library) tables the cluster's radius of gyration, shape index
# and N_GC/N frame by frame.  A few seconds.
#
#   sh examples/spreading.sh OUTDIR   (run again: the run is kept, the
#                                      analysis redone)
#
# Uses afv and pkg-config's afv from PATH and PKG_CONFIG_PATH (after
# make install; e.g. PATH=$PREFIX/bin:$PATH
# PKG_CONFIG_PATH=$PREFIX/lib/pkgconfig).
set -eu
out=${1:?usage: spreading.sh OUTDIR}
here=$(dirname "$0")
mkdir -p "$out"

afv run --out "$out/spreading" --box open --N 100 --init lattice \
  --spacing 1.8 --P0 7 --v0 2.5 --steps 3000 --frame_every 300 \
  --svg_every 0 --quiet --continue
# the custom analysis: rpath from pkg-config, so no LD_LIBRARY_PATH
cc -std=c99 -o "$out/analysis" "$here/analysis.c" \
  $(pkg-config --cflags --libs afv)
"$out/analysis" "$out/spreading/trajectory.dat" 7 > "$out/spreading.csv"
cat "$out/spreading.csv"
# the cluster has grown: last radius of gyration above the first
awk -F, 'NR == 2 { r0 = $2 } END { print "radius of gyration " r0 " -> " $2;
  exit !($2 > r0) }' "$out/spreading.csv"
