#!/usr/bin/env bash
# Builds kinetofem with AddressSanitizer + UndefinedBehaviorSanitizer (clang,
# the instrumented tree of scripts/configure-instrumented.sh, build-asan/) and
# runs the test suite there (ctest -LE large, less the long runs named below).
# Any sanitizer report fails the
# test that triggered it. Extra arguments go to ctest (e.g. -R robustness).
#   KINETOFEM_JOBS   parallel jobs (default: nproc)
#   BUILD_DIR        build folder (default: build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
build=${BUILD_DIR:-build-asan}
jobs=${KINETOFEM_JOBS:-$(nproc)}
bash scripts/setup-deps.sh
start=$(date +%s)
BUILD_DIR=$build bash scripts/configure-instrumented.sh
built=$(date +%s)
# Leaks: on. Third-party leaks (OpenMP runtime, OpenBLAS, Gmsh, HDF5, MPI
# start-up) are suppressed by name in tests/sanitizers/lsan.supp, ours are not.
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=0"
# OpenMPI unloads its plugins (dlclose) at MPI_Finalize; kept loaded (dlclose
# a no-op), their one-time allocations show the plugin names lsan.supp lists.
export LD_PRELOAD="$(cd "$build" && pwd)/tests/libkinetofem_keep_libraries_loaded.so"
export LSAN_OPTIONS="suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$root/tests/sanitizers/ubsan.supp"
# Left out here, run in the release stage only: long runs (20-75 s each under
# ASan, 9.6 min of the stage's CPU together) whose code the instrumented
# tests also run on smaller models: the presets' regression numbers, the AMG
# path of a manipulator, timing tests on finer meshes, the STEP linkage case,
# the linkage-vs-preset comparison, the verify suite a second time from a
# copied program, a kill-timing test, ParaView's own Python reading files,
# three of the four superposition-vs-step-by-step comparisons (the lever-chain
# one stays: both paths instrumented) and the node-graph ordering against
# CHOLMOD's METIS (every instrumented solve uses that ordering), and the
# vibration's monolithic reference (AssemblyModes.*: dense eigen-solves of
# 1 200-1 300 DoFs in the test itself; the reduced assembly's code runs
# instrumented in VibrationOverMotion.*) and the vibration keys through the
# whole coarse manipulator job (ManipulatorJob.VibrationKeys..., 67 s here;
# the same stages run instrumented in VibrationOverMotion.* and
# ManipulatorJob.LeverChainRun...), and the factors one at a time through three
# coarse manipulator jobs (ManipulatorJob.FactorsThatDoNotFitTogether..., 62 s
# here; the set-up part by part and the freed factors run instrumented in
# ElasticAssembly.PartsSetUpOneAtATime... and LinearSolver.AReleasedFactor...).
# Keeps CI under its time limit; KINETOFEM_SANITIZER_SKIP="" runs them too.
skip=${KINETOFEM_SANITIZER_SKIP-'^(ManipulatorPresets\.|ManipulatorJob\.FactorAboveTheLimit|NoSourceTree\.CopiedProgramPassesVerifyQuick|ElasticAssemblyCost\.|RigidBoreCost\.|LinkageAssembly\.|KillDuringRun\.ManipulatorKilledWhileWriting|LoadTransferVerification\.AcceleratedLinkBalanced|LinkageParts\.BundledStepCase|postproc\.XdmfParaView\.|Superposition\.(LeverManipulator|FieldsAtEveryKth|FieldTimes)|Types/NodeGraphOrderingTest\.|AssemblyModes\.|ManipulatorJob\.VibrationKeys|ManipulatorJob\.FactorsThatDoNotFitTogether)'}
exclude=()
[[ -n $skip ]] && exclude=(-E "$skip")
status=0
# The release stage's OMP_NUM_THREADS=1 (test.sh) is not applied here: not
# measured under the sanitizers (the one run with it was slower, 732 s of tests
# against 469 s, but its instrumented build was 2x slower too: a loaded machine).
(cd "$build" && ctest -LE large "${exclude[@]}" --output-on-failure -j "$jobs" "$@") || status=$?
end=$(date +%s)
echo "test-sanitizers: build $((built - start)) s, tests $((end - built)) s, total $((end - start)) s"
exit $status
