#pragma once
// Solid beam models of the vibration checks: a box of HEX20 / TET10 elements
// along x (length L, depth D along y, thickness t along z; box_mesh), its
// stiffness and consistent mass on a DoF map, and the split of a mode's
// kinetic energy over the x, y, z displacement components (to tell bending
// in y, bending in z, torsion and axial modes apart).
#include <array>
#include <cstdio>
#include <vector>

#include <Eigen/Dense>  // cross products in the tests

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/verification/beam_vibration.hpp"
#include "kinetofem/verification/box_mesh.hpp"

namespace kinetofem::vibration_tests {

struct BeamGeometry {
  double length_m = 1.0, depth_m = 0.1, thickness_m = 0.05;
  double youngs_modulus_pa = 210e9, poisson_ratio = 0.0, density_kg_m3 = 7850.0;
  double area_m2() const { return depth_m * thickness_m; }
  double second_moment_y_m4() const {  // bending in the x-y plane (about z)
    return thickness_m * depth_m * depth_m * depth_m / 12.0;
  }
  double second_moment_z_m4() const {  // bending in the x-z plane (about y)
    return depth_m * thickness_m * thickness_m * thickness_m / 12.0;
  }
  double mass_kg() const { return density_kg_m3 * length_m * area_m2(); }
  // The Timoshenko beam of this bar bending with `second_moment_m4` (nu = 0: G = E/2).
  verification::TimoshenkoBeam timoshenko(double second_moment_m4) const {
    return {.length_m = length_m,
            .youngs_modulus_pa = youngs_modulus_pa,
            .shear_modulus_pa = youngs_modulus_pa / 2.0,
            .density_kg_m3 = density_kg_m3,
            .area_m2 = area_m2(),
            .second_moment_m4 = second_moment_m4,
            .shear_coefficient = verification::cowper_rectangle_shear_coefficient(0.0)};
  }
};

inline fem::FeModel beam_model(const BeamGeometry& g, fem::ElementType type,
                               std::array<int, 3> divisions, bool clamp_x0) {
  fem::FeModel model;
  verification::BoxMeshOptions options;
  options.length_m = {g.length_m, g.depth_m, g.thickness_m};
  options.divisions = divisions;
  options.type = type;
  model.mesh = verification::box_mesh(options);
  model.material = fem::IsotropicMaterial{"steel", g.youngs_modulus_pa, g.poisson_ratio,
                                          g.density_kg_m3};
  if (clamp_x0) model.supports = {{"clamp", model.mesh.node_set("x0")}};
  return model;
}

struct Matrices {
  fem::SymmetricUpperMatrix stiffness, mass;
};

inline Matrices assemble(const fem::FeModel& model, const fem::DofMap& dofs) {
  return {fem::assemble_stiffness(model.mesh, model.material, dofs).free_free,
          fem::assemble_mass(model.mesh, model.material, dofs)};
}

// Fraction of phi^T M phi in the x, y, z components (M = m (x) I_3, so the
// three add up to phi^T M phi).
inline Eigen::Vector3d component_energy(const fem::SymmetricUpperMatrix& mass,
                                        const fem::DofMap& dofs, const Eigen::VectorXd& phi) {
  Eigen::Vector3d e;
  const auto M = mass.selfadjointView<Eigen::Upper>();
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd part = Eigen::VectorXd::Zero(phi.size());
    for (fem::Index d = c; d < dofs.dof_count(); d += 3)
      if (const fem::Index eq = dofs.equation(d); eq >= 0) part[eq] = phi[eq];
    e[c] = part.dot(M * part);
  }
  return e / e.sum();
}

// Bending direction of a mode: 1 (y) or 2 (z) when over 90 % of its kinetic
// energy is in that component, else -1 (torsion, axial).
inline int bending_direction(const Eigen::Vector3d& energy) {
  for (int c = 1; c < 3; ++c)
    if (energy[c] > 0.9) return c;
  return -1;
}

}  // namespace kinetofem::vibration_tests
