#!/usr/bin/env bash
# Configures and builds the instrumented tree that the sanitizer and fuzz
# stages of scripts/test.sh share (one build for both):
#   clang, -O1 -gline-tables-only, linked by lld, AddressSanitizer + UndefinedBehaviorSanitizer
#   on every target (KINETOFEM_SANITIZE), the fuzz targets of fuzz/
#   (KINETOFEM_BUILD_FUZZ) with libFuzzer's coverage in the code their inputs
#   reach, tests on, benchmarks off.
# -O1 and line tables only: the sanitizers' recommended optimisation, and half
# the compile time of -O2 -g for the same stack traces. lld: the instrumented
# test programs link several times faster than with GNU ld.
# Coverage (-fsanitize=fuzzer-no-link, on every file through KINETOFEM_BUILD_FUZZ)
# only where the fuzz targets' inputs go: app/ (the case file: fuzz_case_file),
# meshes/ (read_msh: fuzz_read_msh), core/ and fuzz/ (a generated allowlist,
# -fsanitize-coverage-allowlist). The sanitizer stage's tests do not use it, and
# the solver, structure, vibration, ... code that no fuzz input reaches gave
# libFuzzer nothing to steer by. Measured on one file each (clang 14, user CPU):
# structure/src/rigid_bore.cpp 45.3 s with coverage, 37.2 s without (what the
# allowlist leaves out of it); tests/unit/postproc/test_post_vibration.cpp
# 23.5 s, 18.4 s. Over the tree (the last clean CI build's .ninja_log: 2 632
# CPU-s, of which ~2 200 outside app/, core/, meshes/, fuzz/) about 400 CPU-s,
# ~200 s of the stage's wall time on 2 cores. ASan and UBSan stay on every file.
# UBSan without three of its pointer checks (KINETOFEM_UBSAN_SKIP,
# cmake/KinetofemSanitize.cmake): alignment (a misaligned load or store; x86-64
# does it, and our data are doubles and integers in Eigen and std containers),
# object-size (an access beyond the object's known size: ASan reports every
# such access itself, with the allocation's stack) and pointer-overflow
# (pointer arithmetic that wraps: ASan reports the access through the pointer).
# Together they instrument every pointer and reference use of Eigen's templates:
# rigid_bore.cpp 38.2 s -> 27.8 s, tests/verification/structure/
# test_assembly_monolithic.cpp 35.8 s -> ~24 s (-30 %; user CPU, coverage off in
# both). null (a null reference or member call that does not crash at once),
# vptr, function and every arithmetic, bounds, enum, bool, return and
# unreachable check stay.
# Both changes together, old flags -> new, user CPU of one compile (clang 14,
# the 2-core machine under load): app/src/linkage_job.cpp 21.3 -> 16.4 s,
# solver/src/assembly.cpp 34.3 -> 25.9, mechanisms/src/multibody/dynamics.cpp
# 27.0 -> 19.2, tests/unit/structure/test_rigid_bore.cpp 50.6 -> 33.8,
# test_post_vibration.cpp 23.5 -> 18.4: 22-39 % less, ~28 % on average, so
# the tree's 2 632 CPU-s (1311 s of wall time) -> ~1 900 (~940 s); and less
# run time (coverage counters and the left-out checks ran at every access).
# Not used: unity builds (-DCMAKE_UNITY_BUILD=ON would need no CMake edit, but
# the sources are not unity-safe: tried 2026-12-03, meshes/src has two
# anonymous-namespace fnv1a() whose call becomes ambiguous, and every new file
# would have to stay safe); precompiled headers (target_precompile_headers in
# the modules' CMake files; not tried).
#   usage: bash scripts/configure-instrumented.sh [TARGET... | --ctest]
#     (default: all; --ctest: what `ctest -LE large` runs, scripts/ctest-targets.sh;
#     the same here, as the benchmarks are off in this tree)
#   BUILD_DIR (default build-asan), KINETOFEM_JOBS (default nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build-asan}
command -v clang++ > /dev/null || { echo "configure-instrumented.sh: needs clang++ (bash scripts/setup-deps.sh installs it)"; exit 2; }
command -v ld.lld > /dev/null || { echo "configure-instrumented.sh: needs ld.lld (bash scripts/setup-deps.sh installs it)"; exit 2; }
root=$(pwd)
mkdir -p "$build"
build_abs=$(cd "$build" && pwd)
# Source paths as CMake gives them to clang (absolute); generated sources of
# app/ (embedded case texts) and core/ live in the build tree.
allowlist=$build_abs/coverage-allowlist.txt
printf '%s\n' "src:$root/app/*" "src:$root/core/*" "src:$root/meshes/*" "src:$root/fuzz/*" \
  "src:$build_abs/app/*" "src:$build_abs/core/*" "src:$build_abs/meshes/*" "fun:*" > "$allowlist"
flags="-O1 -gline-tables-only -DNDEBUG -fsanitize-coverage-allowlist=$allowlist"
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="$flags" -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$flags" \
  -DCMAKE_EXE_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_SHARED_LINKER_FLAGS=-fuse-ld=lld -DCMAKE_MODULE_LINKER_FLAGS=-fuse-ld=lld \
  -DKINETOFEM_UBSAN_SKIP=alignment,object-size,pointer-overflow \
  -DKINETOFEM_SANITIZE=ON -DKINETOFEM_BUILD_FUZZ=ON -DKINETOFEM_BUILD_TESTS=ON -DKINETOFEM_BUILD_BENCH=OFF > /dev/null
targets=("$@")
if [[ ${1:-} == --ctest ]]; then
  mapfile -t targets < <(bash scripts/ctest-targets.sh "$build")
fi
target_args=()
((${#targets[@]})) && target_args=(--target "${targets[@]}")
cmake --build "$build" -j "${KINETOFEM_JOBS:-$(nproc)}" "${target_args[@]}"
