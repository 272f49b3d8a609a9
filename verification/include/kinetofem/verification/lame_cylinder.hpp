#pragma once
// Lamé thick-walled cylinder under internal pressure, plane strain.
//
// Reference (Lamé; Timoshenko & Goodier, Theory of Elasticity, sec. 33):
// inner radius a, outer b, internal pressure p, plane strain (u_z = 0):
//   u_r(r)      = (1 + nu) p a^2 / (E (b^2 - a^2)) * ((1 - 2 nu) r + b^2 / r)
//   sigma_rr(r) = p a^2 / (b^2 - a^2) * (1 - b^2 / r^2)
//   sigma_tt(r) = p a^2 / (b^2 - a^2) * (1 + b^2 / r^2)
// so at the bore u_r(a) = (1 + nu) p a ((1 - 2 nu) a^2 + b^2) / (E (b^2 - a^2))
// and sigma_tt(a) = p (a^2 + b^2) / (b^2 - a^2).
//
// Model: quarter annulus 0 <= theta <= 90 deg, 0 <= z <= 20 mm, 6 (radial,
// cells growing geometrically 2x from bore to rim, where the gradient is
// small) x 12 x 1 HEX20 with mid-edge nodes on the arcs (mapped_meshes.hpp);
// symmetry u_y = 0 on theta = 0 and u_x = 0 on theta = 90 deg, u_z = 0 on
// both end faces, the pressure on the bore. Checked at every bore node: the
// radial displacement and the recovered nodal hoop stress, 1 % (the
// discretisation errors are ~1e-5 and ~6e-3).
#include <cstddef>

#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::verification {

struct LameCylinder {
  double inner_radius_m = 0.1, outer_radius_m = 0.2;
  double pressure_pa = 100e6;
  double youngs_modulus_pa = 210e9, poisson_ratio = 0.3;

  double radial_displacement_m(double r) const;
  double radial_stress_pa(double r) const;
  double hoop_stress_pa(double r) const;
};

inline constexpr double kLameTolerance = 0.01;  // relative, at every bore node

struct LameModel {
  fem::FeModel model;
  fem::LoadCase load;
};
LameModel lame_model(const LameCylinder& cylinder);

// Solved: the exact bore values, the bore-node values farthest from them,
// and those distances relative to the exact values.
struct LameBoreResult {
  double u_exact_m = 0.0, hoop_exact_pa = 0.0;
  double u_worst_m = 0.0, hoop_worst_pa = 0.0;
  double u_error = 0.0, hoop_error = 0.0;  // relative
  long long free_dofs = 0;
  std::size_t bore_nodes = 0;
};
LameBoreResult solve_lame_cylinder(const LameCylinder& cylinder);

}  // namespace kinetofem::verification
