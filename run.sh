#!/usr/bin/env bash
# Set-up, build, and run Weft's main job on the default scene.
set -euo pipefail
cd "$(dirname "$0")"
source scripts/ensure-deps.sh
weft_ensure_deps
weft_build
scene=${1:-assets/scenes/wind.json}
out=${2:-out/run}
./build/app/weft simulate "$scene" --out "$out"
echo "output written to $out/ (positions.npy, stats.csv, rest.obj, summary.json)"
