#include "kinetofem/mechanisms/spherical_manipulator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <cvodes/cvodes.h>
#include <cvodes/cvodes_ls.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "multibody/sundials_objects.hpp"

namespace kinetofem::mech {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Orthonormal spherical basis at (phi10, phi21).
struct Basis {
  Vector3d r, theta, phi, h;  // e_r, e_theta, e_phi, horizontal radial e_h
};

Basis basis(double phi10, double phi21) {
  const double c1 = std::cos(phi10), s1 = std::sin(phi10), c2 = std::cos(phi21), s2 = std::sin(phi21);
  return {{c2 * c1, c2 * s1, s2}, {-s2 * c1, -s2 * s1, c2}, {-s1, c1, 0.0}, {c1, s1, 0.0}};
}

// Acceleration of the point B + d e_r of the arm (d' = l', d'' = l'': the arm slides).
Vector3d arm_point_acceleration(const Basis& e, const SphericalJointMotion& j, double d) {
  const double w1 = j.qd(0), w2 = j.qd(1), ld = j.qd(2);
  const double a1 = j.qdd(0), a2 = j.qdd(1), ldd = j.qdd(2);
  const double c2 = std::cos(j.q(1)), s2 = std::sin(j.q(1));
  const double ar = ldd - d * w2 * w2 - d * w1 * w1 * c2 * c2;
  const double at = d * a2 + 2.0 * ld * w2 + d * w1 * w1 * s2 * c2;
  const double ap = d * a1 * c2 + 2.0 * ld * w1 * c2 - 2.0 * d * w1 * w2 * s2;
  return ar * e.r + at * e.theta + ap * e.phi;
}

// Inertia tensor (world) of a body symmetric about `axis`.
Matrix3d axial_inertia(const Vector3d& axis, double axial, double transverse) {
  return transverse * Matrix3d::Identity() + (axial - transverse) * axis * axis.transpose();
}

}  // namespace

const std::array<SphericalVariant, 5>& spherical_variants() {
  // SPEC §5 table (source 003, table 1): columns A-E.
  static const std::array<SphericalVariant, 5> variants{{
      {'A', 2.2, 1.2, 25 * kDeg, 0.7, 0.5, 70 * kDeg, 300, 120, 50, 1.0, 0.25, 0.25},
      {'B', 2.0, 1.0, 20 * kDeg, 0.8, 0.6, 75 * kDeg, 250, 120, 40, 0.8, 0.3, 0.2},
      {'C', 1.8, 0.9, 25 * kDeg, 0.75, 0.55, 65 * kDeg, 200, 100, 40, 0.9, 0.25, 0.15},
      {'D', 1.9, 0.9, 24 * kDeg, 0.7, 0.45, 60 * kDeg, 200, 100, 35, 0.85, 0.2, 0.3},
      {'E', 1.8, 0.9, 20 * kDeg, 0.8, 0.5, 65 * kDeg, 200, 100, 35, 1.0, 0.3, 0.2},
  }};
  return variants;
}

const SphericalVariant& spherical_variant(char name) {
  for (const SphericalVariant& v : spherical_variants())
    if (v.name == name) return v;
  fail("spherical manipulator: no variant '{}' (SPEC §5 has A-E)", name);
}

SphericalDesign size_spherical_manipulator(const SphericalVariant& variant, double payload_kg,
                                           const SphericalSizingOptions& options) {
  require(payload_kg >= 0.0, "spherical manipulator: payload mass must be >= 0, got {} kg", payload_kg);
  require(options.sleeve_ratio >= 0.2 && options.sleeve_ratio <= 0.5,
          "spherical manipulator: sleeve ratio l2/l1 = {} outside the source's 0.2..0.5", options.sleeve_ratio);
  require(options.sleeve_diameter_ratio >= 0.2 && options.sleeve_diameter_ratio <= 0.4,
          "spherical manipulator: sleeve diameter ratio d2/l2 = {} outside 0.2..0.4", options.sleeve_diameter_ratio);
  SphericalDesign d;
  d.variant = variant;
  d.payload_kg = payload_kg;
  // l1 = r_Mmax + 0.5 l2 + margin with l2 = k l1  =>  l1 = (r_Mmax + margin) / (1 - 0.5 k).
  d.arm_length_m = (variant.r_max_m + options.margin_m) / (1.0 - 0.5 * options.sleeve_ratio);
  d.sleeve_length_m = options.sleeve_ratio * d.arm_length_m;
  d.sleeve_diameter_m = options.sleeve_diameter_ratio * d.sleeve_length_m;
  d.base_diameter_m = options.base_diameter_ratio * variant.height_a_m;
  d.arm_inertia_transverse = variant.m3_kg * d.arm_length_m * d.arm_length_m / 12.0;
  d.arm_inertia_axial = 0.0;
  d.sleeve_inertia_transverse = 0.1 * variant.m2_kg * d.sleeve_length_m * d.sleeve_length_m;
  d.sleeve_inertia_axial = 0.0;
  d.column_inertia_z = 0.1 * variant.m1_kg * 0.25 * d.base_diameter_m * d.base_diameter_m;
  d.column_com_height_m = 0.5 * variant.height_b_m;
  return d;
}

Vector3d spherical_inverse_kinematics(const SphericalDesign& design, const Vector3d& m) {
  const Vector3d rho(m.x(), m.y(), m.z() - design.variant.height_b_m);
  const double l = rho.norm();
  require(l > 0.0 && std::hypot(m.x(), m.y()) > 0.0,
          "spherical manipulator: point M = ({}, {}, {}) m lies on the base axis (inverse kinematics singular)", m.x(),
          m.y(), m.z());
  return {std::atan2(m.y(), m.x()), std::asin(rho.z() / l), l};
}

Vector3d spherical_forward_kinematics(const SphericalDesign& design, const Vector3d& q) {
  return Vector3d(0.0, 0.0, design.variant.height_b_m) + q(2) * basis(q(0), q(1)).r;
}

SphericalJointMotion spherical_joint_motion(const SphericalDesign& design, const Vector3d& m, const Vector3d& m_dot,
                                            const Vector3d& m_ddot) {
  SphericalJointMotion j;
  j.q = spherical_inverse_kinematics(design, m);
  const Basis e = basis(j.q(0), j.q(1));
  const double l = j.q(2), c2 = std::cos(j.q(1)), s2 = std::sin(j.q(1));
  j.qd(2) = m_dot.dot(e.r);
  j.qd(1) = m_dot.dot(e.theta) / l;
  j.qd(0) = m_dot.dot(e.phi) / (l * c2);
  const double w1 = j.qd(0), w2 = j.qd(1), ld = j.qd(2);
  j.qdd(2) = m_ddot.dot(e.r) + l * w2 * w2 + l * w1 * w1 * c2 * c2;
  j.qdd(1) = (m_ddot.dot(e.theta) - 2.0 * ld * w2 - l * w1 * w1 * s2 * c2) / l;
  j.qdd(0) = (m_ddot.dot(e.phi) - 2.0 * ld * w1 * c2 + 2.0 * l * w1 * w2 * s2) / (l * c2);
  return j;
}

void check_service_zone(const SphericalDesign& design, const Vector3d& q, double t) {
  const SphericalVariant& v = design.variant;
  const double tol = 1e-9;
  require(std::abs(q(0)) <= v.base_rotation_max_rad + tol,
          "spherical manipulator {}: base rotation phi10 = {:.3f} deg exceeds +-{:.1f} deg at t = {:.6g} s", v.name,
          q(0) / kDeg, v.base_rotation_max_rad / kDeg, t);
  require(std::abs(q(1)) <= v.tilt_max_rad + tol,
          "spherical manipulator {}: arm tilt phi21 = {:.3f} deg exceeds +-{:.1f} deg at t = {:.6g} s", v.name,
          q(1) / kDeg, v.tilt_max_rad / kDeg, t);
  const double reach = q(2) * std::cos(q(1));  // horizontal radius of M
  require(q(2) <= v.r_max_m + tol && reach >= v.r_min_m - tol,
          "spherical manipulator {}: M outside the service zone at t = {:.6g} s (l_BM = {:.4f} m, radius {:.4f} m, zone "
          "{}..{} m)",
          v.name, t, q(2), reach, v.r_min_m, v.r_max_m);
}

// ---- straight-line motion ----------------------------------------------------------

StraightLineMotion::StraightLineMotion(const Vector3d& a, const Vector3d& b, double speed_mps, double k_accel,
                                       double k_decel)
    : a_(a),
      direction_((b - a).normalized()),
      length_((b - a).norm()),
      law_(TrapezoidalLaw::from_speed((b - a).norm(), speed_mps, k_accel, k_decel)) {
  require(length_ > 0.0, "straight-line motion: a and b coincide");
}

StraightLineMotion::Point StraightLineMotion::at(double t) const {
  const MotionState s = law_.at(t);
  return {a_ + s.s * direction_, s.s_dot * direction_, s.s_ddot * direction_};
}

std::vector<double> StraightLineMotion::breakpoints() const {
  const double T = law_.duration();
  const double tp = law_.cruise_speed() / law_.acceleration();
  const double tt = law_.cruise_speed() / law_.deceleration();
  return {0.0, tp, T - tt, T};
}

// ---- kinetostatics -------------------------------------------------------------------

SphericalDynamics spherical_inverse_dynamics(const SphericalDesign& design, const SphericalJointMotion& j, double t) {
  const SphericalVariant& v = design.variant;
  const Vector3d g(0.0, 0.0, -design.gravity_mps2), z = Vector3d::UnitZ();
  const Vector3d b(0.0, 0.0, v.height_b_m), a(0.0, 0.0, v.height_a_m);
  const Basis e = basis(j.q(0), j.q(1));
  const double l = j.q(2);
  const Vector3d w1 = j.qd(0) * z, al1 = j.qdd(0) * z;
  const Vector3d w2 = j.qd(0) * z - j.qd(1) * e.phi;
  const Vector3d al2 = j.qdd(0) * z - j.qdd(1) * e.phi + j.qd(1) * j.qd(0) * e.h;

  SphericalDynamics out;
  out.t = t;
  out.joints = j;

  // Link 3 (arm) with the payload at M: load of link 2 on link 3 at B.
  const double d3 = l - 0.5 * design.arm_length_m;
  const Vector3d s3 = b + d3 * e.r, m_point = b + l * e.r;
  const Vector3d inertia3 = v.m3_kg * (arm_point_acceleration(e, j, d3) - g);
  const Vector3d inertia_p = design.payload_kg * (arm_point_acceleration(e, j, l) - g);
  const Matrix3d i3 = axial_inertia(e.r, design.arm_inertia_axial, design.arm_inertia_transverse);
  PairLoad& p32 = out.pair32;
  p32.point_world = b;
  p32.force_world = inertia3 + inertia_p;
  p32.moment_world = (s3 - b).cross(inertia3) + (m_point - b).cross(inertia_p) + i3 * al2 + w2.cross(i3 * w2);
  p32.drive = p32.force_world.dot(e.r);
  p32.reaction_force = p32.force_world - p32.drive * e.r;
  p32.reaction_moment = p32.moment_world;

  // Link 2 (sleeve), centre of mass at B: load of link 1 on link 2 at B.
  const Matrix3d i2 = axial_inertia(e.r, design.sleeve_inertia_axial, design.sleeve_inertia_transverse);
  PairLoad& p21 = out.pair21;
  p21.point_world = b;
  p21.force_world = p32.force_world + v.m2_kg * (Vector3d::Zero() - g);
  p21.moment_world = p32.moment_world + i2 * al2 + w2.cross(i2 * w2);
  const Vector3d tilt_axis = -e.phi;
  p21.drive = p21.moment_world.dot(tilt_axis);
  p21.reaction_force = p21.force_world;
  p21.reaction_moment = p21.moment_world - p21.drive * tilt_axis;

  // Link 1 (column), centre of mass on the axis: load of the base on link 1 at A.
  const Vector3d s1(0.0, 0.0, design.column_com_height_m);
  const Vector3d inertia1 = v.m1_kg * (Vector3d::Zero() - g);
  const Matrix3d i1 = design.column_inertia_z * z * z.transpose();
  PairLoad& p10 = out.pair10;
  p10.point_world = a;
  p10.force_world = p21.force_world + inertia1;
  p10.moment_world = p21.moment_world + (b - a).cross(p21.force_world) + (s1 - a).cross(inertia1) + i1 * al1 +
                     w1.cross(i1 * w1);
  p10.drive = p10.moment_world.dot(z);
  p10.reaction_force = p10.force_world;
  p10.reaction_moment = p10.moment_world - p10.drive * z;

  out.drive_power_W = Vector3d(p10.drive * j.qd(0), p21.drive * j.qd(1), p32.drive * j.qd(2));
  out.total_power_W = out.drive_power_W.sum();
  return out;
}

Vector3d spherical_drive_efforts(const SphericalDesign& design, const SphericalJointMotion& motion) {
  const SphericalDynamics d = spherical_inverse_dynamics(design, motion);
  return {d.pair10.drive, d.pair21.drive, d.pair32.drive};
}

SphericalRun analyse_straight_line(const SphericalDesign& design, const StraightLineMotion& motion, int n) {
  require(n >= 2, "analyse_straight_line: need at least 2 intervals, got {}", n);
  std::vector<double> times = equally_spaced_times(motion.duration(), n + 1);  // ends exactly at the duration
  for (double b : motion.breakpoints()) times.push_back(b);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end(), [](double x, double y) { return std::abs(x - y) < 1e-12; }),
              times.end());
  SphericalRun run;
  for (double t : times) {
    const StraightLineMotion::Point p = motion.at(t);
    const SphericalJointMotion j = spherical_joint_motion(design, p.m, p.m_dot, p.m_ddot);
    check_service_zone(design, j.q, t);
    const SphericalDynamics d = spherical_inverse_dynamics(design, j, t);
    const Vector3d efforts(d.pair10.drive, d.pair21.drive, d.pair32.drive);
    run.peak_drive = run.peak_drive.cwiseMax(efforts.cwiseAbs());
    run.peak_power_W = run.peak_power_W.cwiseMax(d.drive_power_W.cwiseAbs());
    run.samples.push_back(d);
  }
  return run;
}

// ---- forward dynamics (CVODES) ----------------------------------------------------------

namespace {

struct ForwardProblem {
  const SphericalDesign& design;
  const StraightLineMotion& motion;
  double segment_mid = 0.0;  // efforts taken from the planned motion on this segment's side
  std::string error;
};

// Planned efforts at t; at a breakpoint the value of the current segment.
Vector3d planned_efforts(const ForwardProblem& p, double t) {
  StraightLineMotion::Point pt = p.motion.at(t);
  // The law's acceleration is piecewise constant: take it from inside the segment.
  const double inside = t + 1e-9 * (p.segment_mid - t);
  pt.m_ddot = p.motion.at(inside).m_ddot;
  return spherical_drive_efforts(p.design, spherical_joint_motion(p.design, pt.m, pt.m_dot, pt.m_ddot));
}

int forward_rhs(double t, N_Vector yy, N_Vector ydot, void* user_data) {
  auto* p = static_cast<ForwardProblem*>(user_data);
  try {
    const double* y = N_VGetArrayPointer(yy);
    double* f = N_VGetArrayPointer(ydot);
    SphericalJointMotion j;
    j.q = Vector3d(y[0], y[1], y[2]);
    j.qd = Vector3d(y[3], y[4], y[5]);
    // M(q) q'' + h(q, q') = tau: h from the inverse dynamics with q'' = 0, the
    // columns of M from unit accelerations at rest (minus gravity).
    const Vector3d h = spherical_drive_efforts(p->design, j);
    SphericalJointMotion rest = j;
    rest.qd.setZero();
    const Vector3d gravity = spherical_drive_efforts(p->design, rest);
    Matrix3d mass;
    for (int c = 0; c < 3; ++c) {
      rest.qdd = Vector3d::Unit(c);
      mass.col(c) = spherical_drive_efforts(p->design, rest) - gravity;
    }
    const Vector3d qdd = mass.ldlt().solve(planned_efforts(*p, t) - h);
    for (int k = 0; k < 3; ++k) {
      f[k] = y[3 + k];
      f[3 + k] = qdd(k);
    }
    return 0;
  } catch (const std::exception& e) {
    p->error = e.what();
    return -1;
  }
}

}  // namespace

SphericalForwardResult spherical_forward_dynamics(const SphericalDesign& design, const StraightLineMotion& motion,
                                                  const std::vector<double>& times, double relative_tolerance) {
  require(!times.empty(), "spherical forward dynamics: no output times");
  using namespace sundials;
  ForwardProblem problem{design, motion, 0.0, {}};
  const std::vector<double> breaks = motion.breakpoints();
  Context ctx;
  Vector y(6, ctx.ctx);
  const StraightLineMotion::Point p0 = motion.at(times.front());
  const SphericalJointMotion j0 = spherical_joint_motion(design, p0.m, p0.m_dot, p0.m_ddot);
  y.map() << j0.q, j0.qd;
  CvodeMemory cvode(ctx.ctx);
  sundials_check(CVodeInit(cvode.mem, forward_rhs, times.front(), y.v), "CVodeInit");
  sundials_check(CVodeSStolerances(cvode.mem, relative_tolerance, 1e-3 * relative_tolerance), "CVodeSStolerances");
  sundials_check(CVodeSetUserData(cvode.mem, &problem), "CVodeSetUserData");
  DenseSolver dense(6, y.v, ctx.ctx);
  sundials_check(CVodeSetLinearSolver(cvode.mem, dense.solver, dense.matrix), "CVodeSetLinearSolver");
  sundials_check(CVodeSetMaxNumSteps(cvode.mem, 100000), "CVodeSetMaxNumSteps");

  SphericalForwardResult result;
  double t_now = times.front();
  auto segment_end = [&](double t) {
    for (double b : breaks)
      if (b > t + 1e-12) return b;
    return std::numeric_limits<double>::infinity();
  };
  for (double t_out : times) {
    while (t_now < t_out - 1e-14) {
      const double t_stop = std::min(t_out, segment_end(t_now));
      problem.segment_mid = 0.5 * (t_now + t_stop);
      sundials_check(CVodeSetStopTime(cvode.mem, t_stop), "CVodeSetStopTime");
      double t_reached = t_now;
      const int flag = CVode(cvode.mem, t_stop, y.v, &t_reached, CV_NORMAL);
      sundials_check(flag, "CVode", fmt::format("t = {} s{}{}", t_reached, problem.error.empty() ? "" : "; ", problem.error));
      if (std::abs(t_reached - segment_end(t_now)) < 1e-12) {
        // The efforts jump here: restart the integrator on the next segment.
        long steps = 0;
        sundials_check(CVodeGetNumSteps(cvode.mem, &steps), "CVodeGetNumSteps");
        result.steps += steps;
        sundials_check(CVodeReInit(cvode.mem, t_reached, y.v), "CVodeReInit");
      }
      t_now = t_reached;
    }
    SphericalJointMotion j;
    j.q = y.map().head<3>();
    j.qd = y.map().tail<3>();
    result.times.push_back(t_now);
    result.joints.push_back(j);
    const Vector3d planned = motion.at(t_now).m;
    result.max_path_deviation_m =
        std::max(result.max_path_deviation_m, (spherical_forward_kinematics(design, j.q) - planned).norm());
  }
  long steps = 0;
  sundials_check(CVodeGetNumSteps(cvode.mem, &steps), "CVodeGetNumSteps");
  result.steps += steps;
  return result;
}

}  // namespace kinetofem::mech
