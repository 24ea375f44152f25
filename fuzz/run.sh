#!/usr/bin/env bash
# fuzz/run.sh NAME SECONDS -- runs the libFuzzer harness fuzz/build/fuzz_NAME
# for SECONDS s from the seed corpus fuzz/corpus/NAME/ (read, never written:
# new inputs go to fuzz/build/NAME.corpus/), with the tokens of
# fuzz/dict/NAME.dict if there is one, then prints one line: executions,
# executions per second, corpus size, and the crash file if one was found.
# The full log is fuzz/build/NAME.log.  Exit status non-zero on a crash.
set -u
name=$1 seconds=$2
build=fuzz/build
log=$build/$name.log
mkdir -p "$build/$name.corpus"
seeds=()
[ -d "fuzz/corpus/$name" ] && seeds=("fuzz/corpus/$name")
[ -f "fuzz/dict/$name.dict" ] && seeds=(-dict="fuzz/dict/$name.dict" "${seeds[@]}")
"$build/fuzz_$name" -max_total_time="$seconds" -timeout=10 \
  -print_final_stats=1 -artifact_prefix="$build/$name-" \
  "$build/$name.corpus" "${seeds[@]}" >"$log" 2>&1
status=$?
stat() { sed -n "s/^stat::$1: *//p" "$log" | tail -1; }
crash=$(ls "$build/$name"-crash-* "$build/$name"-leak-* "$build/$name"-timeout-* \
        "$build/$name"-oom-* 2>/dev/null | head -1)
printf 'fuzz %-10s %9s executions in %s s (%s/s), %s new inputs, %s\n' \
  "$name" "$(stat number_of_executed_units)" "$seconds" \
  "$(stat average_exec_per_sec)" "$(stat new_units_added)" \
  "${crash:-no crash}"
if [ "$status" -ne 0 ]; then
  echo "fuzz $name: FAILED (exit $status); the end of $log:" >&2
  tail -40 "$log" >&2
fi
exit "$status"
