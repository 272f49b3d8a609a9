#!/usr/bin/env bash
# Installs missing Debian packages, then configures kinetofem (Release) in build/
# and builds the targets given (default: every target). Idempotent.
#   usage: bash scripts/build.sh [TARGET... | --ctest]
#     bash scripts/build.sh kinetofem   the program only: what scripts/main.sh
#                                       builds (a newcomer's first result: the
#                                       libraries and the program, not the 289
#                                       targets of the tests and benchmarks)
#     bash scripts/build.sh --ctest     what `ctest -LE large` runs: every target
#                                       but the benchmarks
#                                       (scripts/ctest-targets.sh; scripts/test.sh)
#     bash scripts/build.sh             everything, benchmarks included
#   KINETOFEM_JOBS   parallel build jobs (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
targets=("$@")
if [[ ${1:-} == --ctest ]]; then
  mapfile -t targets < <(bash scripts/ctest-targets.sh build)
fi
target_args=()
((${#targets[@]})) && target_args=(--target "${targets[@]}")
cmake --build build -j "${KINETOFEM_JOBS:-$(nproc)}" "${target_args[@]}"
