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

bash "$(dirname "$0")/install-debian-packages.sh" setup-test-deps "${PACKAGES[@]}"
