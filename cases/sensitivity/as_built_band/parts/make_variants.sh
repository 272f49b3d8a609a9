#!/bin/sh
# The part files of the sensitivity band's geometric variants, written by the as-built case's
# own parametric script (../../../lever_chain_manipulator_as_built/parts/make_parts.geo) with one
# dimension changed each; every other part of a variant is the case's own.
#
#   cd cases/sensitivity/as_built_band/parts && sh make_variants.sh
#
# Writes <variant>_<part>.step and removes the parts a variant does not change.
set -e
geo=../../../lever_chain_manipulator_as_built/parts/make_parts.geo
variant() {  # variant NAME KEEP-PART GMSH-OPTIONS...
  name=$1; keep=$2; shift 2
  # an absolute prefix: Gmsh saves relative names beside the .geo file
  gmsh -0 "$geo" -setstring prefix "$(pwd)/${name}_" "$@" > /dev/null
  for part in frame lever arm gripper; do
    [ "$part" = "$keep" ] || rm -f "${name}_${part}.step"
  done
}
variant plate12 lever -setnumber lever_plate_t 12      # lever plate 60 x 12 (case: 16)
variant plate25 lever -setnumber lever_plate_t 25      # lever plate 60 x 25
variant lug20 lever -setnumber lever_hub_A_length 20   # the lever's hub at A 20 long (case: 40)
variant lug30 lever -setnumber lever_hub_A_length 30
variant chain231 frame -setnumber chain_z 231          # anchor stud to z = 231: arm plane +20 mm
variant chain251 frame -setnumber chain_z 251          # arm plane +40 mm

# The lever (four-bar) manipulator's variants (cases/lever_manipulator_as_built).
geo=../../../lever_manipulator_as_built/parts/make_parts.geo
variant4() {  # variant4 NAME KEEP-PART GMSH-OPTIONS...
  name=$1; keep=$2; shift 2
  gmsh -0 "$geo" -setstring prefix "$(pwd)/${name}_" "$@" > /dev/null
  for part in frame lever coupler rocker gripper; do
    [ "$part" = "$keep" ] || rm -f "${name}_${part}.step"
  done
}
variant4 fourbar_plate12 lever -setnumber lever_plate_t 12   # lever plate 60 x 12 (case: 16)
variant4 fourbar_plate25 lever -setnumber lever_plate_t 25
variant4 fourbar_rocker8 rocker -setnumber rocker_plate_t 8  # rocker plate 50 x 8 (case: 12)
variant4 fourbar_rocker20 rocker -setnumber rocker_plate_t 20
