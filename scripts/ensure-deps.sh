#!/usr/bin/env bash
# Sourced by run.sh and test.sh: makes sure the Debian packages Weft builds with are installed.
# Installs them when it can (root, or sudo without a password); otherwise prints the one
# apt-get line that is needed and exits non-zero.
WEFT_PACKAGES=(
  build-essential cmake pkg-config
  libeigen3-dev libsuitesparse-dev libomp-dev
  nlohmann-json3-dev libtinyobjloader-dev libassimp-dev liblbfgspp-dev libstb-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libimgui-dev libglfw3-dev libosmesa6-dev libegl-dev libgl-dev
  gnuplot-nox xvfb clang-format python3
  python3-dev pybind11-dev python3-numpy python3-torch
  libopenmpi-dev openmpi-bin python3-mpi4py
)

weft_missing_packages() {
  local p missing=()
  for p in "${WEFT_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  echo "${missing[@]}"
}

weft_ensure_deps() {
  [ -n "${WEFT_DRY_RUN:-}" ] && return 0
  local missing
  missing=$(weft_missing_packages)
  [ -z "$missing" ] && return 0
  echo "weft: installing missing Debian packages: $missing"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
      sudo="sudo -n"
    else
      echo "weft: cannot install packages (not root, no sudo). Run:" >&2
      echo "  sudo apt-get install -y $missing" >&2
      return 1
    fi
  fi
  $sudo apt-get update -qq && DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq $missing \
    || { echo "weft: apt-get install failed; run: sudo apt-get install -y $missing" >&2; return 1; }
}

# Configures and builds Release into build/ (or $WEFT_BUILD_DIR): the targets named (e.g. `weft`),
# or every target, tests included, when none is named. With WEFT_DRY_RUN=1 it only prints the
# build command.
weft_build() {
  local dir=${WEFT_BUILD_DIR:-build}
  local jobs
  jobs=$(nproc 2>/dev/null || echo 2)
  local build=(cmake --build "$dir" -j "$jobs")
  [ $# -gt 0 ] && build+=(--target "$@")
  if [ -n "${WEFT_DRY_RUN:-}" ]; then
    echo "${build[*]}"
    return 0
  fi
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release >/dev/null && "${build[@]}"
}
