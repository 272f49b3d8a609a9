#!/usr/bin/env bash
# Configures and builds the instrumented tree that the sanitizer and fuzz
# stages of scripts/test.sh share (one build for both):
#   clang, -O1 -gline-tables-only, linked by lld, AddressSanitizer + UndefinedBehaviorSanitizer
#   on every target (KINETOFEM_SANITIZE), libFuzzer coverage on every target and
#   the fuzz targets of fuzz/ (KINETOFEM_BUILD_FUZZ), tests on, benchmarks off.
# -O1 and line tables only: the sanitizers' recommended optimisation, and half
# the compile time of -O2 -g for the same stack traces. lld: the instrumented
# test programs link several times faster than with GNU ld.
#   usage: bash scripts/configure-instrumented.sh [TARGET... | --ctest]
#     (default: all; --ctest: what `ctest -LE large` runs, scripts/ctest-targets.sh:
#     everything but tests/large, whose compile and link the sanitizer stage
#     does not need; benchmarks are off in this tree)
#   BUILD_DIR (default build-asan), KINETOFEM_JOBS (default nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build-asan}
command -v clang++ > /dev/null || { echo "configure-instrumented.sh: needs clang++ (bash scripts/setup-deps.sh installs it)"; exit 2; }
command -v ld.lld > /dev/null || { echo "configure-instrumented.sh: needs ld.lld (bash scripts/setup-deps.sh installs it)"; exit 2; }
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_MODULE_LINKER_FLAGS=-fuse-ld=lld \
  -DKINETOFEM_SANITIZE=ON -DKINETOFEM_BUILD_FUZZ=ON -DKINETOFEM_BUILD_TESTS=ON -DKINETOFEM_BUILD_BENCH=OFF > /dev/null
targets=("$@")
if [[ ${1:-} == --ctest ]]; then
  mapfile -t targets < <(bash scripts/ctest-targets.sh "$build")
fi
target_args=()
((${#targets[@]})) && target_args=(--target "${targets[@]}")
cmake --build "$build" -j "${KINETOFEM_JOBS:-$(nproc)}" "${target_args[@]}"
