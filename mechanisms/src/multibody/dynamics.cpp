#include "kinetofem/mechanisms/multibody/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>
#include <cvodes/cvodes.h>
#include <cvodes/cvodes_ls.h>
#include <idas/idas.h>
#include <idas/idas_ls.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/sundials_check.hpp"
#include "sundials_objects.hpp"

namespace kinetofem::mech {

using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

using sundials::Context;
using sundials::CvodeMemory;
using sundials::DenseSolver;
using sundials::IdaMemory;
using sundials::Vector;

struct InitialState {
  VectorXd q, qd;
  Accelerations acc;
};

InitialState consistent_initial_state(const MultibodySystem& system, double t0, const DynamicsOptions& options) {
  KinematicOptions kin;
  kin.singular_tolerance = options.singular_tolerance;
  InitialState s;
  s.q = assemble(system, system.initial_coordinates(), t0, kin);
  check_regular(system, s.q, t0, options.singular_tolerance);
  s.qd = solve_velocities(system, s.q, t0, system.initial_velocities());
  s.acc = solve_accelerations(system, s.q, s.qd, t0);
  return s;
}

// Power of the prescribed-motion drives: effort -lambda times the coordinate rate.
double motion_drive_power(const MultibodySystem& system, const VectorXd& q, const VectorXd& qd,
                          const VectorXd& lambda) {
  double p = 0.0;
  for (const ConstraintBlock& blk : system.blocks()) {
    if (blk.kind != ConstraintKind::Drive) continue;
    const MultibodySystem::CompiledCoordinate c{blk.coordinate, blk.body_i, blk.body_j, blk.s_i, blk.s_j, blk.axis_i};
    p += -lambda(blk.first_row) * system.coordinate(c, q, qd).rate;
  }
  return p;
}

void require_options(const DynamicsOptions& options) {
  require(std::isfinite(options.initial_step_s) && options.initial_step_s >= 0.0,
          "dynamics: initial_step_s must be >= 0 s (0: automatic), got {}", options.initial_step_s);
}

void require_times(const std::vector<double>& times) {
  require(times.size() >= 2, "dynamics: need at least two output times, got {}", times.size());
  for (std::size_t k = 1; k < times.size(); ++k)
    require(times[k] > times[k - 1], "dynamics: output times must increase, times[{}] = {} after {}", k, times[k],
            times[k - 1]);
}

// ---- IDAS, GGL index-2 ----------------------------------------------------------

struct GglProblem {
  const MultibodySystem& system;
  int n = 0, m = 0;
  VectorXd mass;
  std::string error;
};

int ggl_residual(double t, N_Vector yy, N_Vector yp, N_Vector rr, void* user_data) {
  auto* p = static_cast<GglProblem*>(user_data);
  try {
    const int n = p->n, m = p->m;
    const Eigen::Map<const VectorXd> y(N_VGetArrayPointer(yy), 2 * n + 2 * m);
    const Eigen::Map<const VectorXd> yd(N_VGetArrayPointer(yp), 2 * n + 2 * m);
    Eigen::Map<VectorXd> r(N_VGetArrayPointer(rr), 2 * n + 2 * m);
    const VectorXd q = y.head(n), v = y.segment(n, n);
    MatrixXd jac = MatrixXd::Zero(m, n);
    VectorXd phi(m), nu(m);
    for (const ConstraintBlock& blk : p->system.blocks()) {
      const BlockValues b = p->system.evaluate(blk, q, v, t);
      phi.segment(blk.first_row, blk.rows) = b.phi;
      nu.segment(blk.first_row, blk.rows) = b.nu;
      p->system.scatter(blk, b, jac.middleRows(blk.first_row, blk.rows));
    }
    r.head(n) = yd.head(n) - v + jac.transpose() * y.segment(2 * n + m, m);
    r.segment(n, n) = p->mass.cwiseProduct(yd.segment(n, n)) + jac.transpose() * y.segment(2 * n, m) -
                      p->system.applied_forces(q, v, t);
    r.segment(2 * n, m) = phi;
    r.segment(2 * n + m, m) = jac * v - nu;
    return 0;
  } catch (const std::exception& e) {
    p->error = e.what();
    return -1;
  }
}

int ggl_work_rates(double t, N_Vector yy, N_Vector /*yp*/, N_Vector rq, void* user_data) {
  auto* p = static_cast<GglProblem*>(user_data);
  try {
    const int n = p->n, m = p->m;
    const Eigen::Map<const VectorXd> y(N_VGetArrayPointer(yy), 2 * n + 2 * m);
    const VectorXd q = y.head(n), v = y.segment(n, n), lambda = y.segment(2 * n, m);
    double* out = N_VGetArrayPointer(rq);
    out[0] = motion_drive_power(p->system, q, v, lambda) + p->system.force_drive_power(q, v, t);
    out[1] = p->system.other_power(q, v);
    return 0;
  } catch (const std::exception& e) {
    p->error = e.what();
    return -1;
  }
}

// ---- CVODES, minimal coordinate ----------------------------------------------------

struct MinimalProblem {
  const MultibodySystem& system;
  MultibodySystem::CompiledCoordinate coordinate;
  VectorXd mass, q_cache;
  double tolerance_m = 0.0;
  std::string error;
};

struct MinimalState {
  VectorXd q, qd, qdd;
  double s_ddot = 0.0, power_drives = 0.0, power_other = 0.0;
};

MinimalState minimal_state(MinimalProblem& p, double t, double s, double s_dot) {
  const MultibodySystem& sys = p.system;
  const int n = sys.n_coordinates(), m = sys.n_constraints();
  const auto& c = p.coordinate;
  MinimalState out;
  VectorXd q = p.q_cache;
  const VectorXd zero = VectorXd::Zero(n);
  MatrixXd a(n, n);
  auto build = [&](const VectorXd& qq, const VectorXd& qdd_) {
    a.topRows(m) = sys.jacobian(qq, t);
    const auto cv = sys.coordinate(c, qq, qdd_);
    MatrixXd row = MatrixXd::Zero(1, n);
    sys.scatter(c.body_i, c.body_j, cv.grad, row);
    a.bottomRows(1) = row;
    return cv;
  };
  // Position: Phi(q, t) = 0 and s(q) = s.
  double residual = 0.0;
  for (int it = 0; it < 30; ++it) {
    const auto cv = build(q, zero);
    VectorXd f(n);
    f.head(m) = sys.phi(q, t);
    f(m) = cv.value - s;
    residual = std::max(sys.position_drift_m(q, t), std::abs(f(m)) * (c.type == CoordinateType::Angle
                                                                             ? sys.characteristic_length()
                                                                             : 1.0));
    if (residual <= p.tolerance_m) break;
    q -= a.fullPivLu().solve(f);
  }
  require(residual <= p.tolerance_m, "minimal-coordinate path: cannot assemble at t = {} s, s = {}, residual {:.3e} m",
          t, s, residual);
  p.q_cache = q;
  build(q, zero);
  const Eigen::FullPivLU<MatrixXd> lu(a);
  require(lu.isInvertible(), "minimal-coordinate path: singular position at t = {} s, s = {} (the coordinate does not "
                             "determine the mechanism or a dead centre)", t, s);
  VectorXd rhs = VectorXd::Zero(n);
  rhs.head(m) = sys.nu(q, t);
  rhs(m) = s_dot;
  const VectorXd qd = lu.solve(rhs);
  VectorXd unit = VectorXd::Zero(n);
  unit(m) = 1.0;
  const VectorXd v = lu.solve(unit);
  const auto cv = sys.coordinate(c, q, qd);
  rhs.head(m) = sys.gamma(q, qd, t);
  rhs(m) = -cv.quadratic;
  const VectorXd w = lu.solve(rhs);
  const VectorXd forces = sys.applied_forces(q, qd, t);
  const double reduced_inertia = v.dot(p.mass.cwiseProduct(v));
  require(reduced_inertia > 0.0, "minimal-coordinate path: reduced inertia {} is not positive at t = {} s",
          reduced_inertia, t);
  const double generalized_force = v.dot(forces - p.mass.cwiseProduct(w));
  out.s_ddot = generalized_force / reduced_inertia;
  out.q = q;
  out.qd = qd;
  out.qdd = v * out.s_ddot + w;
  out.power_drives = sys.force_drive_power(q, qd, t);
  if (m > 0) {
    const MatrixXd jac = a.topRows(m);
    const VectorXd lambda = (jac * jac.transpose()).ldlt().solve(jac * (forces - p.mass.cwiseProduct(out.qdd)));
    out.power_drives += motion_drive_power(sys, q, qd, lambda);
  }
  out.power_other = sys.other_power(q, qd);
  return out;
}

int minimal_rhs(double t, N_Vector yy, N_Vector ydot, void* user_data) {
  auto* p = static_cast<MinimalProblem*>(user_data);
  try {
    const double* y = N_VGetArrayPointer(yy);
    double* f = N_VGetArrayPointer(ydot);
    const MinimalState st = minimal_state(*p, t, y[0], y[1]);
    f[0] = y[1];
    f[1] = st.s_ddot;
    f[2] = st.power_drives;
    f[3] = st.power_other;
    return 0;
  } catch (const std::exception& e) {
    p->error = e.what();
    return -1;
  }
}

// Automatic first step of both paths (dynamics.hpp): the step whose change
// 0.5 h^2 y'' of the error-tested components is a quarter of their tolerance in
// the worst component, within [1e-9, 1e-3] of the first output interval.
double automatic_first_step(const VectorXd& y, const VectorXd& y_ddot, const VectorXd& absolute_tolerance,
                            double relative_tolerance, double t0, double t1) {
  double curvature = 0.0;  // max |y''| / tolerance, 1/s^2
  for (Eigen::Index i = 0; i < y.size(); ++i)
    curvature =
        std::max(curvature, std::abs(y_ddot(i)) / (relative_tolerance * std::abs(y(i)) + absolute_tolerance(i)));
  const double interval = t1 - t0;
  const double upper = 1e-3 * interval;
  const double lower = std::max(1e-9 * interval, 100.0 * std::numeric_limits<double>::epsilon() *
                                                     std::max(std::abs(t0), std::abs(t1)));
  if (!(curvature > 0.0) || !std::isfinite(curvature)) return upper;
  return std::clamp(0.5 * std::sqrt(2.0 / curvature), lower, upper);
}

std::string failure_context(double t, const std::string& error) {
  return fmt::format("t = {} s{}{}", t, error.empty() ? "" : "; ", error);
}

}  // namespace

Results simulate_ggl(const MultibodySystem& system, const std::vector<double>& times, const DynamicsOptions& options) {
  require_times(times);
  require_options(options);
  const int n = system.n_coordinates(), m = system.n_constraints();
  const InitialState init = consistent_initial_state(system, times.front(), options);
  const FrameOptions frame_options{options.singular_tolerance, options.slack_is_error};
  Results results;
  results.summary.method = "IDAS GGL index-2";
  results.frames.push_back(make_frame(system, times.front(), init.q, init.qd, frame_options, &results.summary));

  GglProblem problem{system, n, m, system.mass_diagonal(), {}};
  Context ctx;
  const sunindextype size = 2 * n + 2 * m;
  Vector y(size, ctx.ctx), yp(size, ctx.ctx), id(size, ctx.ctx), yq(2, ctx.ctx);
  y.map() << init.q, init.qd, init.acc.lambda, VectorXd::Zero(m);
  // The multipliers' rates enter IDAS's predictor only; a forward difference
  // along the motion keeps the first steps from starting with an O(1) error in them.
  const double dt = 1e-7 * std::max(1.0, times.back() - times.front());
  const VectorXd q_next = init.q + dt * init.qd, qd_next = init.qd + dt * init.acc.q_ddot;
  const Accelerations acc_next = solve_accelerations(system, q_next, qd_next, times.front() + dt);
  const VectorXd lambda_rate = (acc_next.lambda - init.acc.lambda) / dt;
  yp.map() << init.qd, init.acc.q_ddot, lambda_rate, VectorXd::Zero(m);
  id.map() << VectorXd::Ones(2 * n), VectorXd::Zero(2 * m);

  IdaMemory ida(ctx.ctx);
  sundials_check(IDAInit(ida.mem, ggl_residual, times.front(), y.v, yp.v), "IDAInit");
  // The multipliers are excluded from the error test but still weigh in the
  // Newton convergence test; with the index-2 iteration matrix's O(1/h^2)
  // conditioning, round-off in them is far above a position tolerance, so they
  // get a tolerance relative to the loads. Their accuracy does not reach the
  // output: frames recompute lambda from (q, v).
  const VectorXd forces0 = system.applied_forces(init.q, init.qd, times.front());
  const double force_scale = std::max({init.acc.lambda.size() ? init.acc.lambda.cwiseAbs().maxCoeff() : 0.0,
                                       forces0.size() ? forces0.cwiseAbs().maxCoeff() : 0.0, 1e-6});
  Vector tolerances(size, ctx.ctx);
  tolerances.map() << VectorXd::Constant(2 * n, options.absolute_tolerance),
      VectorXd::Constant(2 * m, options.multiplier_relative_tolerance * force_scale);
  sundials_check(IDASVtolerances(ida.mem, options.relative_tolerance, tolerances.v), "IDASVtolerances");
  sundials_check(IDASetUserData(ida.mem, &problem), "IDASetUserData");
  DenseSolver dense(size, y.v, ctx.ctx);
  sundials_check(IDASetLinearSolver(ida.mem, dense.solver, dense.matrix), "IDASetLinearSolver");
  sundials_check(IDASetId(ida.mem, id.v), "IDASetId");
  sundials_check(IDASetSuppressAlg(ida.mem, SUNTRUE), "IDASetSuppressAlg");
  sundials_check(IDASetMaxNumSteps(ida.mem, options.max_steps), "IDASetMaxNumSteps");
  if (options.max_step_s > 0.0) sundials_check(IDASetMaxStep(ida.mem, options.max_step_s), "IDASetMaxStep");
  sundials_check(IDAQuadInit(ida.mem, ggl_work_rates, yq.v), "IDAQuadInit");
  // Work integrals under error control: the energy balance is a check of the run.
  sundials_check(IDASetQuadErrCon(ida.mem, SUNTRUE), "IDASetQuadErrCon");
  sundials_check(IDAQuadSStolerances(ida.mem, options.relative_tolerance, options.absolute_tolerance * force_scale),
                 "IDAQuadSStolerances");
  // First step: IDAS's own, 0.5 / ||y'||_WRMS, is ~1e-16 s for a fast start
  // from rest (dynamics.hpp); ours bounds the second-order change instead. The
  // error-tested components are (q, v, work integrals); their second
  // derivatives (q'', q''', power rates) come from the forward difference above.
  double first_step = options.initial_step_s;
  if (first_step <= 0.0) {
    const auto powers = [&](const VectorXd& q, const VectorXd& qd, const VectorXd& lambda, double t) {
      return Eigen::Vector2d(motion_drive_power(system, q, qd, lambda) + system.force_drive_power(q, qd, t),
                             system.other_power(q, qd));
    };
    const Eigen::Vector2d power_rate = (powers(q_next, qd_next, acc_next.lambda, times.front() + dt) -
                                        powers(init.q, init.qd, init.acc.lambda, times.front())) / dt;
    VectorXd tested(2 * n + 2), tested_ddot(2 * n + 2), tested_tolerance(2 * n + 2);
    tested << init.q, init.qd, 0.0, 0.0;
    tested_ddot << init.acc.q_ddot, (acc_next.q_ddot - init.acc.q_ddot) / dt, power_rate;
    tested_tolerance << VectorXd::Constant(2 * n, options.absolute_tolerance),
        Eigen::Vector2d::Constant(options.absolute_tolerance * force_scale);
    first_step = automatic_first_step(tested, tested_ddot, tested_tolerance, options.relative_tolerance,
                                      times.front(), times[1]);
  }
  sundials_check(IDASetInitStep(ida.mem, first_step), "IDASetInitStep");

  for (std::size_t k = 1; k < times.size(); ++k) {
    double t_reached = times[k - 1];
    const int flag = IDASolve(ida.mem, times[k], &t_reached, y.v, yp.v, IDA_NORMAL);
    if (flag < 0) {
      // A failing step is often a singular position: say how close the last state is to one.
      const VectorXd q_last = y.map().head(n);
      std::string context = failure_context(t_reached, problem.error);
      double first = 0.0, step = 0.0;
      if (IDAGetActualInitStep(ida.mem, &first) >= 0 && IDAGetCurrentStep(ida.mem, &step) >= 0)
        context += fmt::format("; first step {:.3e} s, last step tried {:.3e} s", first, step);
      try {
        context += fmt::format("; constraint Jacobian condition {:.3e} there", jacobian_condition(system, q_last, t_reached));
      } catch (const std::exception&) {
      }
      sundials_check(flag, "IDASolve", context);
    }
    double t_quad = 0.0;
    sundials_check(IDAGetQuad(ida.mem, &t_quad, yq.v), "IDAGetQuad");
    const VectorXd q = y.map().head(n), v = y.map().segment(n, n);
    Frame frame = make_frame(system, t_reached, q, v, frame_options, &results.summary);
    frame.work_drives_J = yq.data()[0];
    frame.work_other_J = yq.data()[1];
    results.frames.push_back(std::move(frame));
  }
  RunSummary& s = results.summary;
  long value = 0;
  sundials_check(IDAGetNumSteps(ida.mem, &s.steps), "IDAGetNumSteps");
  sundials_check(IDAGetActualInitStep(ida.mem, &s.first_step_s), "IDAGetActualInitStep");
  sundials_check(IDAGetNumResEvals(ida.mem, &s.residual_evaluations), "IDAGetNumResEvals");
  sundials_check(IDAGetNumJacEvals(ida.mem, &s.jacobian_evaluations), "IDAGetNumJacEvals");
  sundials_check(IDAGetNumErrTestFails(ida.mem, &s.error_test_failures), "IDAGetNumErrTestFails");
  sundials_check(IDAGetNumNonlinSolvConvFails(ida.mem, &value), "IDAGetNumNonlinSolvConvFails");
  s.nonlinear_failures = value;
  summarize(system, results, true);
  return results;
}

Results simulate_minimal(const MultibodySystem& system, const RelativeCoordinate& coordinate,
                         const std::vector<double>& times, const DynamicsOptions& options) {
  require_times(times);
  require_options(options);
  const int n = system.n_coordinates(), m = system.n_constraints();
  require(n - m == 1, "minimal-coordinate path: model '{}' has {} coordinates and {} constraints, needs exactly 1 DoF",
          system.model().name, n, m);
  const InitialState init = consistent_initial_state(system, times.front(), options);
  require(degrees_of_freedom(system, init.q, times.front()) == 1,
          "minimal-coordinate path: model '{}' does not have 1 DoF at t = {} s", system.model().name, times.front());
  const FrameOptions frame_options{options.singular_tolerance, options.slack_is_error};
  MinimalProblem problem{system, system.compile(coordinate, "minimal coordinate"), system.mass_diagonal(), init.q,
                         1e-13 * system.characteristic_length(), {}};
  const auto cv0 = system.coordinate(problem.coordinate, init.q, init.qd);

  Results results;
  results.summary.method = "CVODES minimal coordinate";
  results.frames.push_back(make_frame(system, times.front(), init.q, init.qd, frame_options, &results.summary));

  Context ctx;
  Vector y(4, ctx.ctx);
  y.map() << cv0.value, cv0.rate, 0.0, 0.0;
  CvodeMemory cvode(ctx.ctx);
  sundials_check(CVodeInit(cvode.mem, minimal_rhs, times.front(), y.v), "CVodeInit");
  sundials_check(CVodeSStolerances(cvode.mem, options.relative_tolerance, options.absolute_tolerance),
                 "CVodeSStolerances");
  sundials_check(CVodeSetUserData(cvode.mem, &problem), "CVodeSetUserData");
  DenseSolver dense(4, y.v, ctx.ctx);
  sundials_check(CVodeSetLinearSolver(cvode.mem, dense.solver, dense.matrix), "CVodeSetLinearSolver");
  sundials_check(CVodeSetMaxNumSteps(cvode.mem, options.max_steps), "CVodeSetMaxNumSteps");
  if (options.max_step_s > 0.0) sundials_check(CVodeSetMaxStep(cvode.mem, options.max_step_s), "CVodeSetMaxStep");
  // First step: CVODES's own bounds the forward-Euler change h y' like IDAS's
  // (~1e-17 s for a fast start from rest, harmless for the ODE but wasteful);
  // the automatic rule of the IDAS path instead (dynamics.hpp), on y = (s, s',
  // work integrals) with y'' = (s'', s''', power rates) by a forward difference.
  double first_step = options.initial_step_s;
  if (first_step <= 0.0) {
    const double dt = 1e-7 * std::max(1.0, times.back() - times.front());
    const MinimalState st0 = minimal_state(problem, times.front(), cv0.value, cv0.rate);
    const MinimalState st1 =
        minimal_state(problem, times.front() + dt, cv0.value + dt * cv0.rate, cv0.rate + dt * st0.s_ddot);
    problem.q_cache = init.q;
    Eigen::Vector4d tested_ddot(st0.s_ddot, (st1.s_ddot - st0.s_ddot) / dt,
                                (st1.power_drives - st0.power_drives) / dt, (st1.power_other - st0.power_other) / dt);
    first_step = automatic_first_step(y.map(), tested_ddot, VectorXd::Constant(4, options.absolute_tolerance),
                                      options.relative_tolerance, times.front(), times[1]);
  }
  sundials_check(CVodeSetInitStep(cvode.mem, first_step), "CVodeSetInitStep");

  for (std::size_t k = 1; k < times.size(); ++k) {
    double t_reached = times[k - 1];
    const int flag = CVode(cvode.mem, times[k], y.v, &t_reached, CV_NORMAL);
    sundials_check(flag, "CVode", failure_context(t_reached, problem.error));
    const MinimalState st = minimal_state(problem, t_reached, y.data()[0], y.data()[1]);
    Frame frame = make_frame(system, t_reached, st.q, st.qd, frame_options, &results.summary);
    frame.work_drives_J = y.data()[2];
    frame.work_other_J = y.data()[3];
    results.frames.push_back(std::move(frame));
  }
  RunSummary& s = results.summary;
  sundials_check(CVodeGetNumSteps(cvode.mem, &s.steps), "CVodeGetNumSteps");
  sundials_check(CVodeGetActualInitStep(cvode.mem, &s.first_step_s), "CVodeGetActualInitStep");
  sundials_check(CVodeGetNumRhsEvals(cvode.mem, &s.residual_evaluations), "CVodeGetNumRhsEvals");
  sundials_check(CVodeGetNumJacEvals(cvode.mem, &s.jacobian_evaluations), "CVodeGetNumJacEvals");
  sundials_check(CVodeGetNumErrTestFails(cvode.mem, &s.error_test_failures), "CVodeGetNumErrTestFails");
  sundials_check(CVodeGetNumNonlinSolvConvFails(cvode.mem, &s.nonlinear_failures), "CVodeGetNumNonlinSolvConvFails");
  summarize(system, results, true);
  return results;
}

}  // namespace kinetofem::mech
