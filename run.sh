#!/usr/bin/env bash
# Set-up, build, and run Weft's main job.
#   ./run.sh                 with a display: the editor on the default scene;
#                            headless (or WEFT_HEADLESS=1): simulate the default scene into
#                            out/run, then a system-identification optimisation into out/sysid
#   ./run.sh SCENE [OUT]     headless simulation of SCENE into OUT (default out/run)
# Builds only what that job runs: `weft`, and `weft-editor` when the editor opens (the tests and
# the generated task targets of app/CMakeLists.txt are test.sh's; wind_sysid's target is
# committed). WEFT_DRY_RUN=1 prints the build command and stops (tests/app/RunScriptTest.cpp).
set -euo pipefail
cd "$(dirname "$0")"
source scripts/ensure-deps.sh

opens_editor=0
if [ $# -eq 0 ] && [ -n "${DISPLAY:-}" ] && [ -z "${WEFT_HEADLESS:-}" ]; then
  opens_editor=1
fi
targets=(weft)
[ "$opens_editor" -eq 1 ] && targets+=(weft-editor)

weft_ensure_deps
weft_build "${targets[@]}"
[ -n "${WEFT_DRY_RUN:-}" ] && exit 0

if [ "$opens_editor" -eq 1 ]; then
  exec ./build/app/editor/weft-editor assets/scenes/wind.json
fi

scene=${1:-assets/scenes/wind.json}
out=${2:-out/run}
./build/app/weft simulate "$scene" --out "$out"
echo "output written to $out/ (positions.npy, stats.csv, rest.obj, summary.json)"
if [ $# -eq 0 ]; then
  # Recover the stretch and wind strength that made a recorded motion (DiffCloth Sec. 6).
  ./build/app/weft optimize assets/scenes/wind_sysid.json --out out/sysid
  echo "optimisation written to out/sysid/ (loss.csv, result.json, loss.png)"
fi
