#!/usr/bin/env bash
# The test suite's fast part under AddressSanitizer + UndefinedBehaviorSanitizer.
#
#   scripts/sanitize.sh [--max-seconds S]
#
# Builds every target with WEFT_SANITIZE=address,undefined (-O1, -g1: line tables, enough for
# the reports' stacks, and lighter to build than full debug information) into build-asan/ (or
# $WEFT_ASAN_BUILD_DIR) and runs through ctest each test that took under S seconds (default 5)
# in the last normal run (build/Testing/Temporary/CTestCostData.txt, written by ./test.sh), so
# run ./test.sh first. Tests not timed there (new ones) run too. Any sanitizer report fails its
# test: the build aborts on the first finding. Leak reports are on; tests/sanitizers/lsan.supp
# lists the leaks of system libraries that are not Weft's. The Python module is not built there
# (an interpreter without AddressSanitizer cannot load an instrumented extension).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-deps.sh
weft_ensure_deps

max_seconds=5
while [ $# -gt 0 ]; do
  case "$1" in
    --max-seconds) max_seconds=$2; shift 2 ;;
    *) echo "error: scripts/sanitize.sh: $1: unknown option (--max-seconds S)" >&2; exit 2 ;;
  esac
done

costs=${WEFT_BUILD_DIR:-build}/Testing/Temporary/CTestCostData.txt
if [ ! -f "$costs" ]; then
  echo "error: $costs: no test timings; run ./test.sh first" >&2
  exit 2
fi
# The tests to leave out: those the last normal run timed at S seconds or more (the lines before
# the '---' separator are "name runs average-seconds"; test names are [A-Za-z0-9_./]).
slow=$(awk -v max="$max_seconds" '$1 == "---" { exit } NF == 3 && $3 + 0 >= max { print $1 }' \
  "$costs" | sed 's/\./\\./g' | paste -sd'|' -)

dir=${WEFT_ASAN_BUILD_DIR:-build-asan}
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DWEFT_SANITIZE=address,undefined -DWEFT_BUILD_PYTHON=OFF >/dev/null
cmake --build "$dir" -j "$(nproc 2>/dev/null || echo 2)"

export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
cd "$dir"
echo "sanitize: ASan+UBSan over the tests under ${max_seconds} s (leaving out $(
  [ -n "$slow" ] && echo "$slow" | tr '|' '\n' | wc -l || echo 0))"
if [ -n "$slow" ]; then
  ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" -E "^(${slow})\$"
else
  ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)"
fi
