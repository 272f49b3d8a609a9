// Constraint equations of the planar multibody core (system.hpp): the Jacobian
// Phi_q, the velocity right-hand side nu and the acceleration right-hand side
// gamma of every joint type, drive and transmission checked against finite
// differences of Phi itself; point masses (parallel axis); assembly failure and
// singular positions; the checks of a transmission's data.
#include <functional>
#include <limits>
#include <memory>
#include <string>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"

namespace kinetofem::mech {
namespace {

using Eigen::VectorXd;

Body make_body(const std::string& name, double mass, double inertia, Eigen::Vector2d com, Eigen::Vector3d pose) {
  Body b;
  b.name = name;
  b.mass_kg = mass;
  b.inertia_kgm2 = inertia;
  b.com_body = com;
  b.pose = pose;
  return b;
}

// A model that exercises every constraint type; it need not be assemblable,
// the derivatives are checked at arbitrary q.
MultibodyModel all_joint_types() {
  MultibodyModel m;
  m.name = "all joints";
  Body ground = make_body("ground", 0, 0, {0, 0}, {0.1, -0.2, 0.3});
  ground.fixed = true;
  ground.points["P"] = {0.4, 0.2};
  Body b1 = make_body("b1", 2.0, 0.3, {0.1, 0.05}, {0.5, 0.1, 0.2});
  b1.points["P"] = {0.3, -0.1};
  b1.points["Q"] = {-0.2, 0.25};
  b1.point_masses.push_back({"gripper", 0.7, {0.5, 0.1}});
  Body b2 = make_body("b2", 1.0, 0.1, {0.0, 0.0}, {1.1, 0.4, -0.5});
  b2.points["P"] = {0.2, 0.1};
  b2.points["R"] = {-0.1, 0.3};
  Body b3 = make_body("b3", 1.5, 0.2, {0.2, 0.0}, {0.3, 1.2, 1.0});
  b3.points["P"] = {0.1, -0.3};
  m.bodies = {ground, b1, b2, b3};
  auto joint = [](std::string name, JointType type, std::string bi, std::string pi, std::string bj, std::string pj) {
    Joint j;
    j.name = std::move(name);
    j.type = type;
    j.body_i = std::move(bi);
    j.point_i = std::move(pi);
    j.body_j = std::move(bj);
    j.point_j = std::move(pj);
    return j;
  };
  m.joints.push_back(joint("rev", JointType::Revolute, "ground", "P", "b1", "P"));
  Joint pri = joint("pri", JointType::Prismatic, "b1", "Q", "b2", "P");
  pri.axis_i = {0.6, 0.8};
  m.joints.push_back(pri);
  m.joints.push_back(joint("fix", JointType::Fixed, "b2", "R", "b3", "P"));
  Joint ccw = joint("chain_ccw", JointType::Chain, "ground", "P", "b3", "origin");
  ccw.radius_m = 0.12;
  m.joints.push_back(ccw);
  Joint cw = joint("chain_cw", JointType::Chain, "b1", "Q", "b2", "R");
  cw.radius_m = 0.08;
  cw.wrap_ccw = false;
  m.joints.push_back(cw);
  MotionDrive angle;
  angle.name = "angle drive";
  angle.coordinate = {CoordinateType::Angle, "b1", "origin", "b3", "origin", {1, 0}};
  angle.law = std::make_shared<CycloidalLaw>(0.8, 2.0);
  m.motion_drives.push_back(angle);
  MotionDrive disp;
  disp.name = "displacement drive";
  disp.coordinate = {CoordinateType::Displacement, "b2", "R", "b1", "P", {0.3, -1.0}};
  disp.law = std::make_shared<Polynomial345Law>(0.3, 1.5);
  m.motion_drives.push_back(disp);
  // A belt over three bodies (b1 carries it from the ground's pulley to b2's)
  // and a gear train between two coordinates of four different bodies.
  Transmission belt;
  belt.name = "belt";
  belt.input = {CoordinateType::Angle, "ground", "origin", "b1", "origin", {1, 0}};
  belt.output = {CoordinateType::Angle, "b1", "origin", "b2", "origin", {1, 0}};
  belt.ratio = -4.0;
  belt.radius_m = 0.05;
  m.transmissions.push_back(belt);
  Transmission gears;
  gears.name = "gears";
  gears.kind = TransmissionKind::Gear;
  gears.input = {CoordinateType::Angle, "b2", "origin", "b3", "origin", {1, 0}};
  gears.output = {CoordinateType::Angle, "ground", "origin", "b1", "origin", {1, 0}};
  gears.ratio = 0.35;
  gears.reference = 0.2;
  gears.radius_m = 0.04;
  m.transmissions.push_back(gears);
  return m;
}

struct Trajectory {
  VectorXd q0, v, a;
  VectorXd at(double t) const { return q0 + v * t + 0.5 * a * t * t; }
};

Trajectory some_trajectory(const MultibodySystem& sys) {
  const int n = sys.n_coordinates();
  Trajectory tr;
  tr.q0 = sys.initial_coordinates() + 0.05 * VectorXd::LinSpaced(n, -1.0, 1.0);
  tr.v = VectorXd::LinSpaced(n, 0.7, -1.3);
  tr.a = VectorXd::LinSpaced(n, -2.0, 1.5);
  return tr;
}

TEST(MultibodyConstraints, JacobianMatchesFiniteDifferences) {
  const MultibodySystem sys(all_joint_types());
  ASSERT_EQ(sys.n_constraints(), 2 + 2 + 3 + 1 + 1 + 1 + 1 + 1 + 1);
  const VectorXd q = some_trajectory(sys).q0;
  const double t = 0.37, h = 1e-7;
  const Eigen::MatrixXd jac = sys.jacobian(q, t);
  for (int c = 0; c < sys.n_coordinates(); ++c) {
    VectorXd qp = q, qm = q;
    qp(c) += h;
    qm(c) -= h;
    const VectorXd fd = (sys.phi(qp, t) - sys.phi(qm, t)) / (2 * h);
    // Reference: central difference, truncation ~h^2 |Phi'''| ~ 1e-14, round-off ~1e-9.
    EXPECT_LT((fd - jac.col(c)).cwiseAbs().maxCoeff(), 1e-7) << "column " << c;
  }
}

TEST(MultibodyConstraints, VelocityAndAccelerationRightHandSides) {
  const MultibodySystem sys(all_joint_types());
  const Trajectory tr = some_trajectory(sys);
  const double t0 = 0.61, h = 1e-4;
  auto phi_t = [&](double dt) { return sys.phi(tr.at(dt), t0 + dt); };
  const VectorXd q = tr.at(0.0), qd = tr.v, qdd = tr.a;
  const Eigen::MatrixXd jac = sys.jacobian(q, t0);
  // Reference: dPhi/dt = Phi_q q' - nu and d2Phi/dt2 = Phi_q q'' - gamma along the
  // trajectory (definitions of nu and gamma); central differences with h = 1e-4:
  // truncation ~h^2 ~ 1e-8, round-off ~1e-16/h^2 ~ 1e-8.
  const VectorXd d1 = (phi_t(h) - phi_t(-h)) / (2 * h);
  const VectorXd d2 = (phi_t(h) - 2 * phi_t(0) + phi_t(-h)) / (h * h);
  EXPECT_LT((d1 - (jac * qd - sys.nu(q, t0))).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((d2 - (jac * qdd - sys.gamma(q, qd, t0))).cwiseAbs().maxCoeff(), 1e-6);
}

TEST(MultibodyConstraints, PointMassesUseTheParallelAxisRule) {
  Body b;
  b.name = "arm";
  b.mass_kg = 2.0;
  b.inertia_kgm2 = 0.5;
  b.com_body = {0.1, 0.0};
  b.point_masses.push_back({"casting", 1.0, {0.4, 0.3}});
  MultibodyModel m;
  m.bodies = {b};
  const MultibodySystem sys(m);
  // Hand calculation: m = 3, c = (2*(0.1, 0) + (0.4, 0.3))/3 = (0.2, 0.1),
  // J = 0.5 + 2*(0.1^2 + 0.1^2) + 1*(0.2^2 + 0.2^2) = 0.62.
  EXPECT_DOUBLE_EQ(sys.effective(0).mass_kg, 3.0);
  EXPECT_NEAR(sys.effective(0).com_body.x(), 0.2, 1e-15);
  EXPECT_NEAR(sys.effective(0).com_body.y(), 0.1, 1e-15);
  EXPECT_NEAR(sys.effective(0).inertia_kgm2, 0.62, 1e-15);
}

// Two unit links pinned end to end between ground points (0, 0) and (L, 0).
MultibodyModel two_link_bridge(double span) {
  MultibodyModel m;
  m.name = "bridge";
  Body ground = make_body("ground", 0, 0, {0, 0}, {0, 0, 0});
  ground.fixed = true;
  ground.points["end"] = {span, 0.0};
  Body l1 = make_body("l1", 1, 0.1, {0.5, 0}, {0, 0, 0});
  l1.points["tip"] = {1.0, 0.0};
  Body l2 = make_body("l2", 1, 0.1, {0.5, 0}, {1.0, 0, 0});
  l2.points["tip"] = {1.0, 0.0};
  m.bodies = {ground, l1, l2};
  m.joints.push_back(make_revolute("O", "ground", "origin", "l1", "origin"));
  m.joints.push_back(make_revolute("A", "l1", "tip", "l2", "origin"));
  m.joints.push_back(make_revolute("B", "l2", "tip", "ground", "end"));
  return m;
}

TEST(MultibodyConstraints, AssemblyFailureNamesTimeAndResidual) {
  const MultibodySystem sys(two_link_bridge(2.5));  // links too short for the span
  try {
    assemble(sys, sys.initial_coordinates(), 0.25);
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot be assembled at t = 0.25"), std::string::npos) << what;
    EXPECT_NE(what.find("residual"), std::string::npos) << what;
  }
}

TEST(MultibodyConstraints, StretchedLinkageIsASingularPosition) {
  const MultibodySystem sys(two_link_bridge(2.0));  // exactly stretched: rank loss
  const VectorXd q = sys.initial_coordinates();
  EXPECT_LT(sys.position_drift_m(q, 0.0), 1e-15);
  try {
    check_regular(sys, q, 1.5, 1e-9);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("singular position at t = 1.5"), std::string::npos) << e.what();
  }
}

// The row of the belt of all_joint_types at the initial poses: its constant
// is taken from them (s_out - i s_in), so the row is zero there; its Jacobian
// on the carrying body b1 sums both sides (-1 as the output's body_i, -i as the
// input's body_j: -1 - (-4) = 3).
TEST(MultibodyConstraints, TransmissionRowHoldsAtTheInitialPosesAndSumsTheCarriersColumns) {
  const MultibodySystem sys(all_joint_types());
  const ConstraintBlock& belt = sys.block("belt");
  EXPECT_EQ(belt.kind, ConstraintKind::Transmission);
  const VectorXd q = sys.initial_coordinates();
  EXPECT_NEAR(sys.phi(q, 0.0)(belt.first_row), 0.0, 1e-15);
  // Reference: b1 turns by 0.2, b2 by -0.5 (initial poses): c = (-0.5 - 0.2) - (-4)(0.2 - 0.3) = -1.1.
  EXPECT_NEAR(belt.reference, -1.1, 1e-15);
  const Eigen::MatrixXd jac = sys.jacobian(q, 0.0);
  EXPECT_DOUBLE_EQ(jac(belt.first_row, sys.offset(1) + 2), 3.0);  // b1: -1 - ratio
  EXPECT_DOUBLE_EQ(jac(belt.first_row, sys.offset(2) + 2), 1.0);  // b2: +1
  EXPECT_EQ(jac.row(belt.first_row).cwiseAbs().sum(), 4.0);       // nothing else
}

// Each bad transmission is an Error that names it and says what is wrong.
TEST(MultibodyConstraints, BadTransmissionsAreErrorsNamingThem) {
  auto expect_error = [](const std::function<void(Transmission&)>& spoil, const std::string& words) {
    MultibodyModel m = all_joint_types();
    spoil(m.transmissions.front());
    try {
      const MultibodySystem sys(m);
      ADD_FAILURE() << "no error for: " << words;
    } catch (const Error& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("transmission 'belt'"), std::string::npos) << what;
      EXPECT_NE(what.find(words), std::string::npos) << what;
    }
  };
  expect_error([](Transmission& t) { t.ratio = 0.0; }, "finite non-zero");
  expect_error([](Transmission& t) { t.ratio = std::numeric_limits<double>::quiet_NaN(); }, "finite non-zero");
  expect_error([](Transmission& t) { t.ratio = std::numeric_limits<double>::infinity(); }, "finite non-zero");
  expect_error([](Transmission& t) { t.radius_m = 0.0; }, "radius must be positive");
  expect_error([](Transmission& t) { t.output.type = CoordinateType::Displacement; }, "output coordinate must be an angle");
  expect_error([](Transmission& t) { t.input.body_j = "b9"; }, "names body 'b9'");
}

}  // namespace
}  // namespace kinetofem::mech
