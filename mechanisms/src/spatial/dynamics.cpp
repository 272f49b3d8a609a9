#include "kinetofem/mechanisms/spatial/dynamics.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <idas/idas.h>
#include <idas/idas_ls.h>

#include "../multibody/sundials_objects.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/sundials_check.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "scaled_jacobian.hpp"

namespace kinetofem::mech::spatial {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

namespace sun = kinetofem::mech::sundials;

struct GglProblem {
  const System& system;
  std::vector<int> kept;  // independent joint and drive rows
  int n_q = 0, n_v = 0, m = 0, nb = 0;
  MatrixXd mass;
  std::string error;
};

// Phi, Phi_q, Pi and nu of the kept rows.
struct KeptRows {
  VectorXd phi, nu;
  MatrixXd jq, pi;
};

KeptRows kept_rows(const GglProblem& p, const VectorXd& q, double t) {
  const System& sys = p.system;
  const int m_all = sys.n_constraints();
  VectorXd phi(m_all), nu(m_all);
  MatrixXd jq = MatrixXd::Zero(m_all, p.n_q), pi = MatrixXd::Zero(m_all, p.n_v);
  const VectorXd v0 = VectorXd::Zero(p.n_v);
  for (const ConstraintBlock& blk : sys.blocks()) {
    const BlockValues b = sys.evaluate(blk, q, v0, t);
    phi.segment(blk.first_row, blk.rows) = b.phi;
    nu.segment(blk.first_row, blk.rows) = b.nu;
    sys.scatter_q(blk, b.jq, jq.middleRows(blk.first_row, blk.rows));
    sys.scatter_v(blk, b.pi, pi.middleRows(blk.first_row, blk.rows));
  }
  KeptRows k;
  k.phi = phi(p.kept);
  k.nu = nu(p.kept);
  k.jq = jq(p.kept, Eigen::all);
  k.pi = pi(p.kept, Eigen::all);
  return k;
}

int ggl_residual(double t, N_Vector yy, N_Vector yp, N_Vector rr, void* user_data) {
  auto* p = static_cast<GglProblem*>(user_data);
  try {
    const int nq = p->n_q, nv = p->n_v, m = p->m, nb = p->nb;
    const int size = nq + nv + m + m + nb;
    const Eigen::Map<const VectorXd> y(N_VGetArrayPointer(yy), size);
    const Eigen::Map<const VectorXd> yd(N_VGetArrayPointer(yp), size);
    Eigen::Map<VectorXd> r(N_VGetArrayPointer(rr), size);
    const VectorXd q = y.head(nq), v = y.segment(nq, nv);
    const VectorXd lambda = y.segment(nq + nv, m), mu = y.tail(m + nb);
    const KeptRows k = kept_rows(*p, q, t);
    MatrixXd jq_all(m + nb, nq);
    jq_all << k.jq, p->system.norm_jacobian(q);
    r.head(nq) = yd.head(nq) - p->system.position_rates(q, v) + jq_all.transpose() * mu;
    r.segment(nq, nv) = p->mass * yd.segment(nq, nv) + k.pi.transpose() * lambda - p->system.forces(q, v, t);
    r.segment(nq + nv, m) = k.phi;
    r.segment(nq + nv + m, nb) = p->system.norm_phi(q);
    r.tail(m) = k.pi * v - k.nu;
    return 0;
  } catch (const std::exception& e) {
    p->error = e.what();
    return -1;
  }
}

void require_times(const std::vector<double>& times) {
  require(times.size() >= 2, "spatial dynamics: need at least two output times, got {}", times.size());
  for (std::size_t k = 1; k < times.size(); ++k)
    require(times[k] > times[k - 1], "spatial dynamics: output times must increase, times[{}] = {} after {}", k,
            times[k], times[k - 1]);
}

}  // namespace

Results simulate_ggl(const System& system, const std::vector<double>& times, const DynamicsOptions& options) {
  require_times(times);
  const double t0 = times.front();
  const VectorXd q0 = assemble(system, system.initial_positions(), t0);
  const VectorXd v0 = solve_velocities(system, q0, t0, system.initial_velocities());

  // An independent row set: column-pivoting QR of Pi~^T (the mass-metric
  // Jacobian, scaled_jacobian.hpp) at the initial state.
  const MatrixXd pi0 = system.jacobian_v(q0, t0);
  std::vector<int> kept;
  if (pi0.rows() > 0) {
    const ScaledJacobian scaled(system, q0, t0, options.rank_tolerance);
    Eigen::ColPivHouseholderQR<MatrixXd> qr(scaled.pi_scaled.transpose());
    qr.setThreshold(options.rank_tolerance);
    for (Eigen::Index c = 0; c < qr.rank(); ++c) kept.push_back(static_cast<int>(qr.colsPermutation().indices()(c)));
    std::sort(kept.begin(), kept.end());
  }
  GglProblem problem{system, kept, system.n_positions(), system.n_velocities(), static_cast<int>(kept.size()),
                     system.n_moving(), system.mass_matrix(), {}};
  const int nq = problem.n_q, nv = problem.n_v, m = problem.m, nb = problem.nb;
  const int size = nq + nv + m + m + nb;

  Results results;
  results.summary.method = "IDAS GGL index-2";
  Frame first = make_frame(system, t0, q0, v0);
  const VectorXd v_dot0 = first.v_dot;
  // The kept rows' multipliers carry the whole constraint load M v' - (Q - h):
  // least squares on Pi_kept^T (exact, v' being consistent), not the
  // minimum-norm set over all rows restricted to the kept ones.
  const MatrixXd pi_kept = pi0(kept, Eigen::all);
  const VectorXd load0 = system.forces(q0, v0, t0) - system.mass_matrix() * v_dot0;
  const VectorXd lambda0 =
      kept.empty() ? VectorXd() : VectorXd(pi_kept.transpose().colPivHouseholderQr().solve(load0));
  results.frames.push_back(std::move(first));

  sun::Context ctx;
  sun::Vector y(size, ctx.ctx), yp(size, ctx.ctx), id(size, ctx.ctx), tolerances(size, ctx.ctx);
  y.map() << q0, v0, lambda0, VectorXd::Zero(m + nb);
  const VectorXd q_dot0 = system.position_rates(q0, v0);
  yp.map() << q_dot0, v_dot0, VectorXd::Zero(m + m + nb);
  id.map() << VectorXd::Ones(nq + nv), VectorXd::Zero(m + m + nb);

  sun::IdaMemory ida(ctx.ctx);
  sundials_check(IDAInit(ida.mem, ggl_residual, t0, y.v, yp.v), "IDAInit");
  const VectorXd forces0 = system.forces(q0, v0, t0);
  const double force_scale = std::max({lambda0.size() ? lambda0.cwiseAbs().maxCoeff() : 0.0,
                                       forces0.size() ? forces0.cwiseAbs().maxCoeff() : 0.0, 1e-6});
  tolerances.map() << VectorXd::Constant(nq + nv, options.absolute_tolerance),
      VectorXd::Constant(m + m + nb, options.multiplier_relative_tolerance * force_scale);
  sundials_check(IDASVtolerances(ida.mem, options.relative_tolerance, tolerances.v), "IDASVtolerances");
  sundials_check(IDASetUserData(ida.mem, &problem), "IDASetUserData");
  sun::DenseSolver dense(size, y.v, ctx.ctx);
  sundials_check(IDASetLinearSolver(ida.mem, dense.solver, dense.matrix), "IDASetLinearSolver");
  sundials_check(IDASetId(ida.mem, id.v), "IDASetId");
  sundials_check(IDASetSuppressAlg(ida.mem, SUNTRUE), "IDASetSuppressAlg");
  sundials_check(IDASetMaxNumSteps(ida.mem, options.max_steps), "IDASetMaxNumSteps");
  if (options.max_step_s > 0.0) sundials_check(IDASetMaxStep(ida.mem, options.max_step_s), "IDASetMaxStep");
  // First step: the change 0.5 h^2 q'' of the positions is a quarter of their
  // tolerance (IDAS's own first step bounds h q' and is tiny from rest; the
  // planar core's rule, multibody/dynamics.hpp), within [1e-9, 1e-3] of the
  // first output interval.
  double first_step = options.initial_step_s;
  if (first_step <= 0.0) {
    const double interval = times[1] - t0;
    VectorXd q_ddot = system.position_rates(q0, v_dot0);
    double worst = 0.0;
    for (int i = 0; i < nq; ++i)
      worst = std::max(worst, std::abs(q_ddot(i)) /
                                  (options.relative_tolerance * std::abs(q0(i)) + options.absolute_tolerance));
    first_step = worst > 0.0 ? 0.5 * std::sqrt(2.0 / worst) : 1e-3 * interval;
    first_step = std::clamp(first_step, 1e-9 * interval, 1e-3 * interval);
  }
  sundials_check(IDASetInitStep(ida.mem, first_step), "IDASetInitStep");

  for (std::size_t k = 1; k < times.size(); ++k) {
    double t_reached = times[k - 1];
    const int flag = IDASolve(ida.mem, times[k], &t_reached, y.v, yp.v, IDA_NORMAL);
    if (flag < 0)
      sundials_check(flag, "IDASolve",
                     fmt::format("t = {} s of spatial model '{}'{}{}", t_reached, system.model().name,
                                 problem.error.empty() ? "" : ": ", problem.error));
    const VectorXd q = y.map().head(nq), v = y.map().segment(nq, nv);
    results.frames.push_back(make_frame(system, t_reached, q, v));
  }
  RunSummary& s = results.summary;
  for (const ConstraintBlock& blk : system.blocks())
    for (int r = 0; r < blk.rows; ++r)
      if (!std::binary_search(kept.begin(), kept.end(), blk.first_row + r))
        s.dropped_rows.push_back(fmt::format("'{}' row {} of {}", blk.name, r + 1, blk.rows));
  long value = 0;
  sundials_check(IDAGetNumSteps(ida.mem, &s.steps), "IDAGetNumSteps");
  sundials_check(IDAGetNumResEvals(ida.mem, &s.residual_evaluations), "IDAGetNumResEvals");
  sundials_check(IDAGetNumErrTestFails(ida.mem, &s.error_test_failures), "IDAGetNumErrTestFails");
  sundials_check(IDAGetNumNonlinSolvConvFails(ida.mem, &value), "IDAGetNumNonlinSolvConvFails");
  s.nonlinear_failures = value;
  summarize(system, results);
  return results;
}

}  // namespace kinetofem::mech::spatial
