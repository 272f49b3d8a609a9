#pragma once
// Forward dynamics of a spatial::System on SUNDIALS IDAS, the stabilised
// index-2 (Gear-Gupta-Leimkuhler) form, unknowns y = (q, v, lambda, mu):
//     q' - L(q) v + [Phi_q; N_q]^T mu = 0      (7 nb)
//     M v' + Pi^T lambda - (Q - h) = 0         (6 nb)
//     Phi(q, t) = 0,  p_k.p_k - 1 = 0          (m + nb)
//     Pi v - nu(q, t) = 0                      (m)
// (system.hpp for L, Pi, N = the norm rows). q, v differential; lambda, mu
// algebraic and excluded from the error test. The norm rows enter only at
// position level: the velocity form keeps d(p.p)/dt = 0 identically, and their
// mu keeps p on the unit sphere to the Newton tolerance.
//
// Redundant rows: at the consistent initial state a column-pivoting QR of
// the mass-metric Jacobian Pi~^T (results.hpp) selects an independent set of rows; IDAS integrates with those only (a
// singular Newton matrix is then impossible). The dropped rows still count in
// every frame's drift, and the frames' multipliers come from the rank-revealing
// index-1 solve over all rows (results.hpp).
//
// Consistent initial values: assembly, velocity projection (kinematics.hpp)
// and the index-1 solve, mu = 0.
#include <vector>

#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"

namespace kinetofem::mech::spatial {

struct DynamicsOptions {
  double relative_tolerance = 1e-10;
  double absolute_tolerance = 1e-12;  // q (m, 1) and v (m/s, rad/s)
  // Absolute tolerance of lambda and mu (not error-tested) as a fraction of the
  // largest initial load or multiplier: they only weigh in IDAS's Newton
  // convergence test, where the index-2 matrix is O(1/h^2)-conditioned in them
  // (as in the planar core, multibody/dynamics.hpp).
  double multiplier_relative_tolerance = 1e-1;
  long max_steps = 500000;
  double max_step_s = 0.0;      // 0: no limit
  double initial_step_s = 0.0;  // 0: automatic (the second-order rule of the planar core)
  double rank_tolerance = kRankTolerance;  // relative, on the pivots when selecting rows (results.hpp)
};

// times: output times, increasing; times[0] is the initial time.
Results simulate_ggl(const System& system, const std::vector<double>& times, const DynamicsOptions& options = {});

}  // namespace kinetofem::mech::spatial
