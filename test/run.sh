#!/bin/sh
# test/run.sh [CLANG] -- make test: the suite (test/run_tests), the invariant
# suite again in the assert-enabled build (test/run_tests_assert invariants:
# the default CFLAGS hold -DNDEBUG, which compiles the asserts out), a line
# about the page (test/web_needs.sh), and last the two runs' counts added up
# as "N passed, M failed, K skipped".  Exit status 1 if a test failed or a
# run ended without its counts (a crash).
out=${TMPDIR:-/tmp}/afv_make_test.$$
trap 'rm -f "$out".*' EXIT
status=0
./test/run_tests | tee "$out.1" || status=1
echo "assert-enabled build, invariants:"
./test/run_tests_assert invariants | tee "$out.2" || status=1
sh test/web_needs.sh "${1:-clang}"
# the closing line of each run: "N passed, M failed, K skipped"
tail -n 1 -q "$out.1" "$out.2" | awk '
  NF == 6 && $2 == "passed," && $4 == "failed," { p += $1; f += $3; s += $5; n++ }
  END {
    if (n != 2) { print "make test: a run ended without its counts"; exit 1 }
    printf "%d passed, %d failed, %d skipped\n", p, f, s
    exit f > 0
  }' || status=1
exit $status
