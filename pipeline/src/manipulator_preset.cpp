#include "kinetofem/pipeline/manipulator_preset.hpp"

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"

namespace kinetofem::pipeline {

std::vector<PartSpec> manipulator_parts(const mech::ManipulatorDefinition& def, ManipulatorLinks links) {
  const bool chain = def.type == mech::ManipulatorType::LeverChain;
  const mech::LeverChainGeometry& g = def.geometry;
  const loads::BoreLoad pin = links.bore_load;
  const double clearance = links.pin_fit.clearance_m;
  const std::string fit = links.pin_fit.fit;
  const std::optional<fem::IsotropicMaterial> pin_material = links.pin_fit.pin_material;
  using namespace mech::manipulator;  // the preset's body, joint and face-set names

  PartSpec lever;
  lever.source = PartSource::Lever;
  lever.lever = links.lever;
  lever.lever.length_m = g.a_m;
  lever.label = "part 'lever' (lever 1)";
  lever.attachments = {kLever, nullptr, {{kJointA0, kBoreA0, pin, clearance, fit, pin_material}, {kJointA, kBoreA, pin, clearance, fit, pin_material}}, {}, {{kLeverDrive, kBoreA0}}};

  PartSpec arm;
  arm.source = chain ? PartSource::ArmWithRoller : PartSource::Coupler;
  arm.arm = chain ? meshes::lever_chain_arm(g.c_m, g.h_m, g.r_m) : meshes::lever_coupler(g.c_m, g.h_m, g.r_m);
  for (auto field : {&meshes::ArmDimensions::arm_depth_m, &meshes::ArmDimensions::arm_thickness_m})
    arm.arm.*field = links.arm.*field;
  arm.arm.bore_diameter_m = links.lever.bore_diameter_m;  // one pin size for every joint
  arm.arm.boss_diameter_m = links.lever.boss_diameter_m;
  arm.arm.boss_length_m = links.lever.boss_length_m;
  arm.label = chain ? "part 'arm' (link 2 with roller)" : "part 'arm' (coupler, link 2)";
  arm.attachments.body = kArm;
  arm.attachments.joints.push_back({kJointA, kBoreA, pin, clearance, fit, pin_material});
  if (chain) arm.attachments.joints.push_back({kChain, kRollerRim, loads::BoreLoad::DistributingCoupling});
  else arm.attachments.joints.push_back({kJointB, kBoreB, pin, clearance, fit, pin_material});
  if (def.gripper_mass_kg > 0) arm.attachments.point_masses.push_back({kGripperMass, kGripperMount});
  if (def.casting_mass_kg > 0) arm.attachments.point_masses.push_back({kCastingMass, kGripperMount});

  std::vector<PartSpec> parts = {lever, arm};
  if (!chain) {
    PartSpec rocker;
    rocker.source = PartSource::Rocker;
    rocker.lever = links.lever;
    rocker.lever.length_m = g.b0_m;
    rocker.label = "part 'rocker' (rocker 3)";
    rocker.attachments = {kRocker, nullptr, {{kJointB0, kBoreA0, pin, clearance, fit, pin_material}, {kJointB, kBoreA, pin, clearance, fit, pin_material}}, {}, {}};
    parts.push_back(rocker);
  }
  for (const auto& p : parts) {
    try {
      if (p.source == PartSource::Lever || p.source == PartSource::Rocker) p.lever.validate();
      else p.arm.validate();
    } catch (const Error& e) {
      fail("{}: {}", p.label, e.what());
    }
  }
  return parts;
}

}  // namespace kinetofem::pipeline
