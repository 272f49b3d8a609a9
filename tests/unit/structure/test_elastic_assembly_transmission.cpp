// A transmission in the elastic assembly (a belt or gear train between joint
// angles, mech::Transmission): its options must name it, with valid values
// (the member's statics: tests/verification/structure/test_assembly_transmission.cpp).
#include <gtest/gtest.h>

#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

TEST(ElasticAssemblyTransmission, OptionsNamingNoTransmissionOrBadValuesAreErrors) {
  mech::MultibodyModel m;
  m.name = "belt arm";
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body link1;
  link1.name = "link1";
  link1.mass_kg = 1.0;
  link1.inertia_kgm2 = 0.01;
  link1.points["A"] = {0.2, 0.0};
  mech::Body link2 = link1;
  link2.name = "link2";
  link2.pose = {0.2, 0.0, 0.0};
  m.bodies = {ground, link1, link2};
  m.joints.push_back(mech::make_revolute("O", "ground", "origin", "link1", "origin"));
  m.joints.push_back(mech::make_revolute("A", "link1", "A", "link2", "origin"));
  mech::Transmission belt;
  belt.name = "belt";
  belt.input = {mech::CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  belt.output = {mech::CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  belt.ratio = -4.0;
  belt.radius_m = 0.02;
  m.transmissions.push_back(belt);
  auto error_of = [&](const TransmissionMember& member) {
    AssemblyOptions o;
    o.transmissions = {member};
    try {
      ElasticAssembly assembly({}, m, o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of({"chain", 1.0, 0.0, 0.0}).find("transmission 'chain', which the mechanism 'belt arm' lacks"),
            std::string::npos);
  EXPECT_NE(error_of({"belt", -1.0, 0.0, 0.0}).find("torsional stiffness -1 N m/rad must be >= 0"), std::string::npos);
  EXPECT_NE(error_of({"belt", 1.0, 0.02, -5.0}).find("preload -5 N must be >= 0"), std::string::npos);
  EXPECT_EQ(error_of({"belt", 1.0, 0.02, 5.0}), "");
}

}  // namespace
}  // namespace kinetofem::structure
