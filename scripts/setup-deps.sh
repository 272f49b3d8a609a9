#!/usr/bin/env bash
# Installs, with apt-get, every Debian package kinetofem needs to build and test.
# Idempotent: packages already installed are not touched; nothing is downloaded
# from anywhere but the Debian archive.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config git
  libeigen3-dev
  libsuitesparse-dev libmetis-dev libopenblas-dev
  libsundials-dev
  libhdf5-dev
  libgtest-dev libgmock-dev
  libgmsh-dev gmsh
  libtomlplusplus-dev libcli11-dev libfmt-dev
  libopenmpi-dev openmpi-bin
  libhypre-dev
  libspectra-dev   # header-only Lanczos eigen solver of the vibration stage
  libcairo2-dev
  clang libclang-rt-14-dev lld   # libFuzzer, the sanitizer tree's linker: scripts/configure-instrumented.sh
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "setup-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
