#!/usr/bin/env bash
# ParaView shows a spatial mechanism moving where the run put it: the ctest
# postproc.XdmfParaView.SpatialMechanismMoves (label `paraview`) runs this script.
#
#   scripts/test-spatial-paraview.sh KINETOFEM WORK_DIR
#
# Runs the SPEC §5 manipulator, cases/mechanisms/spherical_variant_A/case.toml,
# into WORK_DIR (emptied first) and checks its .xdmf with the three XDMF readers
# (XDMF Reader, Xdmf3ReaderS, Xdmf3ReaderT):
#   scripts/check_xdmf_paraview.py            the readers agree on every block and
#                                              array, no warnings, the four skeleton
#                                              blocks and the mechanism block present;
#   scripts/check_spatial_mechanism_paraview.py  at the first, middle and last output
#                                              time, the arm's tip (its skeleton's node
#                                              farthest along the arm) is where the
#                                              run's frame puts M (body.arm.origin +
#                                              R (L, 0, 0), from the histories) and at
#                                              the closed form's planned M.position,
#                                              1e-12 of the arm length, and it moved.
# With a display (Xvfb through xvfb-run, or $DISPLAY) it also saves
# spatial_t<time>.png at those times (the skeletons coloured by speed) and checks
# that they are not empty.
#
# Exit 0: passed; 1: failed; 77 (ctest: skipped): no pvpython, unless
# KINETOFEM_REQUIRE_PARAVIEW=1 (scripts/test.sh), which makes that a failure.
set -uo pipefail
if (($# != 2)); then
  echo "usage: $0 KINETOFEM WORK_DIR" >&2
  exit 2
fi
kinetofem=$1 work=$2
root=$(cd "$(dirname "$0")/.." && pwd)
pvpython=${PVPYTHON:-$(command -v pvpython || true)}
if [[ -z $pvpython && ${KINETOFEM_REQUIRE_PARAVIEW:-0} == 1 ]]; then
  echo "FAILED: pvpython (ParaView's Python) not found, and KINETOFEM_REQUIRE_PARAVIEW=1"
  exit 1
fi
if [[ -z $pvpython ]]; then
  echo "SKIPPED: pvpython (ParaView's Python) not found; install ParaView (Debian: apt-get install" \
    "paraview python3-paraview xvfb) or set PVPYTHON"
  exit 77
fi
rm -rf "$work"
mkdir -p "$work"
case_file=$root/cases/mechanisms/spherical_variant_A/case.toml
if ! "$kinetofem" run "$case_file" -o "$work/run" > "$work/run.log" 2>&1; then
  cat "$work/run.log"
  echo "FAILED: kinetofem run $case_file"
  exit 1
fi
xdmf=$work/run/spherical_variant_A.xdmf
# ParaView without the sanitizer stage's LD_PRELOAD (scripts/test-sanitizers.sh).
pv=(env -u LD_PRELOAD "$pvpython")
status=0
"${pv[@]}" "$root/scripts/check_xdmf_paraview.py" --pvpython "$pvpython" \
  --require-blocks skeleton.ground,skeleton.column,skeleton.sleeve,skeleton.arm,mechanism "$xdmf" || status=1
spatial=("$root/scripts/check_spatial_mechanism_paraview.py" --pvpython "$pvpython" --body arm
  --expect-history M.position "$xdmf")
if command -v xvfb-run > /dev/null; then
  # 24-bit screen: xvfb-run's default (8 bit) has no usable GLX visual.
  xvfb-run -a -s "-screen 0 1600x1200x24" "${pv[@]}" "${spatial[@]}" --screenshot "$work/spatial" || status=1
elif [[ -n ${DISPLAY:-} ]]; then
  "${pv[@]}" "${spatial[@]}" --screenshot "$work/spatial" || status=1
else
  echo "note: no display (install xvfb): the screenshots are left out"
  "${pv[@]}" "${spatial[@]}" || status=1
fi
if ((status == 0)); then
  echo "PASSED: ParaView shows the spatial mechanism's skeleton at the run's poses"
else
  echo "FAILED: see above"
fi
exit $status
