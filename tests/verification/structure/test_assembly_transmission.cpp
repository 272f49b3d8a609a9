// Constant-ratio transmissions in the elastic assembly (docs/transmissions.md,
// "In the elastic assembly").
//
// A two-link Q-manipulator at rest, links rigid: link1 held by a rigid angle
// drive, link2 turned about J2 by a belt from the ground's pulley (input:
// link1's angle; output: link2's angle relative to link1; s_out = ratio s_in
// + c), a payload at H = link2's tip, gravity. The belt is the only
// compliance, of torsional stiffness k on the output coordinate. By hand
// (statics of link2 about J2, the belt's moment M_b on link2):
//     M_b + M_g = 0,  M_g = e_z . sum (r - r_J2) x m g   (link2's mass and the payload)
// and the belt twists by g = ds_out - ratio ds_in = -M_b / k (ds_in = 0: the
// drive holds link1), so H moves by g e_z x (H - J2).
// 1. M_b equals the multibody model's moment_output_Nm and the hand value
//    (1e-9 of |M_g|: the same statics three ways); H's displacement equals the
//    belt's twist mapped by hand (1e-6: the tolerance; the two are
//    the same linear algebra, measured at round-off), and the unit-load split
//    gives it all to the belt.
// 2. A preloaded belt whose slack span would drop to zero: Error naming the
//    time and the span.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

struct QArm {
  double l1 = 0.2, l2 = 0.2, ratio = -3.0, payload = 2.0;
  double theta1 = 30 * test::kDeg, theta2 = 50 * test::kDeg;  // link1 absolute, link2 relative
};

mech::MultibodyModel q_arm(const QArm& a) {
  mech::MultibodyModel m;
  m.name = "two-link Q-manipulator";
  m.characteristic_length_m = a.l1;
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body link1;
  link1.name = "link1";
  link1.mass_kg = 1.2;
  link1.inertia_kgm2 = 0.004;
  link1.com_body = {0.5 * a.l1, 0.0};
  link1.points["tip"] = {a.l1, 0.0};
  link1.pose = {0.0, 0.0, a.theta1};
  mech::Body link2 = link1;
  link2.name = "link2";
  link2.mass_kg = 0.9;
  link2.com_body = {0.5 * a.l2, 0.0};
  link2.points = {{"tip", {a.l2, 0.0}}};
  link2.point_masses.push_back({"payload", a.payload, {a.l2, 0.0}});
  link2.pose = {a.l1 * std::cos(a.theta1), a.l1 * std::sin(a.theta1), a.theta1 + a.theta2};
  m.bodies = {frame, link1, link2};
  m.joints = {mech::make_revolute("J1", "frame", "origin", "link1", "origin"),
              mech::make_revolute("J2", "link1", "tip", "link2", "origin")};
  mech::MotionDrive d1;
  d1.name = "d1";
  d1.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "link1", "origin", {1, 0}};
  d1.law = std::make_shared<mech::Polynomial345Law>(0.0, 1.0);  // at rest
  m.motion_drives = {d1};
  mech::Transmission belt;
  belt.name = "belt";
  belt.input = {mech::CoordinateType::Angle, "frame", "origin", "link1", "origin", {1, 0}};
  belt.output = {mech::CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  belt.ratio = a.ratio;
  belt.radius_m = 0.03;
  m.transmissions = {belt};
  return m;
}

TEST(ElasticAssemblyTransmission, BeltTwistMovesThePointAsTheHandStaticsSay) {
  const QArm a;
  const mech::MultibodyModel m = q_arm(a);
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(m), {0.0}).frames.front();
  const double k = 850.0;  // N m/rad on the output coordinate
  AssemblyOptions options;
  options.points = {{"H", "link2", "tip", ""}};
  options.transmissions = {{"belt", k, 0.03, 0.0}};
  ElasticAssembly assembly({}, m, options);
  const PoseSolution pose = assembly.solve(frame);

  // Hand statics of link2 about J2.
  const Eigen::Vector2d g(0.0, -9.80665);
  const Eigen::Vector2d J2 = frame.bodies[1].q.head<2>() +
                             Eigen::Rotation2Dd(frame.bodies[1].q.z()) * Eigen::Vector2d(a.l1, 0.0);
  const double th2 = frame.bodies[2].q.z();
  const Eigen::Vector2d e2(std::cos(th2), std::sin(th2));
  auto moment = [&](const Eigen::Vector2d& arm, const Eigen::Vector2d& f) { return arm.x() * f.y() - arm.y() * f.x(); };
  const double M_g = moment(0.5 * a.l2 * e2, 0.9 * g) + moment(a.l2 * e2, a.payload * g);
  const double M_b = -M_g;
  const TransmissionResult& t = pose.transmission("belt");
  std::printf("  belt moment on link2: assembly %.12f N m, multibody %.12f, hand %.12f; twist %.6e rad\n",
              t.moment_output_nm, frame.transmissions[0].moment_output_Nm, M_b, t.twist_rad);
  EXPECT_NEAR(t.moment_output_nm, frame.transmissions[0].moment_output_Nm, 1e-9 * std::abs(M_g));
  EXPECT_NEAR(t.moment_output_nm, M_b, 1e-9 * std::abs(M_g));
  EXPECT_NEAR(t.twist_rad, -M_b / k, 1e-9 * std::abs(M_b / k));
  // H moves by the twist about J2.
  const Eigen::Vector2d r = a.l2 * e2;
  const Eigen::Vector2d expected = (-M_b / k) * Eigen::Vector2d(-r.y(), r.x());
  const PointResult& h = pose.point("H");
  std::printf("  H: (%.9e, %.9e) m, by hand (%.9e, %.9e) m\n", h.displacement_m.x(), h.displacement_m.y(), expected.x(),
              expected.y());
  EXPECT_LT((h.displacement_m.head<2>() - expected).norm(), 1e-6 * expected.norm());
  ASSERT_EQ(h.contributions.size(), 1u);
  EXPECT_EQ(h.contributions[0].name, "transmission.belt");
  EXPECT_LT((h.contributions[0].displacement_m - h.displacement_m).norm(), 1e-9 * expected.norm());
  // Without a preload one span carries the whole pull.
  EXPECT_NEAR(t.span_tension_n[0] + t.span_tension_n[1], std::abs(M_b) / 0.03, 1e-9 * std::abs(M_b) / 0.03);
}

TEST(ElasticAssemblyTransmission, PreloadedBeltWhoseSpanWouldGoSlackIsAnError) {
  const QArm a;
  const mech::MultibodyModel m = q_arm(a);
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(m), {0.0}).frames.front();
  AssemblyOptions options;
  options.transmissions = {{"belt", 850.0, 0.03, 1.0}};  // 1 N of preload against a pull of tens of N
  ElasticAssembly assembly({}, m, options);
  try {
    (void)assembly.solve(frame);
    FAIL() << "a slack span solved";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("at t = 0 s: transmission 'belt': span "), std::string::npos) << message;
    EXPECT_NE(message.find("goes slack"), std::string::npos) << message;
  }
  // Enough preload: both spans carry, their difference is the pull.
  options.transmissions = {{"belt", 850.0, 0.03, 500.0}};
  ElasticAssembly preloaded({}, m, options);
  const PoseSolution pose = preloaded.solve(frame);
  const TransmissionResult& t = pose.transmission("belt");
  EXPECT_NEAR(t.span_tension_n[0] - t.span_tension_n[1], t.moment_output_nm / 0.03, 1e-9 * 500.0);
  EXPECT_NEAR(t.span_tension_n[0] + t.span_tension_n[1], 1000.0, 1e-9 * 500.0);
}

}  // namespace
}  // namespace kinetofem::structure
