#pragma once
// The FE parts of the SPEC §5 spherical manipulator (meshes/spherical_parts.hpp,
// sized by pipeline/spherical_part_sizing.hpp) placed on the bodies of its
// spatial model (mech::spatial::spherical_manipulator_model), with the face
// sets each load enters through, for the per-part stress stage
// (analyse_spatial_part_over_motion, part_stress.hpp).
//
// Frames: every mesh is in its body's frame of the spatial model. The column
// and the sleeve are meshed in those frames already; the arm is meshed with
// its origin at the gripper point M (x forward, the arm in -l1 <= x <= 0) and
// the model's arm frame has its origin at the rear end, so its mesh is moved
// by +l1 along x.
//
// Where the loads enter (docs/spherical_manipulator_parts.md):
//   column  pair_10 and the base drive M10d through "pair_10" (the bearing
//           seat: the base bearing and the motor's torque); pair_21 and the
//           tilt drive M21d (its reaction) through "pair_21" (the fork's bores).
//   sleeve  pair_21 and M21d through its "pair_21" journals; the slide pair_32
//           with its drive F32d on its two guide lands, "pair_32_front" and
//           "pair_32_rear", centred at x = +-(l2/2 - l_g/2) from B
//           (loads::SpatialSlideAttachment).
//   arm     the slide reversed on the stations of its "slide" face (windows
//           one guide land l_g long, spaced l_g/2): where the lands are at each
//           output time; the payload (point mass at M) through "gripper_mount".
// The actuator of F32d is taken to act along the slide between the lands and
// the arm (a rack or a screw in the sleeve): its force enters with the slide's.
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spherical_manipulator.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/meshes/spherical_parts.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/solver/material.hpp"

namespace kinetofem::pipeline {

struct SphericalManipulatorParts {
  meshes::SphericalPartDimensions dimensions;
  std::vector<SpatialPart> parts;  // column, sleeve, arm
  double meshing_seconds = 0.0;
};

// Meshes the three parts of `design` by `rules` (their density: the
// material's) and defines their loads. Throws Error naming the part when its
// dimensions are impossible or Gmsh fails.
SphericalManipulatorParts spherical_manipulator_parts(const mech::SphericalDesign& design,
                                                      meshes::SphericalPartRules rules, const meshes::MeshOptions& mesh,
                                                      const fem::IsotropicMaterial& material, const Log& log);

// The bodies of `model` get their parts' mass properties (mass, centre of
// mass, inertia tensor), so that the loads on each part are in equilibrium.
void apply_spatial_mass_properties(mech::spatial::Model& model, const std::vector<SpatialPart>& parts);

}  // namespace kinetofem::pipeline
