// The SPEC §1 lever-chain and SPEC §2 lever manipulators as presets of the
// pipeline (pipeline/manipulator_preset.hpp): which parts, of which size,
// and where each joint, the chain, the drive and the payload act.
#include <gtest/gtest.h>

#include <algorithm>

#include "kinetofem/pipeline/manipulator_preset.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

using test::error_of;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The face set a joint of the part acts through ("" if none).
std::string face_of_joint(const PartSpec& part, const std::string& joint) {
  for (const auto& j : part.attachments.joints)
    if (j.joint == joint) return j.face_set;
  return "";
}

TEST(ManipulatorParts, LeverChainGivesLeverAndArmWithTheChainOnTheRollerRim) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  const std::vector<PartSpec> parts = manipulator_parts(def, {});
  ASSERT_EQ(parts.size(), 2u);
  const PartSpec& lever = parts[0];
  const PartSpec& arm = parts[1];
  EXPECT_EQ(lever.attachments.body, "lever");
  EXPECT_EQ(lever.source, PartSource::Lever);
  EXPECT_EQ(lever.lever.length_m, 0.5);  // a (SPEC §1 example)
  EXPECT_EQ(face_of_joint(lever, "A0"), "bore_A0");
  EXPECT_EQ(face_of_joint(lever, "A"), "bore_A");
  ASSERT_EQ(lever.attachments.drives.size(), 1u);
  EXPECT_EQ(lever.attachments.drives[0].drive, "lever_drive");
  EXPECT_EQ(lever.attachments.drives[0].face_set, "bore_A0");

  EXPECT_EQ(arm.attachments.body, "arm");
  EXPECT_EQ(arm.source, PartSource::ArmWithRoller);
  EXPECT_TRUE(arm.arm.with_roller);
  EXPECT_EQ(arm.arm.length_m, 0.35);          // c
  EXPECT_EQ(arm.arm.gripper_offset_m, 0.1);   // h
  EXPECT_EQ(arm.arm.roller_radius_m, 0.075);  // r
  EXPECT_EQ(face_of_joint(arm, "A"), "bore_A");
  EXPECT_EQ(face_of_joint(arm, "chain"), "roller_rim");
  EXPECT_EQ(face_of_joint(arm, "B"), "");
  ASSERT_EQ(arm.attachments.point_masses.size(), 2u);
  for (const auto& m : arm.attachments.point_masses) EXPECT_EQ(m.face_set, "gripper_mount") << m.point_mass;
  EXPECT_EQ(arm.attachments.point_masses[0].point_mass, "gripper");
  EXPECT_EQ(arm.attachments.point_masses[1].point_mass, "casting");
}

TEST(ManipulatorParts, LeverGivesARockerOfLengthB0) {
  // Reference: SPEC §1 (1), b0 = a c / (c + r) = 500 * 350 / 425 = 411.765 mm
  // (printed to 3 decimals: +-0.0005 mm).
  const std::vector<PartSpec> parts = manipulator_parts(test::lever_chain_definition(mech::ManipulatorType::Lever), {});
  ASSERT_EQ(parts.size(), 3u);
  const PartSpec& rocker = parts[2];
  EXPECT_EQ(rocker.attachments.body, "rocker");
  EXPECT_EQ(rocker.source, PartSource::Rocker);
  EXPECT_NEAR(rocker.lever.length_m * 1e3, verification::spec1::kB0.value, verification::spec1::kB0.tolerance);
  EXPECT_NEAR(rocker.lever.length_m * 1e3, 411.765, 0.0005);
  EXPECT_EQ(face_of_joint(rocker, "B0"), "bore_A0");
  EXPECT_EQ(face_of_joint(rocker, "B"), "bore_A");
  EXPECT_TRUE(rocker.attachments.drives.empty());
  // The arm is the coupler: bore B at x = r, no roller, no chain.
  const PartSpec& arm = parts[1];
  EXPECT_EQ(arm.source, PartSource::Coupler);
  EXPECT_FALSE(arm.arm.with_roller);
  EXPECT_EQ(arm.arm.bore_b_offset_m, 0.075);
  EXPECT_EQ(face_of_joint(arm, "B"), "bore_B");
  EXPECT_EQ(face_of_joint(arm, "chain"), "");
}

TEST(ManipulatorParts, NoPayloadGivesNoPointMasses) {
  mech::ManipulatorDefinition def = test::lever_chain_definition();
  def.gripper_mass_kg = 0.0;
  def.casting_mass_kg = 0.0;
  EXPECT_TRUE(manipulator_parts(def, {})[1].attachments.point_masses.empty());
}

TEST(ManipulatorParts, LinksGiveCrossSectionsPinsAndBoreLoad) {
  ManipulatorLinks links;
  links.lever.width_m = 0.07;
  links.lever.bore_diameter_m = 0.035;
  links.lever.boss_diameter_m = 0.085;
  links.arm.arm_depth_m = 0.07;
  links.arm.arm_thickness_m = 0.02;
  links.bore_load = loads::BoreLoad::BearingPressure;
  const std::vector<PartSpec> parts = manipulator_parts(test::lever_chain_definition(), links);
  EXPECT_EQ(parts[0].lever.width_m, 0.07);
  EXPECT_EQ(parts[0].lever.length_m, 0.5);  // a, whatever links.lever says
  EXPECT_EQ(parts[1].arm.arm_depth_m, 0.07);
  EXPECT_EQ(parts[1].arm.arm_thickness_m, 0.02);
  EXPECT_EQ(parts[1].arm.bore_diameter_m, 0.035);  // one pin size for every joint
  EXPECT_EQ(parts[1].arm.boss_diameter_m, 0.085);
  for (const auto& part : parts)
    for (const auto& j : part.attachments.joints)
      EXPECT_EQ(j.distribution, j.joint == "chain" ? loads::BoreLoad::DistributingCoupling : loads::BoreLoad::BearingPressure)
          << part.label << " " << j.joint;
}

TEST(ManipulatorParts, ImpossibleDimensionsAreAnErrorNamingTheLink) {
  {
    ManipulatorLinks links;
    links.lever.width_m = 0.2;  // wider than the bosses (0.09 m)
    const std::string message = error_of([&] { manipulator_parts(test::lever_chain_definition(), links); });
    EXPECT_TRUE(contains(message, "part 'lever' (lever 1): ")) << message;
  }
  {
    ManipulatorLinks links;
    links.arm.arm_thickness_m = 0.06;  // thicker than the boss length (0.05 m)
    const std::string message = error_of([&] { manipulator_parts(test::lever_chain_definition(), links); });
    EXPECT_TRUE(contains(message, "part 'arm' (link 2 with roller): ")) << message;
  }
  {
    // r = 1.7 m: b0 = 0.5 * 0.35 / 2.05 = 85.4 mm, shorter than the 90 mm
    // bosses at its ends (SPEC §1 (1)).
    mech::ManipulatorDefinition def = test::lever_chain_definition(mech::ManipulatorType::Lever);
    def.geometry = mech::make_lever_chain_geometry(0.5, 0.35, 0.1, 1.7);
    const std::string message = error_of([&] { manipulator_parts(def, {}); });
    EXPECT_TRUE(contains(message, "part 'rocker' (rocker 3): ")) << message;
  }
}

}  // namespace
}  // namespace kinetofem::pipeline
