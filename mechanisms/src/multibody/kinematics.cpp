#include "kinetofem/mechanisms/multibody/kinematics.hpp"

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// max |Phi| with angle rows times the characteristic length.
double scaled_residual(const MultibodySystem& system, const VectorXd& q, double t) {
  return system.position_drift_m(q, t);
}

std::string body_poses(const MultibodySystem& system, const VectorXd& q) {
  std::string out;
  for (int b = 0; b < system.n_bodies(); ++b) {
    if (system.offset(b) < 0) continue;
    const Eigen::Vector3d p = system.origin_pose(b, q);
    out += fmt::format("{}{} ({:.6g} m, {:.6g} m, {:.6g} deg)", out.empty() ? "" : ", ", system.model().bodies[b].name,
                       p.x(), p.y(), p.z() * 180.0 / M_PI);
  }
  return out;
}

}  // namespace

VectorXd assemble(const MultibodySystem& system, VectorXd q, double t, const KinematicOptions& options) {
  const double tol = options.tolerance * system.characteristic_length();
  if (system.n_constraints() == 0) return q;
  double residual = scaled_residual(system, q, t);
  for (int it = 0; it < options.max_iterations && residual > tol; ++it) {
    const MatrixXd jac = system.jacobian(q, t);
    const VectorXd step = jac.completeOrthogonalDecomposition().solve(system.phi(q, t));
    if (!step.allFinite()) break;
    q -= step;
    residual = scaled_residual(system, q, t);
  }
  if (!(residual <= tol))
    fail("mechanism '{}' cannot be assembled at t = {} s, residual {:.3e} m after {} Newton iterations (near: {})",
         system.model().name, t, residual, options.max_iterations, body_poses(system, q));
  return q;
}

VectorXd solve_velocities(const MultibodySystem& system, const VectorXd& q, double t, const VectorXd& guess) {
  if (system.n_constraints() == 0) return guess;
  const MatrixXd jac = system.jacobian(q, t);
  const VectorXd mismatch = jac * guess - system.nu(q, t);
  const MatrixXd jjt = jac * jac.transpose();
  return guess - jac.transpose() * jjt.ldlt().solve(mismatch);
}

Accelerations solve_accelerations(const MultibodySystem& system, const VectorXd& q, const VectorXd& qd, double t) {
  const int n = system.n_coordinates(), m = system.n_constraints();
  MatrixXd a = MatrixXd::Zero(n + m, n + m);
  a.topLeftCorner(n, n) = system.mass_diagonal().asDiagonal();
  const MatrixXd jac = system.jacobian(q, t);
  a.topRightCorner(n, m) = jac.transpose();
  a.bottomLeftCorner(m, n) = jac;
  VectorXd rhs(n + m);
  rhs.head(n) = system.applied_forces(q, qd, t);
  rhs.tail(m) = system.gamma(q, qd, t);
  const Eigen::FullPivLU<MatrixXd> lu(a);
  require(lu.isInvertible(),
          "mechanism '{}': the acceleration system is singular at t = {} s (a massless body that is not fully "
          "constrained, redundant constraints or a singular position)",
          system.model().name, t);
  const VectorXd x = lu.solve(rhs);
  return {x.head(n), x.tail(m)};
}

double jacobian_condition(const MultibodySystem& system, const VectorXd& q, double t) {
  if (system.n_constraints() == 0) return 1.0;
  const Eigen::JacobiSVD<MatrixXd> svd(system.jacobian(q, t));
  const VectorXd& s = svd.singularValues();
  const Eigen::Index k = std::min<Eigen::Index>(s.size(), system.n_constraints()) - 1;
  if (s(k) <= 0.0) return std::numeric_limits<double>::infinity();
  return s(0) / s(k);
}

void check_regular(const MultibodySystem& system, const VectorXd& q, double t, double singular_tolerance) {
  const double cond = jacobian_condition(system, q, t);
  if (!(cond * singular_tolerance < 1.0))
    fail("mechanism '{}': singular position at t = {} s (constraint Jacobian loses rank, condition {:.3e}; dead "
         "centre or limit of assembly) at {}",
         system.model().name, t, cond, body_poses(system, q));
}

int degrees_of_freedom(const MultibodySystem& system, const VectorXd& q, double t) {
  if (system.n_constraints() == 0) return system.n_coordinates();
  Eigen::FullPivLU<MatrixXd> lu(system.jacobian(q, t));
  lu.setThreshold(1e-10);
  return system.n_coordinates() - static_cast<int>(lu.rank());
}

Results run_kinematics(const MultibodySystem& system, const std::vector<double>& times,
                       const KinematicOptions& options) {
  require(!times.empty(), "run_kinematics: no output times");
  Results results;
  results.summary.method = "kinematic (prescribed motion, kinetostatics)";
  VectorXd q = system.initial_coordinates();
  VectorXd qd = VectorXd::Zero(system.n_coordinates());
  const int dof = degrees_of_freedom(system, assemble(system, q, times.front(), options), times.front());
  require(dof == 0, "mechanism '{}': a prescribed-motion run needs 0 degrees of freedom, the model has {}",
          system.model().name, dof);
  const FrameOptions frame_options{options.singular_tolerance, options.slack_is_error};
  double t_prev = times.front(), work = 0.0, power_prev = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    if (k > 0) q += qd * (t - t_prev);  // predictor
    try {
      q = assemble(system, q, t, options);
    } catch (const Error& e) {
      if (k == 0) throw;
      // Name the bracket: the limit of assembly or dead centre lies between the
      // last assembled time and this one.
      fail("{} (last assembled at t = {} s with constraint Jacobian condition {:.3e}: a limit of assembly or dead "
           "centre lies in between)",
           e.what(), t_prev, results.frames.back().jacobian_condition);
    }
    check_regular(system, q, t, options.singular_tolerance);
    qd = solve_velocities(system, q, t, qd);
    Frame frame = make_frame(system, t, q, qd, frame_options, &results.summary);
    double power = 0.0;
    for (const DriveFrame& d : frame.drives) power += d.power_W;
    if (k > 0) work += 0.5 * (power + power_prev) * (t - t_prev);
    frame.work_drives_J = work;
    power_prev = power;
    t_prev = t;
    results.frames.push_back(std::move(frame));
  }
  summarize(system, results);
  return results;
}

}  // namespace kinetofem::mech
