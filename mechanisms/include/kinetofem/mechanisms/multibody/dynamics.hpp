#pragma once
// Forward dynamics of a MultibodySystem.
//
// simulate_ggl — IDAS on the stabilised index-2 (Gear-Gupta-Leimkuhler) form,
// unknowns y = (q, v, lambda, mu):
//     q' - v + Phi_q^T mu = 0
//     M v' + Phi_q^T lambda - Q(q, v, t) = 0
//     Phi(q, t) = 0
//     Phi_q v - nu(q, t) = 0
// q, v differential; lambda, mu algebraic and excluded from the error test.
// Position and velocity constraints are both enforced at every step, so the
// drift stays at the Newton tolerance. Consistent initial values come from
// assembly, velocity projection and the index-1 acceleration solve (mu = 0).
// A fully driven (DoF 0) model runs too: its drives' multipliers are the drive
// efforts. The work of the drives and of dampers/point forces is integrated as
// IDAS quadratures for the energy balance.
//
// simulate_minimal — for a 1-DoF model: CVODES (BDF, Newton, dense) on the
// minimal-coordinate form with independent coordinate s (a RelativeCoordinate):
//     m*(s) s'' = Q*(s, s', t),  m* = V^T M V,  Q* = V^T (Q - M w),
// where [Phi_q; s_q] V = [0; 1] (q' = V s') and [Phi_q; s_q] w = [gamma; -s_quad]
// (q'' = V s'' + w); q(s) from Newton at each evaluation. Both paths build their
// output frames with make_frame (results.hpp).
#include <vector>

#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"

namespace kinetofem::mech {

struct DynamicsOptions {
  double relative_tolerance = 1e-10;
  double absolute_tolerance = 1e-12;             // q (m, rad) and v
  // IDAS only: absolute tolerance of lambda and mu (not error-tested) as a
  // fraction of the largest initial load or multiplier. Loose on purpose: the
  // index-2 Newton matrix is O(1/h^2)-conditioned in these components, and their
  // errors act only normal to the constraint manifold (M-metric), where the
  // position and velocity constraints pin the solution; output frames
  // recompute lambda from (q, v).
  double multiplier_relative_tolerance = 1e-1;
  long max_steps = 500000;
  double max_step_s = 0.0;  // 0: no limit
  // First step of the integrator (s), used as given when > 0. Automatic (0),
  // both paths: the step whose change 0.5 h^2 y'' of the error-tested
  // components is a quarter of their error tolerance in the worst component,
  //     h0 = 0.5 sqrt(2 / max_i(|y''_i| / (relative_tolerance |y_i| + atol_i))),
  // at the consistent initial state; IDAS: y = (q, v, work integrals),
  // y'' = (q'', q''', power rates); CVODES: y = (s, s', work integrals),
  // y'' = (s'', s''', power rates); q''' (s''') and the power rates by a
  // forward difference along the motion; atol_i the absolute tolerance of the
  // component (IDAS's work integrals: absolute_tolerance times the load scale).
  // Bounded above by 1e-3 of the first output interval (IDAS's own default
  // scale) and below by 1e-9 of it and 100 ulp of the initial time (round-off
  // of the time). Why: the integrators' own first steps bound the first-order
  // change, h |y'| <~ tol. Started from rest, the velocities sit at 0 with
  // tolerance abs_tol, so a small fast mechanism gets h ~ abs_tol / |q''|
  // (2.3e-16 s for 1.4e4 rad/s^2 at abs_tol 1e-12), where the index-2 corrector
  // of IDAS cannot converge (flag -4 at t0; that mechanism needs >= ~1e-11 s)
  // and CVODES starts at 2e-17 s. From rest a coordinate moves 0.5 q'' h^2 in a
  // step, and that is what the error test sees: hence the second-order rule
  // (that of CVODES's own estimate, without its first-order cap).
  double initial_step_s = 0.0;  // 0: automatic
  double singular_tolerance = 1e-6;
  bool slack_is_error = true;
};

// times: output times, increasing; times[0] is the initial time.
Results simulate_ggl(const MultibodySystem& system, const std::vector<double>& times,
                     const DynamicsOptions& options = {});
Results simulate_minimal(const MultibodySystem& system, const RelativeCoordinate& coordinate,
                         const std::vector<double>& times, const DynamicsOptions& options = {});

}  // namespace kinetofem::mech
