#pragma once
// The SPEC §5 sizes of a sized spherical manipulator (mech::SphericalDesign,
// spherical_manipulator.hpp) as the input of its FE parts
// (meshes::spherical_part_dimensions, spherical_parts.hpp). It lives here
// because meshes/ does not depend on mechanisms/; the pipeline, which puts
// the multibody loads on the parts, depends on both.
//
//   arm_length_m      = design.arm_length_m       (l1)
//   sleeve_length_m   = design.sleeve_length_m    (l2)
//   sleeve_diameter_m = design.sleeve_diameter_m  (d2)
//   base_diameter_m   = design.base_diameter_m    (d0: the column's floor flange)
//   heights, tilt, reach and the masses m1/m2/m3 from design.variant.
#include "kinetofem/mechanisms/spherical_manipulator.hpp"
#include "kinetofem/meshes/spherical_parts.hpp"

namespace kinetofem::pipeline {

inline meshes::SphericalPartSizing spherical_part_sizing(const mech::SphericalDesign& design) {
  const mech::SphericalVariant& v = design.variant;
  meshes::SphericalPartSizing s;
  s.arm_length_m = design.arm_length_m;
  s.sleeve_length_m = design.sleeve_length_m;
  s.sleeve_diameter_m = design.sleeve_diameter_m;
  s.base_diameter_m = design.base_diameter_m;
  s.height_a_m = v.height_a_m;
  s.height_b_m = v.height_b_m;
  s.tilt_max_rad = v.tilt_max_rad;
  s.reach_min_m = v.r_min_m;
  s.reach_max_m = v.r_max_m;
  s.column_mass_kg = v.m1_kg;
  s.sleeve_mass_kg = v.m2_kg;
  s.arm_mass_kg = v.m3_kg;
  return s;
}

}  // namespace kinetofem::pipeline
