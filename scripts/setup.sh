#!/usr/bin/env bash
# Shared by test.sh and demo.sh: install missing Debian packages, configure and build.
# Usage: source scripts/setup.sh; ambisim_setup [extra cmake args...]
set -euo pipefail

AMBISIM_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
AMBISIM_BUILD="${AMBISIM_BUILD:-$AMBISIM_ROOT/build}"

# What each package is for is listed in the README ("Dependencies").
AMBISIM_PACKAGES=(cmake g++ ninja-build pkg-config libglm-dev libeigen3-dev nlohmann-json3-dev
  libpng-dev catch2 libcli11-dev libbenchmark-dev libvtk9-dev xvfb xauth python3 clang-format
  ffmpeg)
# Only for tests/cli/slurm.sh (a one-node Slurm cluster on localhost); installed by test.sh and
# by that test itself, not by demo.sh.
AMBISIM_SLURM_PACKAGES=(slurm-wlm munge)

ambisim_install_packages() {
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "ambisim: installing missing Debian packages: ${missing[*]}" >&2
  local sudo=()
  [ "$(id -u)" -ne 0 ] && sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
}

ambisim_build() {
  local dir="$1"
  shift
  local jobs
  jobs="$(nproc 2>/dev/null || echo 2)"
  cmake -S "$AMBISIM_ROOT" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$dir" -j "$jobs"
}

ambisim_setup() {
  ambisim_install_packages "${AMBISIM_PACKAGES[@]}"
  ambisim_build "$AMBISIM_BUILD" "$@"
}
