#!/usr/bin/env bash
# Installs, with apt-get, the Debian packages that only the test suite needs
# (scripts/test.sh calls it; scripts/main.sh does not): ParaView's Python
# (pvpython) and a virtual X server, for the test postproc.XdmfParaView.ThreeReadersAgree
# (scripts/test-xdmf-paraview.sh: the three XDMF readers on the default case's
# results, and a screenshot under xvfb-run). Several hundred MB with their
# dependencies, so not part of scripts/setup-deps.sh. Idempotent, like
# setup-deps.sh: packages already installed are not touched; nothing is
# downloaded from anywhere but the Debian archive.
set -euo pipefail

# xauth and xfonts-base are only Recommends of xvfb, but xvfb-run needs xauth and
# Xvfb its "fixed" font; OpenGL (Mesa's software rasteriser) comes as a Depends.
PACKAGES=(paraview python3-paraview xvfb xauth xfonts-base)

missing=()
for pkg in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup-test-deps: all ${#PACKAGES[@]} packages present"
  exit 0
fi

echo "setup-test-deps: installing ${missing[*]}"
SUDO=""
if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -q
$SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
