#pragma once
// The SPEC §1 lever-chain and SPEC §2 lever (four-bar) manipulators as
// presets of the motion-to-stress pipeline: their multibody model
// (mech::make_manipulator_model) and their parametric parts, with the link
// topology (which face set each joint, the chain, the drive and the payload
// act through) written here once.
//
//   lever  (link 1) meshes::mesh_lever: joints A0 (bore_A0), A (bore_A);
//                   the lever drive's torque on bore_A0
//   arm    (link 2) meshes::mesh_arm: joint A (bore_A); the chain on
//                   roller_rim (lever-chain) or joint B on bore_B (lever);
//                   gripper and casting on gripper_mount
//   rocker (link 3, lever manipulator) meshes::mesh_lever of length b0:
//                   joints B0 (bore_A0), B (bore_A)
// The part frames are the body frames of manipulator_models.hpp: no placement.
#include <vector>

#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/loads/iso_fit.hpp"
#include "kinetofem/meshes/arm.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "kinetofem/pipeline/part_model.hpp"

namespace kinetofem::pipeline {

struct ManipulatorLinks {
  meshes::LeverDimensions lever;  // length_m = a (set by the preset)
  meshes::ArmDimensions arm;      // roller / coupler dimensions from c, h, r (set by the preset)
  loads::BoreLoad bore_load = loads::BoreLoad::DistributingCoupling;  // pins (the chain: always the coupling)
  loads::ContactFit pin_fit;  // bore_load = Contact: the pins' clearance (or fit)
};

// Parts of the manipulator `definition` (its geometry gives a, b0, c, h, r;
// the cross-section dimensions come from `links`). Throws Error naming the
// link for impossible dimensions.
std::vector<PartSpec> manipulator_parts(const mech::ManipulatorDefinition& definition, ManipulatorLinks links);

}  // namespace kinetofem::pipeline
