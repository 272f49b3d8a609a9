#!/usr/bin/env bash
# Prints, one a line, the build targets that `ctest -LE large` needs in a
# configured build tree: every top-level target (the libraries, the program,
# the test executables, amg_mpi_check, the sanitizer tree's preload library and
# fuzz targets) except
#   - the benchmarks (bench/*.cpp: programs run by hand, no ctest test runs
#     them; 5 programs, about 25 s of compile in the release tree),
#   - the names given after BUILD_DIR (none today).
# tests/large (label large) is built all the same (one file, ~4 s): a test
# executable that is not built leaves ctest a placeholder test <name>_NOT_BUILT
# without its label, which `ctest -LE large` would run and fail; a test
# executable left out here must be left out of ctest by name too.
# New test folders are included without an edit here.
#   usage: bash scripts/ctest-targets.sh BUILD_DIR [EXCLUDED_TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: ctest-targets.sh BUILD_DIR [EXCLUDED_TARGET...]}
shift
excluded=(all test clean help edit_cache rebuild_cache install "$@")
for source in bench/*.cpp; do
  excluded+=("$(basename "$source" .cpp)")
done
# `--target help` lists the primary targets as "name: phony"; folder-qualified
# names (core/test) and the archives' file names (libkinetofem_core.a) are
# aliases of these.
cmake --build "$build" --target help |
  sed -n 's/^\([A-Za-z0-9_.+-]*\): phony$/\1/p' |
  grep -v -x -F "${excluded[@]/#/-e}" |
  grep -v '^lib.*\.a$' || true
