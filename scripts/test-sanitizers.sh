#!/usr/bin/env bash
# Builds kinetofem with AddressSanitizer + UndefinedBehaviorSanitizer
# (KINETOFEM_SANITIZE=ON, RelWithDebInfo) in build-asan/ and runs the test
# suite there (ctest -LE large). Any sanitizer report fails the test that
# triggered it. Extra arguments go to ctest (e.g. -R robustness).
#   KINETOFEM_JOBS   parallel jobs (default: nproc)
#   BUILD_DIR        build folder (default: build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${BUILD_DIR:-build-asan}
jobs=${KINETOFEM_JOBS:-$(nproc)}
bash scripts/setup-deps.sh
start=$(date +%s)
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKINETOFEM_SANITIZE=ON \
  -DKINETOFEM_BUILD_BENCH=OFF
cmake --build "$build" -j "$jobs"
built=$(date +%s)
# Leaks: on. Third-party leaks (OpenMP runtime, OpenBLAS, Gmsh, HDF5, MPI
# start-up) are suppressed by name in tests/sanitizers/lsan.supp, ours are not.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=0"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/tests/sanitizers/ubsan.supp"
status=0
(cd "$build" && ctest -LE large --output-on-failure -j "$jobs" "$@") || status=$?
end=$(date +%s)
echo "test-sanitizers: build $((built - start)) s, tests $((end - built)) s, total $((end - start)) s"
exit $status
