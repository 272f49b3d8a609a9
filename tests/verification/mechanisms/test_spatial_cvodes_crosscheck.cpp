// Cross-check of the spatial multibody core (spatial/dynamics.hpp: IDAS, GGL index-2,
// centre-of-mass coordinates and Euler parameters with multipliers) against an
// independent formulation: the same systems in minimal coordinates, the angles of a
// serial chain of revolute joints, integrated as an ODE with SUNDIALS CVODES
// (docs/multibody.md, "CVODES cross-check on minimal coordinates"). A spherical joint is
// three revolutes about x, y, z (Cardan angles), a universal joint two (x, y), with
// massless links between them; the coordinates are free of singularity while the
// middle angle of each Cardan triple stays away from +-90 deg, which every run checks.
// Compared at every output time: centre-of-mass positions and velocities, rotation
// matrices and angular velocities (world), and every joint's reaction (force and moment
// about the joint point, world) from Newton-Euler on the bodies beyond the joint.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/spatial/dynamics.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"
// The mechanisms library's RAII owners of the SUNDIALS objects (every call checked
// through sundials_check); header-only, shared here rather than copied.
#include "../../../mechanisms/src/multibody/sundials_objects.hpp"

namespace kinetofem::mech::spatial {
namespace {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

constexpr double kG = 9.80665;

std::vector<double> grid(double t_end, int intervals) {
  std::vector<double> t(intervals + 1);
  for (int k = 0; k <= intervals; ++k) t[k] = t_end * k / intervals;
  return t;
}

// ---- Minimal coordinates: a serial chain of revolute joints ---------------------------
//
// Link k hangs from link k-1 (link -1: the ground, the world frame) by a revolute
// joint at the point offset_parent of link k-1's frame, about the unit axis (link k's
// frame, equal to link k-1's since the rotation about it leaves it fixed):
//     R_k = R_{k-1} Rot(axis_k, theta_k),   p_k = p_{k-1} + R_{k-1} offset_k,
// p_k the origin of link k's frame (on the joint axis). Links of zero mass are the
// crosses of universal and spherical joints. Mass properties as in spatial::Body:
// centre of mass com_link and centroidal inertia in link axes (kg, kg m^2).
struct ChainLink {
  std::string body;  // the spatial model's body it is, "" for a massless link
  Vector3d offset_parent = Vector3d::Zero();
  Vector3d axis = Vector3d::UnitZ();
  double mass_kg = 0.0;
  Matrix3d inertia_kgm2 = Matrix3d::Zero();
  Vector3d com_link = Vector3d::Zero();
};

struct Chain {
  std::vector<ChainLink> links;
  Vector3d gravity{0.0, 0.0, -kG};
  int dof() const { return static_cast<int>(links.size()); }
};

// Kinematics of one link at (theta, theta', theta''), world axes.
struct LinkState {
  Matrix3d rotation = Matrix3d::Identity();
  Vector3d origin, origin_velocity, axis;  // p_k, p_k', u_k = R_k axis_k
  Vector3d com, com_velocity, com_acceleration;
  Vector3d omega, alpha;
};

struct ChainState {
  std::vector<LinkState> links;
  VectorXd theta_ddot;
};

// Forward dynamics of the chain: kinematics, mass matrix M(theta) and the
// right-hand side of M theta'' = f(theta, theta'), solved for theta''
// (docs/multibody.md for the derivation).
ChainState evaluate(const Chain& chain, const VectorXd& theta, const VectorXd& theta_dot) {
  const int n = chain.dof();
  ChainState s;
  s.links.resize(n);
  // Jacobians of each link's centre-of-mass velocity and angular velocity in theta'.
  std::vector<MatrixXd> jv(n, MatrixXd::Zero(3, n)), jw(n, MatrixXd::Zero(3, n));
  Matrix3d r_parent = Matrix3d::Identity();
  Vector3d p_parent = Vector3d::Zero(), v_parent = Vector3d::Zero(), w_parent = Vector3d::Zero();
  Vector3d a0_parent = Vector3d::Zero(), alpha0_parent = Vector3d::Zero();  // bias accelerations (theta'' = 0)
  std::vector<Vector3d> a0(n), alpha0(n);
  for (int k = 0; k < n; ++k) {
    const ChainLink& link = chain.links[k];
    LinkState& ls = s.links[k];
    const Vector3d d = r_parent * link.offset_parent;
    ls.rotation = r_parent * Eigen::AngleAxisd(theta(k), link.axis).toRotationMatrix();
    ls.origin = p_parent + d;
    ls.axis = r_parent * link.axis;
    ls.origin_velocity = v_parent + w_parent.cross(d);
    ls.omega = w_parent + ls.axis * theta_dot(k);
    const Vector3d a0_origin = a0_parent + alpha0_parent.cross(d) + w_parent.cross(w_parent.cross(d));
    alpha0[k] = alpha0_parent + w_parent.cross(ls.axis) * theta_dot(k);
    const Vector3d r = ls.rotation * link.com_link;
    ls.com = ls.origin + r;
    ls.com_velocity = ls.origin_velocity + ls.omega.cross(r);
    a0[k] = a0_origin + alpha0[k].cross(r) + ls.omega.cross(ls.omega.cross(r));
    for (int j = 0; j <= k; ++j) {
      jw[k].col(j) = s.links[j].axis;
      jv[k].col(j) = s.links[j].axis.cross(ls.com - s.links[j].origin);
    }
    r_parent = ls.rotation;
    p_parent = ls.origin;
    v_parent = ls.origin_velocity;
    w_parent = ls.omega;
    a0_parent = a0_origin;
    alpha0_parent = alpha0[k];
  }
  MatrixXd mass = MatrixXd::Zero(n, n);
  VectorXd f = VectorXd::Zero(n);
  for (int k = 0; k < n; ++k) {
    const ChainLink& link = chain.links[k];
    if (link.mass_kg == 0.0) continue;
    const LinkState& ls = s.links[k];
    const Matrix3d inertia = ls.rotation * link.inertia_kgm2 * ls.rotation.transpose();
    mass += link.mass_kg * jv[k].transpose() * jv[k] + jw[k].transpose() * inertia * jw[k];
    f -= jv[k].transpose() * (link.mass_kg * (a0[k] - chain.gravity)) +
         jw[k].transpose() * (inertia * alpha0[k] + ls.omega.cross(inertia * ls.omega));
  }
  const Eigen::LDLT<MatrixXd> ldlt(mass);
  require(ldlt.info() == Eigen::Success && ldlt.isPositive(), "chain mass matrix is not positive definite");
  s.theta_ddot = ldlt.solve(f);
  for (int k = 0; k < n; ++k) {
    s.links[k].com_acceleration = a0[k] + jv[k] * s.theta_ddot;
    s.links[k].alpha = alpha0[k] + jw[k] * s.theta_ddot;
  }
  return s;
}

// Load of joint k on the links beyond it (k..n-1): Newton-Euler of that subtree,
//     F = sum m_i (a_i - g),   M_p = sum (c_i - p_k) x m_i (a_i - g) + I_i alpha_i + w_i x I_i w_i,
// the moment about the joint point p_k (world).
Reaction joint_load(const Chain& chain, const ChainState& s, int k) {
  Reaction r;
  r.point_world = s.links[k].origin;
  for (int i = k; i < chain.dof(); ++i) {
    const ChainLink& link = chain.links[i];
    const LinkState& ls = s.links[i];
    const Matrix3d inertia = ls.rotation * link.inertia_kgm2 * ls.rotation.transpose();
    const Vector3d force = link.mass_kg * (ls.com_acceleration - chain.gravity);
    r.force_world += force;
    r.moment_world += (ls.com - r.point_world).cross(force) + inertia * ls.alpha + ls.omega.cross(inertia * ls.omega);
  }
  return r;
}

struct ChainRun {
  std::vector<VectorXd> theta, theta_dot;  // per output time
  long steps = 0, rhs_evaluations = 0, error_test_failures = 0, nonlinear_failures = 0;
};

struct ChainProblem {
  const Chain& chain;
  std::string error;
};

int chain_rhs(sunrealtype /*t*/, N_Vector y, N_Vector ydot, void* user_data) {
  auto* p = static_cast<ChainProblem*>(user_data);
  try {
    const int n = p->chain.dof();
    const Eigen::Map<const VectorXd> yy(N_VGetArrayPointer(y), 2 * n);
    Eigen::Map<VectorXd> yd(N_VGetArrayPointer(ydot), 2 * n);
    const ChainState s = evaluate(p->chain, yy.head(n), yy.tail(n));
    yd.head(n) = yy.tail(n);
    yd.tail(n) = s.theta_ddot;
    return 0;
  } catch (const std::exception& e) {
    p->error = e.what();
    return -1;
  }
}

// y = (theta, theta') through CVODES (BDF, Newton, dense), relative tolerance
// rtol and absolute tolerance atol on every component (rad, rad/s).
ChainRun integrate_chain(const Chain& chain, const VectorXd& theta0, const VectorXd& theta_dot0,
                         const std::vector<double>& times, double rtol, double atol) {
  const int n = chain.dof();
  ChainProblem problem{chain, {}};
  sundials::Context ctx;
  sundials::Vector y(2 * n, ctx.ctx);
  y.map() << theta0, theta_dot0;
  sundials::CvodeMemory cvode(ctx.ctx);
  sundials_check(CVodeInit(cvode.mem, chain_rhs, times.front(), y.v), "CVodeInit");
  sundials_check(CVodeSStolerances(cvode.mem, rtol, atol), "CVodeSStolerances");
  sundials_check(CVodeSetUserData(cvode.mem, &problem), "CVodeSetUserData");
  sundials::DenseSolver dense(2 * n, y.v, ctx.ctx);
  sundials_check(CVodeSetLinearSolver(cvode.mem, dense.solver, dense.matrix), "CVodeSetLinearSolver");
  sundials_check(CVodeSetMaxNumSteps(cvode.mem, 1000000), "CVodeSetMaxNumSteps");
  ChainRun run;
  run.theta.push_back(theta0);
  run.theta_dot.push_back(theta_dot0);
  for (std::size_t k = 1; k < times.size(); ++k) {
    double t_reached = times[k - 1];
    sundials_check(CVode(cvode.mem, times[k], y.v, &t_reached, CV_NORMAL), "CVode",
                   "t = " + std::to_string(t_reached) + " s " + problem.error);
    run.theta.push_back(y.map().head(n));
    run.theta_dot.push_back(y.map().tail(n));
  }
  sundials_check(CVodeGetNumSteps(cvode.mem, &run.steps), "CVodeGetNumSteps");
  sundials_check(CVodeGetNumRhsEvals(cvode.mem, &run.rhs_evaluations), "CVodeGetNumRhsEvals");
  sundials_check(CVodeGetNumErrTestFails(cvode.mem, &run.error_test_failures), "CVodeGetNumErrTestFails");
  sundials_check(CVodeGetNumNonlinSolvConvFails(cvode.mem, &run.nonlinear_failures), "CVodeGetNumNonlinSolvConvFails");
  return run;
}

// The spatial model's bodies at the chain's initial state: pose, origin velocity and
// angular velocity (world) of every link that is a body; the ground added first.
void place_bodies(const Chain& chain, const VectorXd& theta0, const VectorXd& theta_dot0, Model& model) {
  const ChainState s = evaluate(chain, theta0, theta_dot0);
  for (int k = 0; k < chain.dof(); ++k) {
    const ChainLink& link = chain.links[k];
    if (link.body.empty()) continue;
    const auto it = std::find_if(model.bodies.begin(), model.bodies.end(),
                                 [&](const Body& body) { return body.name == link.body; });
    require(it != model.bodies.end(), "chain link names body '{}', which the model does not have", link.body);
    Body& b = *it;
    b.mass_kg = link.mass_kg;
    b.inertia_kgm2 = link.inertia_kgm2;
    b.com_body = link.com_link;
    b.position = s.links[k].origin;
    set_rotation(b, s.links[k].rotation);
    b.velocity = s.links[k].origin_velocity;
    b.angular_velocity = s.links[k].omega;
  }
}

// Largest differences between the two runs over all output times.
struct Differences {
  double position = 0.0, rotation = 0.0;          // relative to the length scale; rotation matrix entries
  double velocity = 0.0, angular_velocity = 0.0;  // relative to the peaks below
  double force = 0.0, moment = 0.0;               // relative to the weight W and to W times the length scale
  double cardan_min_cos = 1.0;  // smallest |cos| of the middle Cardan angles (1: far from the singularity)
  double peak_force = 0.0, peak_moment = 0.0;         // largest joint force (N) and moment (N m) of the reference
  double peak_speed = 0.0, peak_angular_speed = 0.0;  // largest |v_com| (m/s) and |w| (rad/s) of the reference
};

// joint_links: for each joint of the spatial model (model order), the chain link whose
// joint is its first revolute; the spatial joint's body_j is the body beyond it.
Differences compare(const System& sys, const Results& res, const Chain& chain, const ChainRun& run,
                    const std::vector<int>& joint_links, const std::vector<int>& cardan_middles,
                    double length_scale_m) {
  double weight = 0.0;
  for (const ChainLink& link : chain.links) weight += link.mass_kg * kG;
  Differences d;
  for (std::size_t f = 0; f < res.frames.size(); ++f) {
    const Frame& frame = res.frames[f];
    const ChainState s = evaluate(chain, run.theta[f], run.theta_dot[f]);
    for (int k = 0; k < chain.dof(); ++k) {
      if (chain.links[k].body.empty()) continue;
      const BodyState& b = frame.bodies[sys.body_index(chain.links[k].body)];
      const LinkState& ls = s.links[k];
      d.position = std::max(d.position, (b.com - ls.com).cwiseAbs().maxCoeff() / length_scale_m);
      d.rotation = std::max(d.rotation, (b.rotation - ls.rotation).cwiseAbs().maxCoeff());
      d.velocity = std::max(d.velocity, (b.com_velocity - ls.com_velocity).cwiseAbs().maxCoeff());
      d.angular_velocity = std::max(d.angular_velocity, (b.angular_velocity - ls.omega).cwiseAbs().maxCoeff());
      d.peak_speed = std::max(d.peak_speed, ls.com_velocity.norm());
      d.peak_angular_speed = std::max(d.peak_angular_speed, ls.omega.norm());
    }
    for (std::size_t j = 0; j < joint_links.size(); ++j) {
      const Reaction expected = joint_load(chain, s, joint_links[j]);
      const Reaction& got = frame.joints[j].on_j;
      // The spatial core's point on body_j is the chain's joint point (drift aside).
      d.position =
          std::max(d.position, (got.point_world - expected.point_world).cwiseAbs().maxCoeff() / length_scale_m);
      d.peak_force = std::max(d.peak_force, expected.force_world.norm());
      d.peak_moment = std::max(d.peak_moment, expected.moment_world.norm());
      d.force = std::max(d.force, (got.force_world - expected.force_world).cwiseAbs().maxCoeff() / weight);
      d.moment = std::max(d.moment,
                          (got.moment_world - expected.moment_world).cwiseAbs().maxCoeff() / (weight * length_scale_m));
    }
    for (int k : cardan_middles) d.cardan_min_cos = std::min(d.cardan_min_cos, std::abs(std::cos(run.theta[f](k))));
  }
  d.velocity /= d.peak_speed;
  d.angular_velocity /= d.peak_angular_speed;
  return d;
}

void print(const char* name, const Differences& d, const ChainRun& run, const Results& res, double idas_s,
           double cvodes_s) {
  std::printf(
      "%s, IDAS (spatial core) vs CVODES (minimal coordinates): positions %.2e of the length, "
      "rotation matrices %.2e, velocities %.2e and angular velocities %.2e of their peaks (%.3f m/s, %.3f rad/s), "
      "joint forces %.2e of the weight, joint moments %.2e of the weight x length (peaks %.3f N, %.3f N m); "
      "smallest |cos| of a middle Cardan angle %.3f\n"
      "  CVODES: %ld steps, %ld right-hand sides, %ld error-test and %ld nonlinear failures, %.3f s; IDAS %.3f s\n%s",
      name, d.position, d.rotation, d.velocity, d.angular_velocity, d.peak_speed, d.peak_angular_speed, d.force,
      d.moment, d.peak_force, d.peak_moment, d.cardan_min_cos, run.steps, run.rhs_evaluations, run.error_test_failures,
      run.nonlinear_failures, cvodes_s, idas_s, res.format_checks().c_str());
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Both integrators at relative tolerance 1e-12 (absolute 1e-14 on q, v and on theta,
// theta'): each keeps its local error per step below ~1e-12 of the state's scale; over
// the few thousand steps of a 2 s run that is not chaotic over that span, the global
// error is at most a few thousand local errors, ~1e-9 of the scale. Tolerance: 1e-8 of
// each quantity's scale (the length, the peak speeds, the weight), ten times that.
constexpr double kRelativeTolerance = 1e-12;
constexpr double kAbsoluteTolerance = 1e-14;
constexpr double kAgreement = 1e-8;

Matrix3d box_inertia(double mass_kg, const Vector3d& sides_m) {
  const Vector3d s2 = sides_m.cwiseProduct(sides_m);
  return (mass_kg / 12.0 * Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y())).asDiagonal();
}

// A heavy asymmetric body on a spherical joint at the world origin (a general heavy
// top): a 2 kg box 0.12 x 0.2 x 0.9 m with products of inertia, its centre of mass off
// its long axis, hanging below the joint, started tilted and spinning about all three
// axes. Chain: Cardan angles x-y-z, the body's frame origin at the joint.
TEST(SpatialCvodesCrossCheck, HeavyAsymmetricBodyOnASphericalJoint) {
  Chain chain;
  chain.links.resize(3);
  chain.links[0].axis = Vector3d::UnitX();
  chain.links[1].axis = Vector3d::UnitY();
  ChainLink& body = chain.links[2];
  body.body = "body";
  body.axis = Vector3d::UnitZ();
  body.mass_kg = 2.0;
  body.inertia_kgm2 = box_inertia(2.0, {0.12, 0.2, 0.9});
  body.inertia_kgm2(0, 1) = body.inertia_kgm2(1, 0) = 0.002;  // products of inertia
  body.inertia_kgm2(1, 2) = body.inertia_kgm2(2, 1) = -0.003;
  body.com_link = {0.04, -0.03, -0.45};
  VectorXd theta0(3), theta_dot0(3);
  theta0 << 0.3, -0.5, 0.2;
  theta_dot0 << 0.8, -0.4, 3.0;

  Model model;
  model.name = "heavy asymmetric body";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body b;
  b.name = "body";
  model.bodies = {ground, b};
  place_bodies(chain, theta0, theta_dot0, model);
  model.joints = {make_joint("pivot", JointType::Spherical, "ground", "origin", "body", "origin")};
  const System sys(model);

  const std::vector<double> times = grid(2.0, 40);
  DynamicsOptions options;
  options.relative_tolerance = kRelativeTolerance;
  options.absolute_tolerance = kAbsoluteTolerance;
  auto start = std::chrono::steady_clock::now();
  const Results res = simulate_ggl(sys, times, options);
  const double idas_s = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const ChainRun run = integrate_chain(chain, theta0, theta_dot0, times, kRelativeTolerance, kAbsoluteTolerance);
  const double cvodes_s = seconds_since(start);
  ASSERT_EQ(run.theta.size(), res.frames.size());
  const Differences d = compare(sys, res, chain, run, {0}, {1}, 0.45);
  print("heavy asymmetric body on a spherical joint, 2 s", d, run, res, idas_s, cvodes_s);
  // The Cardan angles are a valid chart over the run (gimbal lock at |cos| = 0).
  ASSERT_GT(d.cardan_min_cos, 0.3);
  // Reference: CVODES on the minimal-coordinate equations (docs/multibody.md), both
  // integrators at rtol 1e-12, atol 1e-14: 1e-8 (kAgreement).
  EXPECT_LT(d.position, kAgreement);
  EXPECT_LT(d.rotation, kAgreement);
  EXPECT_LT(d.velocity, kAgreement);
  EXPECT_LT(d.angular_velocity, kAgreement);
  EXPECT_LT(d.force, kAgreement);
  EXPECT_LT(d.moment, kAgreement);
  // The motion is not trivial: the body turns through more than a radian.
  EXPECT_GT((res.frames.back().bodies[1].rotation - res.frames.front().bodies[1].rotation).norm(), 1.0);
}

// A spatial double pendulum: rod 1 (1.5 kg, 1 m, section 0.06 x 0.12 m) on a universal
// joint at the world origin (cross axes: world x, then rod 1's y), rod 2 (1 kg, 0.8 m,
// section 0.05 x 0.03 m, centre of mass 2 cm off its axis) on a spherical joint at the
// end of a 0.15 m arm at rod 1's lower end (so rod 2's pull twists rod 1 and the
// universal joint carries a moment about rod 1's axis); both hang along their -z axes.
// Chain: x, y (universal), then x, y, z (spherical, Cardan angles relative to rod 1).
struct DoublePendulum {
  Chain chain;
  VectorXd theta0 = VectorXd(5), theta_dot0 = VectorXd(5);
  Model model;

  explicit DoublePendulum(double rod2_mass_kg = 1.0) {
    chain.links.resize(5);
    chain.links[0].axis = Vector3d::UnitX();
    ChainLink& rod1 = chain.links[1];
    rod1.body = "rod1";
    rod1.axis = Vector3d::UnitY();
    rod1.mass_kg = 1.5;
    rod1.inertia_kgm2 = box_inertia(1.5, {0.06, 0.12, 1.0});
    rod1.com_link = {0.0, 0.0, -0.5};
    chain.links[2].offset_parent = {0.15, 0.0, -1.0};
    chain.links[2].axis = Vector3d::UnitX();
    chain.links[3].axis = Vector3d::UnitY();
    ChainLink& rod2 = chain.links[4];
    rod2.body = "rod2";
    rod2.axis = Vector3d::UnitZ();
    rod2.mass_kg = rod2_mass_kg;
    rod2.inertia_kgm2 = box_inertia(rod2_mass_kg, {0.05, 0.03, 0.8});
    rod2.com_link = {0.02, 0.0, -0.4};
    theta0 << 0.4, -0.3, 0.5, 0.2, 0.0;
    theta_dot0 << 0.5, 1.0, -0.8, 0.6, 2.0;

    model.name = "spatial double pendulum";
    Body ground;
    ground.name = "ground";
    ground.fixed = true;
    Body b1;
    b1.name = "rod1";
    b1.points["tip"] = {0.15, 0.0, -1.0};
    Body b2;
    b2.name = "rod2";
    model.bodies = {ground, b1, b2};
    place_bodies(chain, theta0, theta_dot0, model);
    model.joints = {make_joint("U", JointType::Universal, "ground", "origin", "rod1", "origin", Vector3d::UnitX(),
                               Vector3d::UnitY()),
                    make_joint("S", JointType::Spherical, "rod1", "tip", "rod2", "origin")};
  }
};

TEST(SpatialCvodesCrossCheck, SpatialDoublePendulumUniversalAndSpherical) {
  const DoublePendulum pendulum;
  const System sys(pendulum.model);
  const std::vector<double> times = grid(2.0, 40);
  DynamicsOptions options;
  options.relative_tolerance = kRelativeTolerance;
  options.absolute_tolerance = kAbsoluteTolerance;
  auto start = std::chrono::steady_clock::now();
  const Results res = simulate_ggl(sys, times, options);
  const double idas_s = seconds_since(start);
  start = std::chrono::steady_clock::now();
  const ChainRun run = integrate_chain(pendulum.chain, pendulum.theta0, pendulum.theta_dot0, times, kRelativeTolerance,
                                       kAbsoluteTolerance);
  const double cvodes_s = seconds_since(start);
  ASSERT_EQ(run.theta.size(), res.frames.size());
  const Differences d = compare(sys, res, pendulum.chain, run, {0, 2}, {3}, 1.0);
  print("spatial double pendulum (universal + spherical), 2 s", d, run, res, idas_s, cvodes_s);
  ASSERT_GT(d.cardan_min_cos, 0.3);
  // Reference: CVODES on the minimal-coordinate equations, rtol 1e-12 on both sides: 1e-8.
  EXPECT_LT(d.position, kAgreement);
  EXPECT_LT(d.rotation, kAgreement);
  EXPECT_LT(d.velocity, kAgreement);
  EXPECT_LT(d.angular_velocity, kAgreement);
  EXPECT_LT(d.force, kAgreement);
  EXPECT_LT(d.moment, kAgreement);

  // The comparison resolves a model error far smaller than an engineer would notice:
  // rod 2 heavier by one part in a million moves the trajectory and the reactions by
  // more than ten times the tolerance.
  const DoublePendulum heavier(1.0 + 1e-6);
  const ChainRun perturbed =
      integrate_chain(heavier.chain, heavier.theta0, heavier.theta_dot0, times, kRelativeTolerance, kAbsoluteTolerance);
  const Differences p = compare(sys, res, heavier.chain, perturbed, {0, 2}, {3}, 1.0);
  std::printf(
      "  with rod 2 heavier by 1e-6 in the minimal model: positions %.2e of the length, velocities %.2e of "
      "the peak, joint forces %.2e of the weight\n",
      p.position, p.velocity, p.force);
  EXPECT_GT(std::max({p.position, p.velocity, p.force}), 10.0 * kAgreement);
}

}  // namespace
}  // namespace kinetofem::mech::spatial
