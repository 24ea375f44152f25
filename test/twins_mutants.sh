#!/bin/sh
# twins_mutants.sh -- the twin check must see a wrong sign on either side.
#
#   sh test/twins_mutants.sh [CC]        (from the repository root)
#
# Builds test/twins.c three times into a temporary directory: as it is
# (must agree), with one sign of the chain rule flipped in the plain file
# (reference/afv_plain.c, the (V2) term), and with one flipped in the
# library (afv.c, the (A) term of a).  Each mutant must make the check
# fail (exit status 1).  Exit status 0 if all three behave, 1 if not.
set -eu
CC="${1:-cc}"
FLAGS="-O1 -std=c99 -I. -Itest"
# the library's sources but afv.c (each build brings its own), as the
# Makefile lists them
LIB="$(make -s --no-print-directory print-lib-sources | tr ' ' '\n' | grep -vx 'afv.c' | tr '\n' ' ')"
[ -n "$LIB" ] || { echo "twins_mutants: make print-lib-sources gave nothing"; exit 1; }
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/reference"

# one build: $1 the name, $2 the plain file, $3 the library's afv.c
build() {
  sed 's|"../reference/afv_plain.c"|"reference/afv_plain.c"|' test/twins.c \
    > "$tmp/twins.c"
  cp "$2" "$tmp/reference/afv_plain.c"
  cp "$3" "$tmp/afv.c"
  $CC $FLAGS -I"$tmp" -o "$tmp/$1" "$tmp/twins.c" test/fixtures.c "$tmp/afv.c" \
    $LIB -lm
}

# mutate: $1 the file, $2 the exact line, $3 its replacement, $4 the output
mutate() {
  grep -qF "$2" "$1" || { echo "twins_mutants: not found in $1: $2"; exit 1; }
  awk -v old="$2" -v new="$3" 'index($0, old) && !done {
      sub(/[^ ].*/, new); done = 1 } { print }' "$1" > "$4"
}

mutate reference/afv_plain.c '*gx += (c->Dx - Vx) * k;' '*gx -= (c->Dx - Vx) * k;' \
  "$tmp/plain_v2.c"
mutate afv.c 'ab[0] += 0.5 * c;' 'ab[0] -= 0.5 * c;' "$tmp/afv_area.c"

st=0
run() {   # $1 name, $2 expected exit status
  set +e
  "$tmp/$1" > "$tmp/$1.out"
  got=$?
  set -e
  printf '%-16s exit %d (want %d): %s\n' "$1" "$got" "$2" "$(tail -2 "$tmp/$1.out" | head -1)"
  [ "$got" -eq "$2" ] || st=1
}
build as_is reference/afv_plain.c afv.c
build plain_v2 "$tmp/plain_v2.c" afv.c
build library_area reference/afv_plain.c "$tmp/afv_area.c"
run as_is 0
run plain_v2 1
run library_area 1
exit $st
