#!/usr/bin/env bash
# ParaView's three XDMF readers (XDMF Reader, Xdmf3ReaderS, Xdmf3ReaderT) read the
# .xdmf files that kinetofem writes alike: the ctest
# postproc.XdmfParaView.ThreeReadersAgree (label `paraview`) runs this script.
#
#   scripts/test-xdmf-paraview.sh UNIT_POSTPROC KINETOFEM WORK_DIR
#
# Writes into WORK_DIR (emptied first)
#   sample/      the synthetic file of the unit test XdmfParaViewSample (three
#                bodies: TET10 with a series, HEX20+TET4 Mixed with a series, a
#                static HEX20; mechanism histories) and its expectations, and an
#                empty results file;
#   slider_crank/, lever_static/   two small runs of `kinetofem run` (histories
#                only; fe_static);
#   default/     the default case, cases/lever_chain_manipulator/case.toml, as
#                scripts/main.sh runs it (its mesh, every stage: the per-link
#                blocks with their fatigue fields, the assembly, the vibration's
#                static and lowest mode shapes, the mechanism block) but with 5
#                output times instead of 101 (about 1 min of the program with one
#                thread; the blocks and arrays do not depend on the count);
# and checks each with scripts/check_xdmf_paraview.py at the first, middle and
# last time step: point and cell counts, arrays and values agree across the
# readers (and with the expectations), and no reader prints a warning. For the
# default case every reader must also show each of its nine blocks, the run's
# own peak von Mises (von_mises_max) and fatigue utilizations, no assembly
# displacement above the run's total deformation, and non-zero mode shapes
# (.summary.toml of the run: --summary). With a display (Xvfb through
# xvfb-run, or $DISPLAY) it also saves default_von_mises.png, von_mises on the
# deformed bodies at the last time step, and checks that it is not empty.
#
# Exit 0: passed; 1: failed; 77 (ctest: skipped): no pvpython. PVPYTHON picks
# another pvpython. scripts/test.sh installs ParaView (scripts/setup-test-deps.sh:
# Debian paraview, python3-paraview, xvfb), so CI runs this test, and sets
# KINETOFEM_REQUIRE_PARAVIEW=1, which turns a missing pvpython from a skip into
# a failure there.
set -uo pipefail
if (($# != 3)); then
  echo "usage: $0 UNIT_POSTPROC KINETOFEM WORK_DIR" >&2
  exit 2
fi
unit=$1 kinetofem=$2 work=$3
root=$(cd "$(dirname "$0")/.." && pwd)
pvpython=${PVPYTHON:-$(command -v pvpython || true)}
if [[ -z $pvpython && ${KINETOFEM_REQUIRE_PARAVIEW:-0} == 1 ]]; then
  echo "FAILED: pvpython (ParaView's Python) not found, and KINETOFEM_REQUIRE_PARAVIEW=1 (scripts/test.sh," \
    "after scripts/setup-test-deps.sh installed it)"
  exit 1
fi
if [[ -z $pvpython ]]; then
  echo "SKIPPED: pvpython (ParaView's Python) not found; install ParaView (Debian: apt-get install" \
    "paraview python3-paraview xvfb) or set PVPYTHON"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"

if ! KINETOFEM_XDMF_SAMPLE_DIR="$work/sample" "$unit" --gtest_filter='XdmfParaViewSample.*' \
  > "$work/sample.log" 2>&1; then
  cat "$work/sample.log"
  echo "FAILED: writing the sample file ($unit)"
  exit 1
fi

run_case() {
  local name=$1
  shift
  if ! "$kinetofem" run "$@" -o "$work/$name" > "$work/$name.log" 2>&1; then
    cat "$work/$name.log"
    echo "FAILED: kinetofem run $*"
    exit 1
  fi
}
run_case slider_crank "$root/cases/mechanisms/slider_crank/case.toml"
run_case lever_static "$root/cases/lever_static/case.toml" --set mesh.element_size_mm=20
run_case default "$root/cases/lever_chain_manipulator/case.toml" --set motion.output_times=5

# ParaView without the sanitizer stage's LD_PRELOAD (scripts/test-sanitizers.sh): only
# kinetofem's own programs above are meant to run under it.
check=(env -u LD_PRELOAD "$pvpython" "$root/scripts/check_xdmf_paraview.py" --pvpython "$pvpython")
status=0
"${check[@]}" --expect "$work/sample/paraview_sample.expect.json" \
  "$work/sample/paraview_sample.xdmf" || status=1
"${check[@]}" "$work/sample/paraview_empty.xdmf" "$work/slider_crank/slider_crank.xdmf" \
  "$work/lever_static/lever_static.xdmf" || status=1
default_blocks=lever,arm,assembly.lever,assembly.arm,vibration.static.lever,vibration.static.arm
default_blocks+=,vibration.lowest.lever,vibration.lowest.arm,mechanism
manipulator=(--times 5 --require-blocks "$default_blocks"
  --summary "$work/default/lever_chain_manipulator.summary.toml" "$work/default/lever_chain_manipulator.xdmf")
shot=(--screenshot "$work/default_von_mises.png" --field von_mises)
if command -v xvfb-run > /dev/null; then
  # 24-bit screen: xvfb-run's default (8 bit) has no usable GLX visual.
  xvfb-run -a -s "-screen 0 1600x1200x24" "${check[@]}" "${shot[@]}" "${manipulator[@]}" || status=1
elif [[ -n ${DISPLAY:-} ]]; then
  "${check[@]}" "${shot[@]}" "${manipulator[@]}" || status=1
else
  echo "note: no display (install xvfb): the screenshot is left out"
  "${check[@]}" "${manipulator[@]}" || status=1
fi
if ((status == 0)); then
  echo "PASSED: the three XDMF readers agree on every file, no warnings"
else
  echo "FAILED: see above"
fi
exit $status
