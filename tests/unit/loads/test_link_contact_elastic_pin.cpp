// loads::solve_contact_over_motion with an elastic pin
// (JointAttachment::pin_material): a rigid pin is what it was, an elastic
// pin of a very high modulus tends to it, a steel pin widens the contact.
#include <gtest/gtest.h>

#include <cstdio>

#include "kinetofem/loads/link_contact.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace kinetofem::loads {
namespace {

LinkContactHistory history(const std::optional<fem::IsotropicMaterial>& pin) {
  const mech::MultibodyModel model = testing::double_pendulum();
  const mech::MultibodySystem system(model);
  const auto frames = mech::run_kinematics(system, testing::even_times(0.5, 4)).frames;
  const fem::FeModel fe = testing::supported_two_bore_link();
  JointAttachment j2{"J2", "bore_1", BoreLoad::Contact, 20e-6};
  j2.pin_material = pin;
  LinkDefinition link2{"link2", &fe, {j2}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  return solve_contact_over_motion(analysis, loads, frames, log);
}

// Largest pressure difference over the motion, over the rigid pin's peak.
double difference(const LinkContactHistory& a, const LinkContactHistory& b) {
  return (a.pressure_pa - b.pressure_pa).cwiseAbs().maxCoeff() / b.pressure_pa.maxCoeff();
}

TEST(LinkContactElasticPin, AVeryStiffPinTendsToTheRigidPin) {
  // A pin of 1e3 and 1e5 times steel's modulus: its compliance is that much
  // below the bore's, so the pressures differ from the rigid pin's in
  // proportion (reference: the limit E -> infinity is the rigid pin; the
  // difference falls at least 50-fold from 1e3 to 1e5 and is below 1e-4 of
  // the peak at 1e5). A steel pin differs by more (its own compliance is
  // of the bore's order).
  const LinkContactHistory rigid = history(std::nullopt);
  fem::IsotropicMaterial stiff;
  stiff.youngs_modulus_pa *= 1e3;
  const LinkContactHistory e3 = history(stiff);
  stiff.youngs_modulus_pa *= 1e2;
  const LinkContactHistory e5 = history(stiff);
  const LinkContactHistory steel = history(fem::IsotropicMaterial{});
  const double d3 = difference(e3, rigid), d5 = difference(e5, rigid), ds = difference(steel, rigid);
  std::printf("pressure vs the rigid pin: E x 1e3 %.2e, E x 1e5 %.2e, steel %.2e of the peak\n", d3, d5, ds);
  EXPECT_LE(d5, 1e-4);
  EXPECT_LE(d5 * 50, d3);
  EXPECT_GT(ds, 10 * d3);
  EXPECT_LE(e5.worst_resultant_error, 1e-8);
}

TEST(LinkContactElasticPin, ARigidPinIsTheSameEveryRun) {
  // No pin material: the rigid pin's path, deterministic to the bit (the
  // elastic pin adds nothing to it).
  const LinkContactHistory a = history(std::nullopt), b = history(std::nullopt);
  EXPECT_EQ((a.pressure_pa - b.pressure_pa).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace kinetofem::loads
