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
BUILD_DIR=$build bash scripts/configure-instrumented.sh --ctest
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
# one stayed until 2026-12-03: below) and the node-graph ordering against
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
#
# Also left out (2026-12-03; seconds: the test's time in the last clean CI run's
# sanitizer stage, two tests at a time on 2 cores, 1644 s summed over the 742
# tests run): long runs that only repeat numeric work the release stage checks,
# on code that other instrumented tests run too. Together 551 s of the 1644, so
# about 275 s of the stage's wall time.
#   FatigueSuperposition.LeverManipulator... (124 s): the lever twin of
#     FatigueSuperposition.LeverChainManipulator..., which stays (superposed and
#     step-by-step stresses, the fatigue stage, the results file, instrumented);
#     the lever (four-bar) job stays in ManipulatorJob.LeverManipulatorHasThreeLinks.
#   Superposition.LeverChainManipulator... (58 s): the same two load paths as the
#     fatigue one that stays (with the assembly, which runs instrumented in
#     ManipulatorJob.LeverChainRun...); FatigueSuperposition.StepByStepWithSome-
#     FieldsWritten... stays (output.field_every, fields of some steps only).
#   CantileverModes.FirstThree... (90 s): mesh convergence of three frequencies;
#     the eigen solver runs instrumented in FreeFreeModes.*, TipMass.*,
#     CraigBampton.* (all kept).
#   Verify.QuickSuite... (81 s): the verification rows once more (their code
#     runs instrumented in tests/verification); both reports are written
#     instrumented by Verify.WrongReferenceShowsFail... (kept).
#   AmgSolver.Tet10Cantilever... (40 s): a 24 000-DoF AMG-PCG solve; the same AMG
#     code runs instrumented in AmgSolver.Hex20..., .InterpolationWithRotations...,
#     .AutoSwitches... and the MPI test.
#   VibrationOverMotion.WithoutDamping... (34 s), .ASlowMotionIsQuasiStatic...
#     (27 s): the modal march's physics over several strokes and dampings; the
#     stage runs instrumented in VibrationOverMotion.WritesFrequencies...,
#     .TheReducedStaticDeflection..., .BadOptions... (kept).
#   QuadraticElements/CantileverTest.* (23 + 23 s): TET10 and HEX20 convergence
#     on three meshes; both elements run instrumented in most FE tests.
#   Spec4QManipulator.IsokinematicPair... (17 s): two closed curves compared as
#     point sets (kinematics only, no memory handling of its own).
#   LinkLoads.BlockSolveOverAllTimes... (34 s): a block solve against one solve
#     per column, equal to round-off; block solves run instrumented in every
#     manipulator job (the load patterns), LinkLoads.* keeps its other tests.
# Also left out (2026-12-04): the bundled SPEC §4/§6 and slider-crank cases run
# whole (GripperPartsCase.ThroughTheWholeChain..., 16 s in release: eight Gmsh
# parts, the assembly and the vibration; SliderCrankPartsAssembly.*, 5 s: two
# STEP parts through every stage; QManipulatorPartsCase.*, 3 s). Their
# stages run instrumented on smaller models: the slider and transmission
# members in ElasticAssemblySlider.* and ElasticAssemblyTransmission.*, the
# transmission's loads in LinkLoads.*, the gripper's assembly in
# GripperAssembly.* (kept), the stages in VibrationOverMotion.* and the
# fatigue tests.
# Every robustness test, every unit test of parsing, I/O and memory handling,
# and the fuzz targets still run instrumented.
# Keeps CI under its time limit; KINETOFEM_SANITIZER_SKIP="" runs them too.
skip=${KINETOFEM_SANITIZER_SKIP-'^(ManipulatorPresets\.|ManipulatorJob\.FactorAboveTheLimit|NoSourceTree\.CopiedProgramPassesVerifyQuick|ElasticAssemblyCost\.|RigidBoreCost\.|LinkageAssembly\.|KillDuringRun\.ManipulatorKilledWhileWriting|LoadTransferVerification\.AcceleratedLinkBalanced|LinkageParts\.BundledStepCase|postproc\.XdmfParaView\.|Superposition\.(LeverManipulator|FieldsAtEveryKth|FieldTimes|LeverChainManipulator)|Types/NodeGraphOrderingTest\.|AssemblyModes\.|ManipulatorJob\.VibrationKeys|ManipulatorJob\.FactorsThatDoNotFitTogether|FatigueSuperposition\.LeverManipulator|CantileverModes\.FirstThree|Verify\.QuickSuite|AmgSolver\.Tet10Cantilever|VibrationOverMotion\.(WithoutDamping|ASlowMotionIsQuasiStatic)|QuadraticElements/CantileverTest\.|Spec4QManipulator\.IsokinematicPair|LinkLoads\.BlockSolveOverAllTimes|GripperPartsCase\.ThroughTheWholeChain|SliderCrankPartsAssembly\.|QManipulatorPartsCase\.)'}
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
