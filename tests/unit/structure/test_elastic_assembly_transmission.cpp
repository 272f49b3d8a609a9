// The elastic assembly does not model a transmission (a belt or gear train
// between joint angles, mech::Transmission) yet: a linkage with one is an
// Error naming it, before any part is set up, not an assembly silently
// without its belt.
#include <gtest/gtest.h>

#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

TEST(ElasticAssemblyTransmission, ALinkageWithATransmissionIsRefusedNamingIt) {
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
  try {
    ElasticAssembly assembly({}, m);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("transmission 'belt'"), std::string::npos) << what;
    EXPECT_NE(what.find("does not model transmissions yet"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace kinetofem::structure
