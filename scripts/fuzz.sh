#!/usr/bin/env bash
# Builds the libFuzzer targets in the instrumented tree shared with the
# sanitizer stage (scripts/configure-instrumented.sh, build-asan/: clang,
# ASan + UBSan, coverage) and runs each for N seconds (default 60) on a copy of
# its seed corpus fuzz/corpus/<target>/; new inputs go to
# $BUILD_DIR/corpus/<target>/, crashes to $BUILD_DIR/crashes/<target>/
# (crash-<sha1>: rerun one with $BUILD_DIR/fuzz/fuzz_<target> FILE). Exit
# status non-zero if any target crashed.
#   usage: bash scripts/fuzz.sh [SECONDS] [TARGET...]   (targets: case_file read_msh)
#   FUZZ_RUNS=N   stop each target after N inputs instead (with FUZZ_SEED, default
#                 1, the run is then the same on every machine: what CI uses, so
#                 that a CI run cannot fail on a finding another run would miss)
#   KINETOFEM_JOBS   parallel build jobs (default: nproc); BUILD_DIR (default: build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
targets=("$@")
((${#targets[@]})) || targets=(case_file read_msh)
build=${BUILD_DIR:-build-asan}
BUILD_DIR=$build bash scripts/configure-instrumented.sh "${targets[@]/#/fuzz_}"
# allocator_may_return_null: a huge allocation (Gmsh trusting a count in a header)
# returns null from malloc, and the targets' operator new (fuzz/throwing_new.cpp)
# throws std::bad_alloc as in a normal build, which read_msh reports as an Error.
export ASAN_OPTIONS="detect_leaks=0:abort_on_error=1:allocator_may_return_null=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
status=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  crashes="$build/crashes/$target"
  mkdir -p "$corpus" "$crashes"
  cp -n fuzz/corpus/"$target"/* "$corpus"/ 2> /dev/null || true
  if [[ -n ${FUZZ_RUNS:-} ]]; then
    limit=(-runs="$FUZZ_RUNS" -seed="${FUZZ_SEED:-1}")
    echo "fuzz.sh: $target for $FUZZ_RUNS inputs (seed ${FUZZ_SEED:-1})"
  else
    limit=(-max_total_time="$seconds")
    echo "fuzz.sh: $target for $seconds s"
  fi
  "$build/fuzz/fuzz_$target" "${limit[@]}" -max_len=65536 -timeout=20 -rss_limit_mb=4096 \
    -artifact_prefix="$crashes/" -print_final_stats=1 "$corpus" 2>&1 | grep -v "^#[0-9]*.*\(NEW\|REDUCE\|pulse\)" || status=1
  if compgen -G "$crashes/*" > /dev/null; then
    echo "fuzz.sh: $target: findings in $crashes"; status=1
  fi
done
exit $status
