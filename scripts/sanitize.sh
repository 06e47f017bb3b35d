#!/usr/bin/env bash
# The test suite's fast part under the sanitizers (docs/hardening.md).
#
#   scripts/sanitize.sh [--thread] [--max-seconds S] [--tests REGEX] [--jobs N]
#
# Default: AddressSanitizer + UndefinedBehaviorSanitizer. Builds every target with
# WEFT_SANITIZE=address,undefined (GCC, -O1, -g1: line tables, enough for the reports' stacks,
# and lighter to build than full debug information) into build-asan/ (or $WEFT_ASAN_BUILD_DIR).
# Leak reports are on; tests/sanitizers/lsan.supp lists the leaks of system libraries that are
# not Weft's.
#
# --thread: ThreadSanitizer. Clang, with LLVM's OpenMP runtime (libomp, whose Archer tool,
# loaded through OMP_TOOL_LIBRARIES, tells TSan about OpenMP's barriers, reductions and tasks;
# GCC's libgomp is not instrumented), into build-tsan/ (or $WEFT_TSAN_BUILD_DIR); the tests run
# with two OpenMP threads each (WEFT_TEST_OMP_THREADS=2) so that every parallel loop is checked.
# Under TSan with Archer a simulation runs hundreds of times slower (every parallel region and
# barrier is tracked), so by default only the suites about concurrency run (the threaded
# broad phases and contact collection, determinism across thread counts, the editor's
# simulation and optimiser threads, the work distributors, the render frame writer; see
# $concurrency below); --tests REGEX picks others.
#
# Either way runs through ctest each test that took under S seconds (default 5) in the last
# normal run (build/Testing/Temporary/CTestCostData.txt, written by ./test.sh), so run ./test.sh
# first; tests not timed there (new ones) run too. --tests REGEX narrows that to the tests whose
# names match; --jobs N builds and tests N at a time (default: the cores). Any sanitizer report
# fails its test: the process aborts on the first finding.
# The Python module is not built (an interpreter without the sanitizer cannot load an
# instrumented extension), nor are the task targets recorded (the normal build did that).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-deps.sh
mode=address
max_seconds=5
only=""
jobs=$(nproc 2>/dev/null || echo 2)
while [ $# -gt 0 ]; do
  case "$1" in
    --thread) mode=thread; shift ;;
    --max-seconds) max_seconds=$2; shift 2 ;;
    --tests) only=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    *) echo "error: scripts/sanitize.sh: $1: unknown option (--thread, --max-seconds S, --tests REGEX, --jobs N)" >&2
       exit 2 ;;
  esac
done
concurrency='^(Solvers/Determinism|ContactScenes/ThreadDeterminism|SelfCollisionDetector|CellSizes/SpatialHash|CollisionBroadPhase|CollisionCrossings|ParallelContactCollector|SerialDistributor|Mpi|Determinism|RenderCli|SimulationCache|EditorSession|OptimizerRun|StateGradients|EditorScript|Fuzz|Sanitizers)[./]'
if [ "$mode" = thread ]; then
  WEFT_PACKAGES+=(clang libomp-dev)
  only=${only:-$concurrency}
fi
weft_ensure_deps

costs=${WEFT_BUILD_DIR:-build}/Testing/Temporary/CTestCostData.txt
if [ ! -f "$costs" ]; then
  echo "error: $costs: no test timings; run ./test.sh first" >&2
  exit 2
fi
# The tests to leave out: those the last normal run timed at S seconds or more (the lines before
# the '---' separator are "name runs average-seconds"; test names are [A-Za-z0-9_./]).
slow=$(awk -v max="$max_seconds" '$1 == "---" { exit } NF == 3 && $3 + 0 >= max { print $1 }' \
  "$costs" | sed 's/\./\\./g' | paste -sd'|' -)

common=(-DCMAKE_BUILD_TYPE=RelWithDebInfo
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG"
  -DWEFT_BUILD_PYTHON=OFF -DWEFT_RECORD_TASK_TARGETS=OFF)
if [ "$mode" = thread ]; then
  dir=${WEFT_TSAN_BUILD_DIR:-build-tsan}
  archer=$(ls /usr/lib/llvm-*/lib/libarcher.so 2>/dev/null | sort -V | tail -1)
  if [ -z "$archer" ]; then
    echo "error: scripts/sanitize.sh: libarcher.so (LLVM's OpenMP tool for TSan) not found; install libomp-dev" >&2
    exit 2
  fi
  # Clang's -fopenmp links LLVM's libomp; CMake's FindOpenMP takes it from there.
  CC=clang CXX=clang++ cmake -S . -B "$dir" "${common[@]}" -DWEFT_SANITIZE=thread \
    -DWEFT_TEST_OMP_THREADS=2 >/dev/null
  export OMP_TOOL_LIBRARIES=$archer
  export ARCHER_OPTIONS="verbose=0"
  # ignore_noninstrumented_modules: accesses inside libraries built without TSan (libomp itself,
  # CHOLMOD, Mesa) are not checked; their own synchronisation is invisible to TSan.
  export TSAN_OPTIONS="halt_on_error=1:abort_on_error=1:second_deadlock_stack=1:history_size=4:ignore_noninstrumented_modules=1"
else
  dir=${WEFT_ASAN_BUILD_DIR:-build-asan}
  cmake -S . -B "$dir" "${common[@]}" -DWEFT_SANITIZE=address,undefined >/dev/null
  # intercept_tls_get_addr=0: GCC 12's runtime (up to GCC 13 and LLVM 16) takes a dynamic TLS
  # block that happens to start 16 bytes past a page boundary for a glibc < 2.25 header and
  # reads a range from it; LeakSanitizer's tracer then crashes at exit ("Tracer caught signal
  # 11"), now and then, in processes that dlopen libraries with TLS (Mesa, Open MPI's plugins).
  export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:intercept_tls_get_addr=0"
  export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
  export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
fi
cmake --build "$dir" -j "$jobs"

cd "$dir"
select=()
[ -n "$only" ] && select=(-R "$only")
leave_out="^(${slow:-none})\$"
echo "sanitize ($mode): the tests under ${max_seconds} s${only:+ matching $only} (leaving out $(
  [ -n "$slow" ] && echo "$slow" | tr '|' '\n' | wc -l || echo 0) slower ones)"
if [ "$mode" = thread ]; then
  ctest --output-on-failure -j "$jobs" "${select[@]}" -E "$leave_out"
else
  # The tests that start MPI ranks (mpirun) run apart, with full stack unwinding on every
  # allocation (slower): Open MPI's allocations still held at exit are suppressed by library
  # (tests/sanitizers/lsan.supp), and the fast unwinder stops at the frames of libraries built
  # without frame pointers, before it reaches the library's name.
  mpi='^(DistributedCli|Mpi)\.'
  # The MPI tests (also matching --tests), by name.
  mpi_tests=$(ctest -N -R "$mpi" | sed -n 's/^ *Test *#[0-9]*: //p' | grep -E "${only:-.}" |
    sed 's/[.\/]/\\&/g' | paste -sd'|' -)
  status=0
  ctest --output-on-failure -j "$jobs" "${select[@]}" -E "$leave_out|$mpi" || status=$?
  if [ -n "$mpi_tests" ]; then
    ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0" \
      ctest --output-on-failure -j "$jobs" -R "^(${mpi_tests})\$" -E "$leave_out" || status=$?
  fi
  exit "$status"
fi
