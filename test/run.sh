#!/bin/sh
# test/run.sh [CLANG] -- make test: the suite (test/run_tests) in two
# processes side by side (the slow suites SLOW beside all the others: a
# 2-core machine finishes in about half the time), the invariant suite
# again in the assert-enabled build (test/run_tests_assert invariants: the
# default CFLAGS hold -DNDEBUG, which compiles the asserts out), a line
# about the page (test/web_needs.sh), and last the runs' counts added up
# as "N passed, M failed, K skipped".  Exit status 1 if a test failed or a
# run ended without its counts (a crash).
SLOW="paper hostile runjob"
out=${TMPDIR:-/tmp}/afv_make_test.$$
trap 'rm -f "$out".*' EXIT
status=0
# shellcheck disable=SC2086
./test/run_tests $SLOW > "$out.1" 2>&1 &
slow=$!
# shellcheck disable=SC2086
./test/run_tests --except $SLOW | tee "$out.2" || status=1
wait $slow || status=1
cat "$out.1"
echo "assert-enabled build, invariants:"
./test/run_tests_assert invariants | tee "$out.3" || status=1
sh test/web_needs.sh "${1:-clang}"
# the closing line of each run: "N passed, M failed, K skipped"
tail -n 1 -q "$out.1" "$out.2" "$out.3" | awk '
  NF == 6 && $2 == "passed," && $4 == "failed," { p += $1; f += $3; s += $5; n++ }
  END {
    if (n != 3) { print "make test: a run ended without its counts"; exit 1 }
    printf "%d passed, %d failed, %d skipped\n", p, f, s
    exit f > 0
  }' || status=1
exit $status
