#pragma once
// Timoshenko's cantilever under end shear as a 3D verification problem
// (shared by tests/verification/solver/cantilever_test.cpp and the larger
// refinement study in tests/large/).
//
// Beam 0 <= x <= L, -c <= y <= c (depth D = 2c), thickness t along z
// (0..t), E, nu = 0, end shear P along +y at x = L.
//
// Exact solution (Timoshenko & Goodier, Theory of Elasticity, sec. 21, the
// plane-stress cantilever): sigma_xx = -P (L - x) y / I,
// tau_xy = P (c^2 - y^2) / (2 I), all other stresses zero, I = t D^3 / 12.
// With nu = 0 this field is also an exact 3D solution (no lateral
// contraction: u_z = 0, sigma_zz = 0) and its displacement has u_y(0, y) = 0
// on the whole wall x = 0, while the wall section warps in x. Taking the
// wall's rotation as the mean section rotation omega = -int u_x y dA / I
// (Cowper's definition, the one behind the shear coefficient), the exact tip
// deflection relative to the wall is
//   delta = P L^3 / (3 E I) + P L / (kappa G A),  kappa = 10 (1 + nu) / (12 + 11 nu) = 5/6,
// so Timoshenko beam theory with Cowper's kappa is exact here (the exact
// elasticity shear term 6 P L / (5 G A) equals P L / (kappa G A) for nu = 0).
// Exact compliance C = int (sigma_xx^2 / E + tau_xy^2 / G) dV = P delta.
//
// FE model: the exact tractions t = sigma n on both end faces (parabolic
// shear at x = L, linear bending stress at x = 0), as consistent nodal
// forces; supports that the exact solution satisfies: u_y = 0 on the wall
// face, u_z = 0 on z = 0, u_x = 0 at the wall nodes (0, 0, 0) and (0, c, 0).
// The loads are self-equilibrated, so the point supports carry nothing, and
// there is no clamped corner: the solution is smooth, and the compliance
// f . u of quadratic elements converges from below as O(h^4).
// Mesh at refinement k: 8k x 2k x k cells of `type` (L/D = 10, t = D/2).
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

struct TimoshenkoCantilever {
  double length_m = 1.0;
  double depth_m = 0.1;
  double thickness_m = 0.05;
  double youngs_modulus_pa = 210e9;
  double load_n = 1000.0;

  double second_moment_m4() const { return thickness_m * depth_m * depth_m * depth_m / 12.0; }
  double shear_coefficient() const { return 10.0 / 12.0; }  // Cowper, nu = 0
  // delta = P L^3 / (3 E I) + P L / (kappa G A), G = E / 2 (nu = 0), m.
  double beam_deflection_m() const;
  double exact_compliance_nm() const { return load_n * beam_deflection_m(); }
};

struct CantileverSolution {
  double compliance_nm = 0.0;  // f . u over the loaded nodes
  double deflection_m = 0.0;   // mean u_y(L) - mean u_y(0) - omega(0) L
  long long free_dofs = 0;
  double solve_seconds = 0.0;
};

CantileverSolution solve_cantilever(const TimoshenkoCantilever& beam, fem::ElementType type,
                                    int refinement);

}  // namespace kinetofem::verification
