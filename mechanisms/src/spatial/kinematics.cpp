#include "kinetofem/mechanisms/spatial/kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"
#include "scaled_jacobian.hpp"

namespace kinetofem::mech::spatial {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

// The joints and drives left with a residual above the tolerance, largest
// first (a least-squares Newton step spreads an impossible closure over all
// the rows that share it, so one name alone could mislead).
std::string open_blocks(const System& system, const VectorXd& q, double t, double tolerance) {
  const VectorXd phi = system.phi(q, t);
  std::vector<std::pair<double, std::string>> open;
  const VectorXd norms = system.norm_phi(q);
  if (norms.size() && norms.cwiseAbs().maxCoeff() > tolerance)
    open.emplace_back(norms.cwiseAbs().maxCoeff(), "(Euler-parameter norms)");
  for (const ConstraintBlock& blk : system.blocks()) {
    const double r = phi.segment(blk.first_row, blk.rows).cwiseAbs().maxCoeff();
    if (r > tolerance) open.emplace_back(r, blk.name);
  }
  std::sort(open.begin(), open.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::string text;
  for (const auto& [r, name] : open) text += fmt::format("{}'{}' (residual {:.3e})", text.empty() ? "" : ", ", name, r);
  return text;
}

}  // namespace

VectorXd assemble(const System& system, VectorXd q, double t, const KinematicOptions& options) {
  const int m = system.n_constraints(), nb = system.n_moving(), n = system.n_positions();
  const double tol = options.tolerance * system.characteristic_length();
  for (int it = 0; it < options.max_iterations; ++it) {
    if (system.position_drift_m(q, t) <= tol) return q;
    MatrixXd jac(m + nb, n);
    jac << system.jacobian_q(q, t), system.norm_jacobian(q);
    VectorXd res(m + nb);
    res << system.phi(q, t), system.norm_phi(q);
    Eigen::CompleteOrthogonalDecomposition<MatrixXd> cod(jac);
    q -= cod.solve(res);
  }
  if (system.position_drift_m(q, t) <= tol) return q;
  fail("spatial model '{}' cannot be assembled at t = {} s: after {} Newton iterations these stay open: {}",
       system.model().name, t, options.max_iterations, open_blocks(system, q, t, tol));
}

VectorXd solve_velocities(const System& system, const VectorXd& q, double t, const VectorXd& v_guess) {
  // min |v - v_guess|_M with Pi v = nu: in x = C^T v, x = x_g + pinv(Pi~) (nu - Pi~ x_g).
  const ScaledJacobian scaled(system, q, t);
  VectorXd x = scaled.to_scaled(v_guess);
  if (system.n_constraints() > 0) x += scaled.pinv.transpose() * (system.nu(q, t) - scaled.pi_scaled * x);
  return scaled.to_velocity(x);
}

int degrees_of_freedom(const System& system, const VectorXd& q, double t) {
  return system.n_velocities() - ScaledJacobian(system, q, t).rank;
}

Results run_kinematics(const System& system, const std::vector<double>& times, const KinematicOptions& options) {
  require(!times.empty(), "spatial kinematics: no output times");
  VectorXd q = assemble(system, system.initial_positions(), times.front(), options);
  const int dof = degrees_of_freedom(system, q, times.front());
  require(dof == 0, "spatial kinematics of '{}': the mechanism has {} degrees of freedom at t = {} s, needs 0 (drive them)",
          system.model().name, dof, times.front());
  VectorXd v = solve_velocities(system, q, times.front(), VectorXd::Zero(system.n_velocities()));
  Results results;
  results.summary.method = "kinematic";
  for (std::size_t k = 0; k < times.size(); ++k) {
    if (k > 0) {
      const double dt = times[k] - times[k - 1];
      require(dt > 0.0, "spatial kinematics: output times must increase, times[{}] = {}", k, times[k]);
      q = assemble(system, q + dt * system.position_rates(q, v), times[k], options);
      v = solve_velocities(system, q, times[k], v);
    }
    results.frames.push_back(make_frame(system, times[k], q, v));
  }
  summarize(system, results);
  return results;
}

}  // namespace kinetofem::mech::spatial
