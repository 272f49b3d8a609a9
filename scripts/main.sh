#!/usr/bin/env bash
# Set up, build the program, and run the main job on the bundled default case.
# Builds only the `kinetofem` program (its libraries and itself), not the tests
# and benchmarks: on a fresh 2-core machine that is the difference between the
# first result after about half an hour and after the time README.md states.
# scripts/test.sh builds the rest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh kinetofem
./build/app/kinetofem run cases/lever_chain_manipulator/case.toml "$@"
