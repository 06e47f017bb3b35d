#!/usr/bin/env bash
# Runs one libFuzzer target for a while (docs/hardening.md).
#
#   scripts/fuzz.sh TARGET SECONDS [LIBFUZZER-OPTION ...]
#   scripts/fuzz.sh --list
#
# TARGET is scene, mesh_obj, mesh_ply, mesh_gltf, mesh_fbx, npy, stored_run or editor_script
# (tests/fuzz/). Builds the targets with
# clang (WEFT_FUZZ: coverage, AddressSanitizer, UndefinedBehaviorSanitizer) into build-fuzz/ (or
# $WEFT_FUZZ_BUILD_DIR), grows the corpus build-fuzz/corpus/TARGET from the target's seeds (kept
# between runs) and writes what it finds (crash-*, leak-*, timeout-*, oom-*) to
# build-fuzz/findings/TARGET/. The last lines are libFuzzer's final statistics: executions,
# coverage, the corpus. Exit status 1 when something was found.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/ensure-deps.sh
WEFT_PACKAGES+=(clang)
weft_ensure_deps

targets=(scene mesh_obj mesh_ply mesh_gltf mesh_fbx npy stored_run editor_script)
if [ "${1:-}" = "--list" ]; then printf '%s\n' "${targets[@]}"; exit 0; fi
if [ $# -lt 2 ]; then
  echo "error: scripts/fuzz.sh: usage: scripts/fuzz.sh TARGET SECONDS [LIBFUZZER-OPTION ...]" >&2
  exit 2
fi
target=$1 seconds=$2
shift 2
case " ${targets[*]} " in *" $target "*) ;; *)
  echo "error: scripts/fuzz.sh: $target: not a fuzz target (${targets[*]})" >&2; exit 2 ;;
esac

dir=${WEFT_FUZZ_BUILD_DIR:-build-fuzz}
CC=clang CXX=clang++ cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG" -DWEFT_FUZZ=ON -DWEFT_RECORD_TASK_TARGETS=OFF >/dev/null
cmake --build "$dir" -j "$(nproc 2>/dev/null || echo 2)" --target "weft_fuzz_$target"

corpus=$dir/corpus/$target findings=$dir/findings/$target seeds=$dir/seeds/$target
mkdir -p "$corpus" "$findings"
# The seeds, gathered as files into one folder (libFuzzer takes folders; a file argument would
# make it replay that file and stop): every seed file and the files of seed folders, up to 1 MB.
rm -rf "$seeds" && mkdir -p "$seeds"
for s in $(sed -n "s/^$target=//p" "$dir/fuzz-seeds.txt" | tr '|' ' '); do
  [ -e "$s" ] || continue
  find "$s" -maxdepth 1 -type f -size -1024k -exec cp -t "$seeds" {} +
done
dict=()
[ -f "tests/fuzz/$target.dict" ] && dict=(-dict="$PWD/tests/fuzz/$target.dict")

export ASAN_OPTIONS="detect_leaks=1"
export LSAN_OPTIONS="suppressions=$PWD/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1"
export OMP_NUM_THREADS=1
binary=$PWD/$dir/tests/fuzz/weft_fuzz_$target
# Relative mesh paths in scene inputs resolve against the working directory: assets/scenes.
cd assets/scenes
"$binary" "${dict[@]}" -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 \
  -print_final_stats=1 -artifact_prefix="$OLDPWD/$findings/" "$OLDPWD/$corpus" "$OLDPWD/$seeds" \
  "$@"
