// Unit tests of the spatial core's constraint equations (spatial/system.hpp):
// Phi_q of every joint type and drive against central finite differences of
// Phi, Pi = Phi_q L, gamma against the finite-difference second derivative of
// Phi along a known motion, the joint table's counts, and a redundant planar
// loop built from spatial revolutes.
#include <cmath>
#include <cstdio>
#include <memory>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"

namespace kinetofem::mech::spatial {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::Vector4d;
using Eigen::VectorXd;

// Hamilton product a (x) b: A(a (x) b) = A(a) A(b).
Vector4d quaternion_product(const Vector4d& a, const Vector4d& b) {
  Vector4d c;
  c(0) = a(0) * b(0) - a.tail<3>().dot(b.tail<3>());
  c.tail<3>() = a(0) * b.tail<3>() + b(0) * a.tail<3>() + a.tail<3>().cross(b.tail<3>());
  return c;
}

// Two moving bodies in general poses (not assembled: the Jacobians hold
// everywhere) joined by `type`, optionally driven; a tilted ground holds body 1
// by a spherical joint so that fixed-body columns are exercised too.
Model two_body_model(JointType type, std::optional<DriveCoordinate> drive = std::nullopt) {
  Model m;
  m.name = "two bodies";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.euler_parameters = axis_angle(Vector3d(1, 2, 3).normalized(), 0.4);
  ground.position = {0.1, -0.2, 0.3};
  ground.points["anchor"] = {0.2, 0.1, -0.1};
  Body b1;
  b1.name = "b1";
  b1.mass_kg = 2.0;
  b1.inertia_kgm2 = Eigen::Vector3d(0.1, 0.2, 0.15).asDiagonal();
  b1.com_body = {0.3, 0.05, -0.02};
  b1.points["end"] = {0.6, 0.1, 0.05};
  b1.points["start"] = {0.0, -0.1, 0.02};
  b1.position = {0.3, 0.2, 0.1};
  b1.euler_parameters = axis_angle(Vector3d(-1, 0.5, 2).normalized(), 0.9);
  Body b2 = b1;
  b2.name = "b2";
  b2.points["start"] = {0.05, 0.02, -0.03};
  b2.position = {0.85, 0.45, 0.2};
  b2.euler_parameters = axis_angle(Vector3d(0.3, -1, 0.4).normalized(), 1.1);
  m.bodies = {ground, b1, b2};
  m.joints.push_back(make_joint("G", JointType::Spherical, "ground", "anchor", "b1", "start"));
  Joint j = make_joint("J", type, "b1", "end", "b2", "start", Vector3d(0.2, 0.3, 1.0), Vector3d(0.1, 0.4, 0.9));
  if (type == JointType::Universal) j.axis_j = Vector3d(1.0, -0.3, 0.2);
  m.joints.push_back(j);
  if (drive) {
    MotionDrive d;
    d.name = "drive";
    d.joint = "J";
    d.coordinate = *drive;
    d.law = std::make_shared<Polynomial345Law>(0.7, 2.0);
    m.motion_drives.push_back(d);
  }
  return m;
}

struct Case {
  JointType type;
  std::optional<DriveCoordinate> drive;
};

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (JointType t : all_joint_types) cases.push_back({t, std::nullopt});
  cases.push_back({JointType::Revolute, DriveCoordinate::Rotation});
  cases.push_back({JointType::Prismatic, DriveCoordinate::Translation});
  cases.push_back({JointType::Cylindrical, DriveCoordinate::Rotation});
  cases.push_back({JointType::Cylindrical, DriveCoordinate::Translation});
  return cases;
}

std::string label(const Case& c) {
  std::string s = joint_facts(c.type).name;
  if (c.drive) s += *c.drive == DriveCoordinate::Rotation ? " + rotation drive" : " + translation drive";
  return s;
}

TEST(SpatialJointTable, RowsEqualCarriedReactionComponents) {
  for (JointType t : all_joint_types) {
    const JointFacts& f = joint_facts(t);
    EXPECT_EQ(f.rows, f.forces + f.moments) << f.name;
    const System sys(two_body_model(t));
    EXPECT_EQ(sys.block("J").rows, f.rows) << f.name;
    EXPECT_EQ(sys.evaluate(sys.block("J"), sys.initial_positions(), sys.initial_velocities(), 0.0).phi.size(), f.rows);
    EXPECT_EQ(joint_type_named(f.name), t);
  }
}

// At an assembled pose with motion, each joint's reaction on body_j (at P_j,
// world axes) carries only the components of the joint table: a joint with 2
// forces has none along h_i; 0 moments: none; 2: none about h_i; the universal
// joint's 1: only about h_i x h_j. Action equals reaction at a shared point;
// across a slide the moments differ by the arm d x F.
TEST(SpatialJointTable, ReactionsCarryOnlyTheTableComponents) {
  for (JointType t : all_joint_types) {
    const JointFacts& facts = joint_facts(t);
    Model m = two_body_model(t);
    m.gravity = {1.0, -9.0, 3.0};
    const System sys(m);
    const VectorXd q = assemble(sys, sys.initial_positions(), 0.0);
    VectorXd v_guess(sys.n_velocities());
    v_guess << 0.3, -0.2, 0.5, 1.1, -0.7, 0.4, -0.6, 0.8, 0.2, 2.0, 0.5, -1.5;
    const VectorXd v = solve_velocities(sys, q, 0.0, v_guess);
    const Frame f = make_frame(sys, 0.0, q, v);
    const ConstraintBlock& blk = sys.block("J");
    const JointState& j = f.joints[1];
    const Vector3d h_i = sys.rotation(blk.body_i, q) * blk.h_i, h_j = sys.rotation(blk.body_j, q) * blk.h_j;
    const double scale = std::max(j.on_j.force_world.norm(), j.on_j.moment_world.norm());
    // Reference: the rows' directions (system.hpp); round-off, 1e-12 of the reaction.
    const double tol = 1e-12 * scale;
    if (facts.forces == 2) {
      EXPECT_NEAR(j.on_j.force_world.dot(h_i), 0.0, tol) << facts.name;
    }
    if (facts.moments == 0) {
      EXPECT_LT(j.on_j.moment_world.norm(), tol) << facts.name;
    }
    if (facts.moments == 2) {
      EXPECT_NEAR(j.on_j.moment_world.dot(h_i), 0.0, tol) << facts.name;
    }
    if (facts.moments == 1) {
      EXPECT_NEAR(j.on_j.moment_world.dot(h_i), 0.0, tol) << facts.name;
      EXPECT_NEAR(j.on_j.moment_world.dot(h_j), 0.0, tol) << facts.name;
    }
    EXPECT_LT((j.on_i.force_world + j.on_j.force_world).norm(), tol) << facts.name;
    const Vector3d arm = j.on_j.point_world - j.on_i.point_world;
    EXPECT_LT((j.on_i.moment_world + j.on_j.moment_world + arm.cross(j.on_j.force_world)).norm(), tol) << facts.name;
    EXPECT_GT(scale, 0.1) << facts.name;
    EXPECT_EQ(f.redundant_rows, 0) << facts.name;
  }
}

TEST(SpatialConstraints, JacobianMatchesCentralDifferences) {
  for (const Case& c : all_cases()) {
    const System sys(two_body_model(c.type, c.drive));
    const double t = 0.7;
    const VectorXd q = sys.initial_positions();
    const MatrixXd jac = sys.jacobian_q(q, t);
    MatrixXd fd(jac.rows(), jac.cols());
    const double h = 1e-6;
    for (int k = 0; k < q.size(); ++k) {
      VectorXd qp = q, qm = q;
      qp(k) += h;
      qm(k) -= h;
      fd.col(k) = (sys.phi(qp, t) - sys.phi(qm, t)) / (2.0 * h);
    }
    const double rel = (jac - fd).cwiseAbs().maxCoeff() / std::max(1.0, jac.cwiseAbs().maxCoeff());
    std::printf("Phi_q vs central differences, %s: %.2e relative\n", label(c).c_str(), rel);
    // Reference: central differences, truncation O(h^2) ~ 1e-12, round-off ~ eps/h ~ 1e-10.
    EXPECT_LT(rel, 1e-7) << label(c);
  }
}

TEST(SpatialConstraints, VelocityJacobianIsPhiQTimesL) {
  for (const Case& c : all_cases()) {
    const System sys(two_body_model(c.type, c.drive));
    const VectorXd q = sys.initial_positions();
    MatrixXd l = MatrixXd::Zero(sys.n_positions(), sys.n_velocities());
    for (int k = 0; k < sys.n_velocities(); ++k)
      l.col(k) = sys.position_rates(q, VectorXd::Unit(sys.n_velocities(), k));
    const MatrixXd pi = sys.jacobian_v(q, 0.7);
    // Reference: Pi = Phi_q L on unit Euler parameters (system.hpp); round-off.
    EXPECT_LT((pi - sys.jacobian_q(q, 0.7) * l).cwiseAbs().maxCoeff(), 1e-13) << label(c);
  }
}

TEST(SpatialConstraints, GammaMatchesSecondDerivativeAlongAMotion) {
  for (const Case& c : all_cases()) {
    const System sys(two_body_model(c.type, c.drive));
    const VectorXd q0 = sys.initial_positions();
    const int nb = sys.n_moving();
    // A known motion: r = r0 + u t + a t^2/2, rotation at a constant body-axes
    // angular velocity w (so w' = 0): p(t) = p0 (x) (cos(|w|t/2), sin(|w|t/2) w/|w|).
    std::vector<Vector3d> u(nb), a(nb), w(nb);
    for (int k = 0; k < nb; ++k) {
      u[k] = Vector3d(0.3 - k, 0.5, -0.2 * k);
      a[k] = Vector3d(1.0, -2.0 + k, 0.7);
      w[k] = Vector3d(1.5, -0.8 + k, 2.0 - 0.5 * k);
    }
    const double t0 = 0.7;
    const auto q_at = [&](double s) {
      VectorXd q = q0;
      for (int k = 0; k < nb; ++k) {
        q.segment<3>(7 * k) += u[k] * s + 0.5 * a[k] * s * s;
        q.segment<4>(7 * k + 3) = quaternion_product(q0.segment<4>(7 * k + 3), axis_angle(w[k], w[k].norm() * s));
      }
      return q;
    };
    VectorXd v(sys.n_velocities()), v_dot = VectorXd::Zero(sys.n_velocities());
    for (int k = 0; k < nb; ++k) {
      v.segment<3>(6 * k) = u[k];
      v.segment<3>(6 * k + 3) = w[k];
      v_dot.segment<3>(6 * k) = a[k];
    }
    const double h = 1e-4;
    const VectorXd phi_tt = (sys.phi(q_at(h), t0 + h) - 2.0 * sys.phi(q_at(0.0), t0) + sys.phi(q_at(-h), t0 - h)) / (h * h);
    const VectorXd q = q_at(0.0);
    const VectorXd analytic = sys.jacobian_v(q, t0) * v_dot - sys.gamma(q, v, t0);
    const double rel = (analytic - phi_tt).cwiseAbs().maxCoeff() / std::max(1.0, analytic.cwiseAbs().maxCoeff());
    std::printf("gamma vs second difference, %s: %.2e relative\n", label(c).c_str(), rel);
    // Reference: Phi'' = Pi v' - gamma; central second difference, truncation
    // O(h^2) ~ 1e-8, round-off ~ eps/h^2 ~ 1e-8.
    EXPECT_LT(rel, 1e-6) << label(c);
  }
}

// A planar four-bar (ground 2 m, crank 1 m, coupler 2.5 m, rocker 1.8 m,
// mass_per_m kg/m, axial_inertia about each rod) with four revolutes about z, crank driven: 20 rows on 18 velocities, DoF 0 with 3
// redundant rows (the out-of-plane ones of the loop). The index-1 solve must
// not fail, must report 3, and must balance every body.
void check_redundant_four_bar(double mass_per_m, double axial_inertia) {
  Model m;
  m.name = "spatial four-bar";
  m.gravity = {0.0, -9.80665, 0.0};
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["D"] = {2.0, 0.0, 0.0};
  const auto link = [&](const std::string& name, double length, const Vector3d& origin, double angle) {
    Body b;
    b.name = name;
    b.mass_kg = mass_per_m * length;
    const double across = b.mass_kg * length * length / 12.0;
    b.inertia_kgm2 = Eigen::Vector3d(axial_inertia, across, across).asDiagonal();
    b.com_body = {0.5 * length, 0.0, 0.0};
    b.points["end"] = {length, 0.0, 0.0};
    b.position = origin;
    b.euler_parameters = axis_angle(Vector3d::UnitZ(), angle);
    return b;
  };
  // Approximate poses; assembly closes the loop.
  m.bodies = {ground, link("crank", 1.0, {0, 0, 0}, 1.0), link("coupler", 2.5, {0.54, 0.84, 0}, -0.2),
              link("rocker", 1.8, {2.0, 0.0, 0.0}, 1.9)};
  m.joints = {make_joint("A", JointType::Revolute, "ground", "origin", "crank", "origin"),
              make_joint("B", JointType::Revolute, "crank", "end", "coupler", "origin"),
              make_joint("C", JointType::Revolute, "coupler", "end", "rocker", "end"),
              make_joint("D", JointType::Revolute, "ground", "D", "rocker", "origin")};
  MotionDrive d;
  d.name = "crank drive";
  d.joint = "A";
  d.law = std::make_shared<ConstantVelocityLaw>(2.0);
  m.motion_drives = {d};
  const System sys(m);
  const Results res = run_kinematics(sys, {0.0, 0.1, 0.2, 0.3});
  for (const Frame& f : res.frames) {
    EXPECT_EQ(f.redundant_rows, 3);
    // Reference: d'Alembert equilibrium of every body, round-off.
    EXPECT_LT(f.equilibrium_residual, 1e-12);
    EXPECT_LT(f.drift_position_m, 1e-12);
    EXPECT_NEAR(f.drives[0].s_dot, 2.0, 1e-12);
    // Minimum-norm multipliers under in-plane loads: no force along z (1e-9 of the weight).
    const double weight = mass_per_m * (1.0 + 2.5 + 1.8) * 9.80665;
    for (const JointState& j : f.joints) EXPECT_NEAR(j.on_j.force_world.z(), 0.0, 1e-9 * weight) << j.name;
  }
  std::printf("%s", res.format_checks().c_str());
}

TEST(SpatialRedundancy, PlanarFourBarOfRevolutesReportsThreeRedundantRows) { check_redundant_four_bar(1.0, 0.01); }

// The rank is decided in the mass metric (results.hpp): heavy links with a
// tiny inertia about their own axis (1e-12 kg m^2, 1e15 below the others)
// still give 3 redundant rows, not a spurious fourth.
TEST(SpatialRedundancy, RankIsIndependentOfTheMassScale) { check_redundant_four_bar(1000.0, 1e-12); }

// A point mass with rotary inertia moves the centre of mass and adds
// J_pm + m_pm (|d|^2 I - d d^T) about it; the bare body's own inertia shifts
// likewise (parallel-axis rule, body axes).
TEST(SpatialModel, PointMassWithRotaryInertiaFollowsTheParallelAxisRule) {
  Model m;
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body b;
  b.name = "arm";
  b.mass_kg = 3.0;
  b.inertia_kgm2 = Vector3d(0.1, 0.2, 0.3).asDiagonal();
  b.com_body = {0.5, 0.0, 0.0};
  PointMass pm;
  pm.name = "casting";
  pm.mass_kg = 1.0;
  pm.position_body = {1.3, 0.4, 0.0};
  pm.inertia_kgm2 = Vector3d(0.01, 0.02, 0.03).asDiagonal();
  b.point_masses = {pm};
  m.bodies = {ground, b};
  const System sys(m);
  const EffectiveBody& e = sys.effective(1);
  const Vector3d c = (3.0 * Vector3d(0.5, 0, 0) + 1.0 * Vector3d(1.3, 0.4, 0)) / 4.0;
  const auto shift = [](double mass, const Vector3d& d) {
    return Eigen::Matrix3d(mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose()));
  };
  const Eigen::Matrix3d expected = b.inertia_kgm2 + shift(3.0, Vector3d(0.5, 0, 0) - c) + pm.inertia_kgm2 +
                                   shift(1.0, pm.position_body - c);
  EXPECT_DOUBLE_EQ(e.mass_kg, 4.0);
  // Reference: the parallel-axis rule written out above; round-off.
  EXPECT_LT((e.com_body - c).norm(), 1e-15);
  EXPECT_LT((e.inertia_kgm2 - expected).cwiseAbs().maxCoeff(), 1e-15);
}

// The generalised force of a point force does the power F . v_P at any
// velocity, and the gyroscopic term does none (w . (w x J w) = 0).
TEST(SpatialModel, PointForceAndGyroscopicTermsHaveTheRightPower) {
  Model m = two_body_model(JointType::Spherical);
  m.gravity.setZero();
  PointForce f;
  f.name = "load";
  f.body = "b2";
  f.point = "start";
  f.force_world = {3.0, -2.0, 5.0};
  m.point_forces = {f};
  const System sys(m);
  const VectorXd q = sys.initial_positions();
  VectorXd v(sys.n_velocities());
  v << 0.3, -0.2, 0.5, 1.1, -0.7, 0.4, -0.6, 0.8, 0.2, 2.0, 0.5, -1.5;
  const int b2 = sys.body_index("b2");
  const Vector3d s = sys.named_point(b2, "start") - sys.effective(b2).com_body;
  const Vector3d v_point = sys.com_velocity(b2, v) + sys.rotation(b2, q) * sys.angular_velocity_body(b2, v).cross(s);
  // Reference: virtual power of the force at its point; the gyroscopic terms
  // are workless. Round-off.
  EXPECT_NEAR(sys.forces(q, v, 0.0).dot(v), f.force_world.dot(v_point), 1e-13);
}

// A pose given as a rotation matrix equals the same pose as Euler parameters.
TEST(SpatialModel, RotationMatrixAndEulerParametersGiveTheSamePose) {
  const Vector4d p = axis_angle(Vector3d(0.3, -0.5, 0.8).normalized(), 2.9);
  Body b;
  set_rotation(b, rotation(p));
  // Reference: the rotation matrix of p (rotation.hpp); round-off.
  EXPECT_LT((rotation(b.euler_parameters) - rotation(p)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((rotation(p) * rotation(p).transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(SpatialModelErrors, AxisOfZeroLength) {
  Model m = two_body_model(JointType::Revolute);
  m.joints[1].axis_i.setZero();
  try {
    const System sys(m);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'J': axis_i of zero length"), std::string::npos) << e.what();
  }
}

TEST(SpatialModelErrors, DriveOnAJointWithoutThatCoordinate) {
  const Model m = two_body_model(JointType::Spherical, DriveCoordinate::Rotation);
  try {
    const System sys(m);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a spherical joint ('J') has no driven rotation"), std::string::npos)
        << e.what();
  }
}

TEST(SpatialModelErrors, MechanismThatCannotBeAssembledNamesTheJoints) {
  Model m;
  m.name = "too long";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["far"] = {3.0, 0.0, 0.0};
  Body rod;
  rod.name = "rod";
  rod.mass_kg = 1.0;
  rod.inertia_kgm2 = Eigen::Matrix3d::Identity();
  rod.points["end"] = {1.0, 0.0, 0.0};
  m.bodies = {ground, rod};
  m.joints = {make_joint("near", JointType::Spherical, "ground", "origin", "rod", "origin"),
              make_joint("reach", JointType::Spherical, "ground", "far", "rod", "end")};
  const System sys(m);
  try {
    assemble(sys, sys.initial_positions(), 0.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot be assembled"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'reach'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("'near'"), std::string::npos) << e.what();
  }
}

// A law that holds s = 0 at rest but asks for the acceleration `a`: not a
// motion, the smallest way to make two drives on one coordinate disagree.
class AccelerationOnly final : public MotionLaw {
 public:
  explicit AccelerationOnly(double a) : a_(a) {}
  MotionState at(double) const override { return {0.0, 0.0, a_}; }
  double stroke() const override { return 0.0; }
  double duration() const override { return 1.0; }
  std::string describe() const override { return "acceleration only"; }

 private:
  double a_;
};

TEST(SpatialModelErrors, RedundantRowsThatDisagreeAreNamed) {
  // One revolute turned by two drives on its angle: the rows are the same
  // (redundant) and hold in position and velocity, but ask for different
  // accelerations.
  Model m;
  m.name = "two drives";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body crank;
  crank.name = "crank";
  crank.mass_kg = 1.0;
  crank.inertia_kgm2 = Eigen::Vector3d(0.01, 0.02, 0.02).asDiagonal();
  crank.com_body = {0.1, 0.0, 0.0};
  m.bodies = {ground, crank};
  m.joints = {make_joint("pivot", JointType::Revolute, "ground", "origin", "crank", "origin")};
  for (const auto& [name, a] : {std::pair{"slow", 1.0}, std::pair{"fast", 2.0}}) {
    MotionDrive d;
    d.name = name;
    d.joint = "pivot";
    d.law = std::make_shared<AccelerationOnly>(a);
    m.motion_drives.push_back(d);
  }
  const System system(m);
  const Eigen::VectorXd q = assemble(system, system.initial_positions(), 0.0);
  try {
    make_frame(system, 0.0, q, Eigen::VectorXd::Zero(system.n_velocities()));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("inconsistent"), std::string::npos) << what;
    EXPECT_NE(what.find("'slow'"), std::string::npos) << what;
    EXPECT_NE(what.find("'fast'"), std::string::npos) << what;
    EXPECT_EQ(what.find("'pivot'"), std::string::npos) << what;
  }
}

TEST(SpatialModelErrors, InertiaNotPositiveDefinite) {
  Model m = two_body_model(JointType::Revolute);
  m.bodies[2].inertia_kgm2 = Eigen::Vector3d(0.1, 0.0, 0.1).asDiagonal();
  m.bodies[2].com_body.setZero();
  EXPECT_THROW(System{m}, Error);
}

}  // namespace
}  // namespace kinetofem::mech::spatial
