#include "kinetofem/mechanisms/multibody/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

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

// Largest change of any coordinate between q_from and q_to: angles in rad,
// positions as a fraction of the characteristic length.
double scaled_change(const MultibodySystem& system, const VectorXd& q_from, const VectorXd& q_to) {
  double change = 0.0;
  const double length = system.characteristic_length();
  for (Eigen::Index i = 0; i < q_from.size(); ++i) {
    const double d = std::abs(q_to(i) - q_from(i));
    change = std::max(change, i % 3 == 2 ? d : d / length);
  }
  return change;
}

// Why [M Phi_q^T; Phi_q 0] is singular: redundant constraints or a singular
// position (Phi_q loses rank), else bodies without mass or inertia that the
// constraints do not hold.
std::string singular_acceleration_cause(const MultibodySystem& system, const MatrixXd& jac, const VectorXd& mass,
                                        double t) {
  const std::string head =
      fmt::format("mechanism '{}': the acceleration system is singular at t = {} s", system.model().name, t);
  Eigen::FullPivLU<MatrixXd> lu_jac(jac);
  lu_jac.setThreshold(1e-10);
  if (lu_jac.rank() < jac.rows())
    return fmt::format("{}: the constraint Jacobian has rank {} of {} rows (redundant constraints or a singular "
                       "position)",
                       head, lu_jac.rank(), jac.rows());
  std::string unheld;
  for (int b = 0; b < system.n_bodies(); ++b) {
    const int o = system.offset(b);
    if (o < 0 || (mass(o) > 0.0 && mass(o + 2) > 0.0)) continue;
    unheld += fmt::format("{}'{}' ({:g} kg, {:g} kg*m^2)", unheld.empty() ? "" : ", ", system.model().bodies[b].name,
                          mass(o), mass(o + 2));
  }
  if (!unheld.empty())
    return fmt::format("{}: bodies with no mass or no inertia that the constraints do not hold: {}", head, unheld);
  return fmt::format("{} (the constraint Jacobian has full rank and every body has mass and inertia)", head);
}

// Largest change of the motion drives' coordinates from their values at t over
// [t, t + step] and their largest rate there (rad and rad/s, or fractions of the
// characteristic length), sampled at 17 points: the endpoints of a step alone
// miss a drive that goes out and comes back within it.
struct DriveSweep {
  double change = 0.0, rate = 0.0;
};

DriveSweep drive_sweep(const MultibodySystem& system, double t, double step) {
  constexpr int kSamples = 16;
  DriveSweep out;
  for (const ConstraintBlock& blk : system.blocks()) {
    if (blk.kind != ConstraintKind::Drive || blk.law == nullptr) continue;
    const double scale = blk.coordinate == CoordinateType::Angle ? 1.0 : 1.0 / system.characteristic_length();
    const double s0 = blk.law->at(t).s;
    for (int i = 0; i <= kSamples; ++i) {
      const MotionState m = blk.law->at(t + step * i / kSamples);
      out.change = std::max(out.change, scale * std::abs(m.s - s0));
      out.rate = std::max(out.rate, scale * std::abs(m.s_dot));
    }
  }
  return out;
}

}  // namespace

void follow_assembly(const MultibodySystem& system, VectorXd& q, VectorXd& qd, double t_from, double t_to,
                     const KinematicOptions& options, long& substeps) {
  // Continuation in time: a pose is only accepted when it lies within
  // max_substep of the previous one, so that Newton cannot land on another
  // assembly branch (the mirror image of a slider-crank or four-bar) however far
  // apart the output times are. The next step starts from the rate of the last
  // one; a rejected step is halved.
  const double span = t_to - t_from;
  const double min_step = std::max(1e-9 * span, 64.0 * std::numeric_limits<double>::epsilon() *
                                                    std::max(std::abs(t_from), std::abs(t_to)));
  double t = t_from;
  // Steps aim at half the largest change, so that the curvature of the path
  // seldom makes one too long.
  const double aim = 0.5 * options.max_substep;
  double rate = std::max(scaled_change(system, VectorXd::Zero(q.size()), qd),
                         drive_sweep(system, t_from, span).rate);  // per second
  double h = rate > 0.0 ? std::min(span, aim / rate) : span;
  while (t < t_to) {
    if (++substeps > options.max_substeps)
      fail("mechanism '{}': the motion is too large to follow: more than {} substeps (each moving the linkage by at "
           "most {} rad, or {} of the characteristic length {:.6g} m) by t = {} s; check the motion law's speed and "
           "stroke",
           system.model().name, options.max_substeps, options.max_substep, options.max_substep,
           system.characteristic_length(), t);
    h = std::max(h, min_step);
    const bool last = h >= t_to - t;
    const double t_next = last ? t_to : t + h;
    const double step = t_next - t;
    std::string reason;
    VectorXd q_next;
    const DriveSweep sweep = drive_sweep(system, t, step);
    if (sweep.change > options.max_substep) {
      reason = fmt::format("the motion drives move by {:.3g} (rad, or times the characteristic length {:.6g} m) in "
                           "{:.3e} s",
                           sweep.change, system.characteristic_length(), step);
    } else {
      try {
        q_next = assemble(system, q + qd * step, t_next, options);
        const double change = scaled_change(system, q, q_next);
        if (change > options.max_substep)
          reason = fmt::format("the pose moves by {:.3g} (rad, or times the characteristic length {:.6g} m) in {:.3e} s",
                               change, system.characteristic_length(), step);
      } catch (const Error& e) {
        reason = e.what();
      }
    }
    if (reason.empty()) {
      check_regular(system, q_next, t_next, options.singular_tolerance);
      const VectorXd qd_next = solve_velocities(system, q_next, t_next, qd);
      q = q_next;
      qd = qd_next;
      t = t_next;
      rate = std::max(scaled_change(system, VectorXd::Zero(q.size()), qd), sweep.rate);
      h = 2.0 * step;
      if (rate > 0.0) h = std::min(h, aim / rate);
      continue;
    }
    if (step <= min_step)
      fail("mechanism '{}': the assembly cannot be followed from t = {} s to t = {} s ({}; last assembled at t = {} s "
           "with constraint Jacobian condition {:.3e}: a limit of assembly, dead centre or branch point lies in between)",
           system.model().name, t_from, t_to, reason, t, jacobian_condition(system, q, t));
    h = 0.5 * step;
  }
}

VectorXd assemble(const MultibodySystem& system, VectorXd q, double t, const KinematicOptions& options) {
  if (system.n_constraints() == 0) return q;
  // An angle row's residual cannot fall below the round-off of the angles it
  // compares: a crank after 300 turns (1900 rad) carries 4e-13 rad of it, more
  // than the tolerance times a link length.
  double largest_angle = 1.0;
  for (Eigen::Index i = 2; i < q.size(); i += 3) largest_angle = std::max(largest_angle, std::abs(q(i)));
  const double tol = system.characteristic_length() *
                     std::max(options.tolerance, 16.0 * std::numeric_limits<double>::epsilon() * largest_angle);
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
  // Solved scaled: a = D x, lambda = S mu with D = M^(-1/2) (1 where a
  // coordinate has no mass) and S making each row of Phi_q D of unit size, so
  // that the mass block is the identity. Unscaled, a body of 1e300 kg next to
  // one of 1 kg makes every constraint row look like round-off, and the system
  // singular.
  const VectorXd mass = system.mass_diagonal();
  const VectorXd d = mass.unaryExpr([](double mi) { return mi > 0.0 ? 1.0 / std::sqrt(mi) : 1.0; });
  const MatrixXd jac = system.jacobian(q, t);
  const MatrixXd jac_d = jac * d.asDiagonal();
  VectorXd s = VectorXd::Ones(m);
  for (int r = 0; r < m; ++r) {
    const double row = jac_d.row(r).cwiseAbs().maxCoeff();
    if (row > 0.0) s(r) = 1.0 / row;
  }
  MatrixXd a = MatrixXd::Zero(n + m, n + m);
  a.topLeftCorner(n, n) = mass.cwiseProduct(d).cwiseProduct(d).asDiagonal();
  a.bottomLeftCorner(m, n) = s.asDiagonal() * jac_d;
  a.topRightCorner(n, m) = a.bottomLeftCorner(m, n).transpose();
  VectorXd rhs(n + m);
  rhs.head(n) = d.cwiseProduct(system.applied_forces(q, qd, t));
  rhs.tail(m) = s.cwiseProduct(system.gamma(q, qd, t));
  const Eigen::FullPivLU<MatrixXd> lu(a);
  if (!lu.isInvertible()) fail("{}", singular_acceleration_cause(system, jac, mass, t));
  const VectorXd x = lu.solve(rhs);
  return {d.cwiseProduct(x.head(n)), s.cwiseProduct(x.tail(m))};
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
  // The budget of substeps comes on top of one substep per output interval.
  KinematicOptions follow = options;
  follow.max_substeps += static_cast<long>(times.size());
  long substeps = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    if (k == 0) {
      q = assemble(system, q, t, options);
      check_regular(system, q, t, options.singular_tolerance);
      qd = solve_velocities(system, q, t, qd);
    } else {
      require(t > t_prev, "run_kinematics: output times must increase, t = {} s after {} s", t, t_prev);
      follow_assembly(system, q, qd, t_prev, t, follow, substeps);
    }
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
