// Pins in frictionless, unilateral contact with their bores over a motion
// (loads::solve_contact_over_motion, the stress stage with contact):
// equilibrium with the joint reactions, no tension and no penetration, the
// contact zone following a turning force, Saint-Venant against the
// distributing coupling, a point-like contact at a very large clearance.
// The pins are rigid (docs/contact.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/link_contact.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace kinetofem::loads {
namespace {

using testing::double_pendulum;
using testing::even_times;
using testing::supported_two_bore_link;
using testing::turning_link;

constexpr double kPi = std::numbers::pi;

std::vector<mech::Frame> frames_of(const mech::MultibodyModel& model, const std::vector<double>& times) {
  const mech::MultibodySystem system(model);
  return mech::run_kinematics(system, times).frames;
}

// Largest angular spacing between neighbouring nodes of a bore (rad).
double node_spacing(const fem::BoreContactSurface& bore) {
  std::vector<double> a(bore.angle_rad().begin(), bore.angle_rad().end());
  std::sort(a.begin(), a.end());
  double widest = a.front() + 2 * kPi - a.back();
  for (size_t k = 1; k < a.size(); ++k) widest = std::max(widest, a[k] - a[k - 1]);
  return widest;
}

double angle_between(double a, double b) { return std::abs(std::remainder(a - b, 2 * kPi)); }

TEST(PinContactVerification, ContactForcesCarryTheJointReactionsAtEveryOutputTime) {
  // Issue-level check 3. link1 of the double pendulum, both pins in contact
  // (J1 line-to-line, J2 with 30 um clearance), 21 output times. Reference:
  // equilibrium, the contact forces' resultant normal to the pin equals the
  // joint reaction (with the out-of-plane moments, none here), 1e-8 of the
  // force; lambda >= 0 exactly; penetration below 1e-12 m (the solver's
  // tolerance is 1e-10 of its gap scale, about 1e-6 m, in the mean gap
  // at a corner).
  const mech::MultibodyModel model = double_pendulum();
  const auto frames = frames_of(model, even_times(0.5, 20));
  const fem::FeModel fe = supported_two_bore_link();
  LinkDefinition link1{"link1", &fe, {{"J1", "bore_1", BoreLoad::Contact, 0.0}, {"J2", "bore_2", BoreLoad::Contact, 30e-6}},
                       {}, {{"D1", "bore_1"}, {"D2", "bore_2"}}};
  const LinkLoads loads(link1, model);
  ASSERT_EQ(loads.contact_bores().size(), 2u);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  const LinkContactHistory h = solve_contact_over_motion(analysis, loads, frames, log);
  ASSERT_EQ(h.pressure_pa.cols(), Eigen::Index(frames.size()));
  EXPECT_GE(h.pressure_pa.minCoeff(), 0.0);
  EXPECT_LE(h.worst_penetration_m, 1e-12);
  double worst = 0.0;
  for (const auto& bore : h.bores)
    for (size_t t = 0; t < frames.size(); ++t) {
      const Eigen::Vector4d& r = bore.carried[t];
      const Eigen::Vector3d expected(r[0], r[1], 0.0);
      ASSERT_GT(expected.norm(), 1.0);
      worst = std::max(worst, (bore.states[t].force_n - expected).norm() / expected.norm());
    }
  std::printf("contact resultant vs joint reaction: worst %.2e; penetration %.2e m; at most %d active-set steps; "
              "%.3f ms per pose for %ld contact corners; %d poses by the interior-point fallback\n",
              worst, h.worst_penetration_m, h.most_active_set_steps, 1e3 * h.solve_seconds / double(frames.size()),
              long(h.contact_corners()), h.interior_point_poses);
  EXPECT_LE(worst, 1e-8);
  EXPECT_LE(h.worst_resultant_error, 1e-8);
}

TEST(PinContactVerification, SuperpositionAndStepByStepGiveTheSameStress) {
  // The contact forces enter the superposition as load patterns (the
  // singular vectors of their history, to 1e-13) and the step-by-step path
  // as nodal forces: the same stress to 1e-8 of the peak.
  const mech::MultibodyModel model = double_pendulum();
  const auto frames = frames_of(model, even_times(0.5, 10));
  const fem::FeModel fe = supported_two_bore_link();
  LinkDefinition link2{"link2", &fe, {{"J2", "bore_1", BoreLoad::Contact, 20e-6}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  LinkStressOptions superposed, stepped;
  superposed.load_path = LoadPath::Superposition;
  stepped.load_path = LoadPath::StepByStep;
  const LinkEnvelope a = analyse_link_over_motion(analysis, loads, frames, log, superposed);
  const LinkEnvelope b = analyse_link_over_motion(analysis, loads, frames, log, stepped);
  ASSERT_TRUE(a.patterns.has_value());
  ASSERT_TRUE(a.contact.has_value());
  const double diff = (a.max_von_mises_pa - b.max_von_mises_pa).cwiseAbs().maxCoeff();
  std::printf("superposition vs step by step with contact: %.2e of the peak %.3f MPa\n", diff / b.peak_von_mises_pa,
              b.peak_von_mises_pa * 1e-6);
  EXPECT_LE(diff, 1e-8 * b.peak_von_mises_pa);
  EXPECT_LE(a.worst_support_reaction, 1e-6);
}

// The von Mises envelope of link2 with J2 as `load` (clearance `clearance_m`).
LinkEnvelope link2_envelope(BoreLoad load, double clearance_m, const std::vector<mech::Frame>& frames,
                            const fem::FeModel& fe) {
  const mech::MultibodyModel model = double_pendulum();
  LinkDefinition link2{"link2", &fe, {{"J2", "bore_1", load, clearance_m}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  return analyse_link_over_motion(analysis, loads, frames, log);
}

TEST(PinContactVerification, AwayFromTheBoreALineToLineRigidPinEqualsTheCoupling) {
  // Issue-level check 6, second half (Saint-Venant's principle): a rigid pin
  // line-to-line and the distributing coupling carry the same resultant, so
  // away from the bore (the middle of the link, more than 2.5 widths from
  // either bore's axis) their stress is the same to 1 % of the largest
  // stress there.
  const mech::MultibodyModel model = double_pendulum();
  const auto frames = frames_of(model, even_times(0.5, 10));
  const fem::FeModel fe = supported_two_bore_link();
  const LinkEnvelope contact = link2_envelope(BoreLoad::Contact, 0.0, frames, fe);
  const LinkEnvelope coupling = link2_envelope(BoreLoad::DistributingCoupling, 0.0, frames, fe);
  double largest = 0.0, difference = 0.0;
  int nodes = 0;
  for (fem::Index i = 0; i < fe.mesh.node_count(); ++i) {
    const double x = fe.mesh.nodes(i, 0);
    if (x < 0.09 || x > 0.15) continue;  // 60 mm wide link, bores at 0 and 0.24 m
    largest = std::max(largest, coupling.max_von_mises_pa[i]);
    difference = std::max(difference, std::abs(contact.max_von_mises_pa[i] - coupling.max_von_mises_pa[i]));
    ++nodes;
  }
  ASSERT_GT(nodes, 20);
  std::printf("middle of the link (%d nodes): contact vs coupling differ by %.3f %% of %.3f MPa; at the bore: "
              "peak %.3f vs %.3f MPa\n",
              nodes, 100 * difference / largest, largest * 1e-6, contact.peak_von_mises_pa * 1e-6,
              coupling.peak_von_mises_pa * 1e-6);
  EXPECT_LE(difference, 0.01 * largest);
}

TEST(PinContactVerification, AVeryLargeClearanceGivesAPointLikeContact) {
  // Issue-level check 6, first half: a rigid pin with 2 mm clearance in a
  // 30 mm bore touches it on a line (Hertz: a half-width of about 0.05 mm
  // at these loads, far below the 10 mm mesh): the contact covers at most
  // one angular corner spacing, centred on the force within one spacing, and
  // its peak pressure is far above the cosine bearing pressure's peak
  // 2 F / (pi R L) (the line-to-line value, Persson), here more than 3 times.
  const mech::MultibodyModel model = double_pendulum();
  const auto frames = frames_of(model, even_times(0.5, 10));
  const fem::FeModel fe = supported_two_bore_link();
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  auto history = [&](double clearance) {
    LinkDefinition link2{"link2", &fe, {{"J2", "bore_1", BoreLoad::Contact, clearance}}, {{"tip", "bore_2"}},
                         {{"D2", "bore_1"}}};
    return solve_contact_over_motion(analysis, LinkLoads(link2, model), frames, log);
  };
  const LinkContactHistory loose = history(2e-3), tight = history(0.0);
  const auto& bore = loose.bores.front();
  const double spacing = node_spacing(bore.surface);
  for (size_t t = 0; t < frames.size(); ++t) {
    const auto& s = bore.states[t];
    const double force_angle = std::atan2(bore.carried[t][1], bore.carried[t][0]);
    EXPECT_LE(s.arc_rad, spacing + 1e-12) << "t = " << frames[t].t;
    if (s.arc_rad > spacing)
      for (Eigen::Index c = 0; c < bore.surface.size(); ++c)
        if (bore.pressure_pa(c, Eigen::Index(t)) > 0)
          std::printf("corner %ld at %.1f deg: %.4e Pa\n", long(c), bore.surface.angle_rad()[c] * 180 / kPi,
                      bore.pressure_pa(c, Eigen::Index(t)));
    EXPECT_LE(angle_between(s.peak_angle_rad, force_angle), spacing) << "t = " << frames[t].t;
    const double cosine_peak = 2 * Eigen::Vector2d(bore.carried[t].head<2>()).norm() /
                               (kPi * bore.surface.radius_m() * bore.surface.length_m());
    EXPECT_GT(s.peak_pressure_pa, 3.0 * cosine_peak) << "t = " << frames[t].t;
  }
  std::printf("2 mm clearance: arc at most %.1f deg (node spacing %.1f deg); line-to-line arc %.1f deg\n",
              [&] {
                double a = 0;
                for (const auto& s : bore.states) a = std::max(a, s.arc_rad);
                return a * 180 / kPi;
              }(),
              spacing * 180 / kPi, tight.bores.front().states.back().arc_rad * 180 / kPi);
}

TEST(PinContactVerification, TheContactZoneFollowsAForceTurningAboutThePin) {
  // Issue-level check 4. A link turned slowly through a full turn about its
  // pin (testing::turning_link): in its frame the pin's force turns once
  // about the bore. At every pose the contact lies on the side the force
  // pushes (every node in contact within 90 degrees and one node spacing of
  // the force's direction) and the peak pressure within 30 degrees of it;
  // the force's directions cover the whole turn.
  const mech::MultibodyModel model = turning_link();
  const auto frames = frames_of(model, even_times(20.0, 72));
  const fem::FeModel fe = supported_two_bore_link();
  LinkDefinition link{"link", &fe, {{"J1", "bore_1", BoreLoad::Contact, 20e-6}}, {{"mass", "bore_2"}}, {{"D1", "bore_1"}}};
  const LinkLoads loads(link, model);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  const LinkContactHistory h = solve_contact_over_motion(analysis, loads, frames, log);
  const auto& bore = h.bores.front();
  const double spacing = node_spacing(bore.surface);
  std::vector<double> directions;
  for (size_t t = 0; t < frames.size(); ++t) {
    const double force_angle = std::atan2(bore.carried[t][1], bore.carried[t][0]);
    directions.push_back(force_angle);
    const Eigen::VectorXd pressure = h.pressure_pa.col(Eigen::Index(t));
    for (Eigen::Index i = 0; i < bore.surface.size(); ++i) {
      if (pressure[i] > 0) {
        EXPECT_LE(angle_between(bore.surface.angle_rad()[i], force_angle), kPi / 2 + spacing) << "t = " << frames[t].t;
      }
    }
    EXPECT_LE(angle_between(bore.states[t].peak_angle_rad, force_angle), kPi / 6) << "t = " << frames[t].t;
  }
  std::sort(directions.begin(), directions.end());
  double widest = directions.front() + 2 * kPi - directions.back();
  for (size_t k = 1; k < directions.size(); ++k) widest = std::max(widest, directions[k] - directions[k - 1]);
  EXPECT_LT(widest, 15 * kPi / 180);
}

TEST(PinContact, ContactNeedsARevolutePinAndNoInterference) {
  const mech::MultibodyModel model = double_pendulum();
  const fem::FeModel fe = supported_two_bore_link();
  LinkDefinition negative{"link2", &fe, {{"J2", "bore_1", BoreLoad::Contact, -1e-5}}, {{"tip", "bore_2"}}};
  EXPECT_THROW(LinkLoads(negative, model), Error);
  LinkDefinition mixed{"link1", &fe,
                       {{"J1", "bore_1", BoreLoad::Contact, 0.0}, {"J2", "bore_2", BoreLoad::BearingPressure, 0.0}}};
  EXPECT_THROW(LinkLoads(mixed, model), Error);
}

TEST(PinContact, AContactNodeHeldByTheSupportIsAnError) {
  const mech::MultibodyModel model = double_pendulum();
  fem::FeModel fe = testing::two_bore_link_model();
  const std::vector<fem::Index> bore = fem::nodes_of_faces(fe.mesh.face_set("bore_1"));
  std::vector<fem::Index> all(size_t(fe.mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
  fe.supports = fem::three_two_one_support(fe.mesh, all);
  fe.supports.front().nodes = {bore.front()};
  LinkDefinition link2{"link2", &fe, {{"J2", "bore_1", BoreLoad::Contact, 0.0}}, {{"tip", "bore_2"}}};
  const LinkLoads loads(link2, model);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  EXPECT_THROW(solve_contact_over_motion(analysis, loads, frames_of(model, {0.0, 0.1}), log), Error);
}

}  // namespace
}  // namespace kinetofem::loads
