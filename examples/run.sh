#!/bin/sh
# examples/run.sh -- runs every example against an installed afv (the
# continuous integration does, after make install PREFIX=...).
#
#   sh examples/run.sh PREFIX OUTDIR     (PYTHON=python3 by default)
#
# PREFIX/bin on PATH, PREFIX/lib/pkgconfig on PKG_CONFIG_PATH and the
# module's directory on PYTHONPATH, as README.md says for a user's PREFIX;
# no LD_LIBRARY_PATH (the C example gets an rpath from pkg-config).
set -eu
prefix=${1:?usage: run.sh PREFIX OUTDIR}
out=${2:?usage: run.sh PREFIX OUTDIR}
here=$(cd "$(dirname "$0")" && pwd)
PYTHON=${PYTHON:-python3}
PATH="$prefix/bin:$PATH"
PKG_CONFIG_PATH="$prefix/lib/pkgconfig${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
PYTHONPATH="$prefix/lib/python3/dist-packages${PYTHONPATH:+:$PYTHONPATH}"
export PATH PKG_CONFIG_PATH PYTHONPATH
unset LD_LIBRARY_PATH

for example in spreading.sh mixture.sh quench.py python_module.py; do
  echo "---- examples/$example"
  case $example in
    *.sh) sh "$here/$example" "$out" ;;
    *.py) "$PYTHON" "$here/$example" "$out" ;;
  esac
done
