#include "kinetofem/mechanisms/spatial/results.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "scaled_jacobian.hpp"

namespace kinetofem::mech::spatial {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

// A block's local velocities (12: body i's (r', w), body j's), zero for a fixed body.
Eigen::Matrix<double, 12, 1> gather(const System& system, const ConstraintBlock& blk, const VectorXd& v) {
  Eigen::Matrix<double, 12, 1> local = Eigen::Matrix<double, 12, 1>::Zero();
  const int ki = system.moving_index(blk.body_i), kj = system.moving_index(blk.body_j);
  if (ki >= 0) local.head<6>() = v.segment<6>(6 * ki);
  if (kj >= 0) local.tail<6>() = v.segment<6>(6 * kj);
  return local;
}

Reaction reaction(const System& system, int body, const Vector3d& s_body, const Eigen::Matrix<double, 6, 1>& load,
                  const VectorXd& q) {
  Reaction r;
  r.body = system.model().bodies[body].name;
  const Matrix3d a = system.rotation(body, q);
  const Vector3d arm = a * s_body;  // joint point from the centre of mass
  r.point_world = system.com(body, q) + arm;
  r.force_world = load.head<3>();
  r.moment_world = a * load.tail<3>() - arm.cross(r.force_world);
  return r;
}

}  // namespace

IndexOneSolution solve_index_one(const System& system, const VectorXd& q, const VectorXd& v, double t) {
  const int m = system.n_constraints();
  const ScaledJacobian scaled(system, q, t);
  // In x = C^T v': x + Pi~^T lambda = C^-1 (Q - h), Pi~ x = gamma, so
  // (Pi~ Pi~^T) lambda = Pi~ C^-1 (Q - h) - gamma; its minimum-norm solution is
  // P P^T (...) (scaled_jacobian.hpp). A redundant row makes Pi~ Pi~^T singular,
  // and this gives the minimum-norm multipliers with the unique v'.
  const VectorXd f = scaled.scaled_force(system.forces(q, v, t));
  const VectorXd gamma = system.gamma(q, v, t);
  IndexOneSolution s;
  s.lambda = m > 0 ? VectorXd(scaled.pinv * (scaled.pinv.transpose() * (scaled.pi_scaled * f - gamma)))
                   : VectorXd();
  const VectorXd x = m > 0 ? VectorXd(f - scaled.pi_scaled.transpose() * s.lambda) : f;
  s.v_dot = scaled.to_velocity(x);
  s.redundant_rows = m - scaled.rank;
  // Redundant rows whose right-hand sides disagree leave Pi v' != gamma.
  const VectorXd row_residual = m > 0 ? VectorXd((scaled.pi_scaled * x - gamma).cwiseAbs()) : VectorXd();
  const double residual = m > 0 ? row_residual.maxCoeff() : 0.0;
  const double scale = std::max(1.0, m > 0 ? gamma.cwiseAbs().maxCoeff() + (scaled.pi_scaled * f).cwiseAbs().maxCoeff() : 0.0);
  if (!(residual <= 1e-6 * scale)) {
    // The joints and drives whose rows are left unsatisfied: those that disagree.
    std::string named;
    for (const ConstraintBlock& blk : system.blocks())
      if (row_residual.segment(blk.first_row, blk.rows).maxCoeff() > 1e-6 * scale)
        named += fmt::format("{}'{}'", named.empty() ? "" : ", ", blk.name);
    fail("spatial model '{}' at t = {} s: the acceleration equations are inconsistent (residual {:.3e}) in {}: "
         "redundant constraints that disagree, or a singular position",
         system.model().name, t, residual, named);
  }
  return s;
}

Frame make_frame(const System& system, double t, const VectorXd& q, const VectorXd& v) {
  const Model& model = system.model();
  const IndexOneSolution sol = solve_index_one(system, q, v, t);
  Frame f;
  f.t = t;
  f.q = q;
  f.v = v;
  f.v_dot = sol.v_dot;
  f.lambda = sol.lambda;
  f.redundant_rows = sol.redundant_rows;
  for (int b = 0; b < system.n_bodies(); ++b) {
    BodyState s;
    s.name = model.bodies[b].name;
    s.euler_parameters = system.euler_parameters(b, q);
    s.rotation = system.rotation(b, q);
    s.com = system.com(b, q);
    s.origin = s.com - s.rotation * system.effective(b).com_body;
    s.com_velocity = system.com_velocity(b, v);
    s.angular_velocity = s.rotation * system.angular_velocity_body(b, v);
    s.com_acceleration = system.com_velocity(b, sol.v_dot);
    // d(A w)/dt = A (w x w) + A w' = A w'.
    s.angular_acceleration = s.rotation * system.angular_velocity_body(b, sol.v_dot);
    f.bodies.push_back(std::move(s));
  }
  for (const ConstraintBlock& blk : system.blocks()) {
    const BlockValues b = system.evaluate(blk, q, v, t);
    const VectorXd lam = sol.lambda.segment(blk.first_row, blk.rows);
    const Eigen::Matrix<double, 12, 1> load = -b.pi.transpose() * lam;
    switch (blk.kind) {
      case BlockKind::Joint: {
        JointState j;
        j.name = blk.name;
        j.type = blk.joint;
        j.on_i = reaction(system, blk.body_i, blk.s_i, load.head<6>(), q);
        j.on_j = reaction(system, blk.body_j, blk.s_j, load.tail<6>(), q);
        f.joints.push_back(std::move(j));
        break;
      }
      case BlockKind::Drive: {
        DriveState d;
        d.name = blk.name;
        const MotionState law = blk.law->at(t);
        d.s = blk.reference + law.s + b.phi(0);
        d.s_dot = b.pi.row(0).dot(gather(system, blk, v));
        // gamma = law'' - quadratic term, so s'' = Pi v' + law'' - gamma.
        d.s_ddot = b.pi.row(0).dot(gather(system, blk, sol.v_dot)) + law.s_ddot - b.gamma(0);
        d.effort = -lam(0);
        d.on_i = reaction(system, blk.body_i, blk.s_i, load.head<6>(), q);
        d.on_j = reaction(system, blk.body_j, blk.s_j, load.tail<6>(), q);
        f.drives.push_back(std::move(d));
        break;
      }
    }
  }
  f.kinetic_energy_J = system.kinetic_energy(v);
  f.potential_energy_J = system.potential_energy(q);
  f.drift_position_m = system.position_drift_m(q, t);
  f.drift_velocity_m_per_s = system.velocity_drift_m_per_s(q, v, t);
  const VectorXd applied = system.forces(q, v, t);
  const VectorXd constraint = system.jacobian_v(q, t).transpose() * sol.lambda;
  const VectorXd inertia = system.mass_matrix() * sol.v_dot;
  const double scale = std::max({applied.size() ? applied.cwiseAbs().maxCoeff() : 0.0,
                                 constraint.size() ? constraint.cwiseAbs().maxCoeff() : 0.0,
                                 inertia.size() ? inertia.cwiseAbs().maxCoeff() : 0.0, 1e-300});
  f.equilibrium_residual = applied.size() ? (inertia + constraint - applied).cwiseAbs().maxCoeff() / scale : 0.0;
  return f;
}

void summarize(const System& system, Results& results) {
  RunSummary& s = results.summary;
  for (const Frame& f : results.frames) {
    s.max_drift_position_m = std::max(s.max_drift_position_m, f.drift_position_m);
    s.max_drift_velocity_m_per_s = std::max(s.max_drift_velocity_m_per_s, f.drift_velocity_m_per_s);
    s.max_equilibrium_residual = std::max(s.max_equilibrium_residual, f.equilibrium_residual);
  }
  s.max_drift_relative = s.max_drift_position_m / system.characteristic_length();
  if (!results.frames.empty()) s.redundant_rows = results.frames.front().redundant_rows;
}

std::string Results::format_checks() const {
  const RunSummary& s = summary;
  std::string text = fmt::format("  {}: {} frames, redundant rows {}\n", s.method, frames.size(), s.redundant_rows);
  if (!s.dropped_rows.empty()) {
    text += "  rows left out of the integration:";
    for (std::size_t k = 0; k < s.dropped_rows.size(); ++k) text += (k == 0 ? " " : ", ") + s.dropped_rows[k];
    text += "\n";
  }
  text += fmt::format("  drift: position {:.3e} m ({:.3e} of the characteristic length), velocity {:.3e} m/s\n",
                      s.max_drift_position_m, s.max_drift_relative, s.max_drift_velocity_m_per_s);
  text += fmt::format("  equilibrium residual {:.3e}\n", s.max_equilibrium_residual);
  if (s.steps > 0)
    text += fmt::format("  solver: {} steps, {} residual evaluations, {} error-test and {} nonlinear failures\n",
                        s.steps, s.residual_evaluations, s.error_test_failures, s.nonlinear_failures);
  return text;
}

}  // namespace kinetofem::mech::spatial
