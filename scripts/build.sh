#!/usr/bin/env bash
# Installs missing Debian packages, then configures and builds kinetofem
# (Release) in build/. Idempotent; used by scripts/main.sh and scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build -j "${KINETOFEM_JOBS:-$(nproc)}"
