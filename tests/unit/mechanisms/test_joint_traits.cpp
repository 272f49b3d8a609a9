// Unit tests of the joint table (joint_traits.hpp): every joint type has
// facts, its case-file name finds it back, and the facts agree with the
// constraint rows the multibody system compiles.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "kinetofem/mechanisms/multibody/joint_traits.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"

namespace kinetofem::mech {
namespace {

TEST(JointTraits, EveryTypeHasFactsAndItsNameRoundTrips) {
  std::set<std::string> names;
  for (JointType type : all_joint_types) {
    const JointFacts& f = joint_facts(type);
    ASSERT_NE(f.name, nullptr);
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    const auto back = joint_type_named(f.name);
    ASSERT_TRUE(back.has_value()) << f.name;
    EXPECT_EQ(*back, type);
    EXPECT_GE(f.rows, 1);
    EXPECT_LE(f.rows, int(f.length_row.size()));
    switch (f.assembly_tie) {
      case AssemblyTie::Rigid: EXPECT_TRUE(f.assembly_held == 5 || f.assembly_held == 6) << f.name; break;
      case AssemblyTie::Slide: EXPECT_EQ(f.assembly_held, 5) << f.name; break;
      case AssemblyTie::None:
      case AssemblyTie::ChainSpring: EXPECT_EQ(f.assembly_held, 0) << f.name; break;
    }
    // Only a pin in a bore takes a bearing pressure, and it carries no moment.
    if (f.bearing_pressure) EXPECT_FALSE(f.reaction_moment) << f.name;
  }
  EXPECT_FALSE(joint_type_named("spherical").has_value());
  EXPECT_FALSE(joint_type_named("").has_value());
}

TEST(JointTraits, NamesAndListsForTheCaseFile) {
  EXPECT_EQ(joint_type_names([](const JointFacts&) { return true; }).size(), all_joint_types.size());
  EXPECT_EQ(joint_type_list([](const JointFacts& f) { return f.assembly_tie != AssemblyTie::None; }),
            "revolute, prismatic, fixed and chain");
  EXPECT_EQ(joint_type_list([](const JointFacts& f) { return f.has_roller; }), "chain");
  EXPECT_EQ(joint_type_list([](const JointFacts& f) { return f.reference == JointReference::Angle; }),
            "prismatic and fixed");
}

TEST(JointTraits, CompiledBlocksHaveTheTableRows) {
  // One body hanging on the ground by each joint type in turn.
  for (JointType type : all_joint_types) {
    const JointFacts& f = joint_facts(type);
    SCOPED_TRACE(f.name);
    MultibodyModel m;
    m.name = "one joint";
    Body ground;
    ground.name = "ground";
    ground.fixed = true;
    ground.points["P"] = Eigen::Vector2d(0.0, 0.0);
    Body link;
    link.name = "link";
    link.mass_kg = 1.0;
    link.inertia_kgm2 = 0.01;
    link.pose = Eigen::Vector3d(0.5, 0.0, 0.0);
    link.points["Q"] = Eigen::Vector2d(-0.5, 0.0);
    m.bodies = {ground, link};
    Joint j = make_revolute("J", "ground", "P", "link", "Q");
    j.type = type;
    if (f.has_roller) {
      j.point_j = "origin";
      j.radius_m = 0.1;
      m.bodies[1].pose = Eigen::Vector3d(0.0, 0.5, 0.0);
    }
    m.joints.push_back(j);
    const MultibodySystem system(m);
    ASSERT_EQ(system.blocks().size(), 1u);
    const ConstraintBlock& blk = system.blocks().front();
    EXPECT_EQ(blk.kind, ConstraintKind::Joint);
    EXPECT_EQ(blk.joint, type);
    EXPECT_EQ(blk.rows, f.rows);
    for (int r = 0; r < f.rows; ++r) EXPECT_EQ(blk.length_row[size_t(r)], f.length_row[size_t(r)]) << r;
  }
}

}  // namespace
}  // namespace kinetofem::mech
