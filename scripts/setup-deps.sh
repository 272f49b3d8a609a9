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

bash "$(dirname "$0")/install-debian-packages.sh" setup-deps "${PACKAGES[@]}"
