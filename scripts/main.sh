#!/usr/bin/env bash
# Set up, build, and run the main job on the bundled default case.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
./build/app/kinetofem run cases/lever_chain_manipulator/case.toml "$@"
