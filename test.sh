#!/usr/bin/env bash
# Set-up, build, and run the whole test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")"
source scripts/ensure-deps.sh
weft_ensure_deps
weft_build
cd "${WEFT_BUILD_DIR:-build}"
ctest --output-on-failure -j "$(nproc 2>/dev/null || echo 2)" "$@"
