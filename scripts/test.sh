#!/usr/bin/env bash
# Set up, build, and run the test suite (everything except the 'large' label).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest -LE large --output-on-failure -j "${KINETOFEM_JOBS:-$(nproc)}" "$@"
