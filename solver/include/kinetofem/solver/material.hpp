#pragma once
// IsotropicMaterial — small-strain isotropic linear elasticity.
//
// Hooke's law in Voigt notation, stress = D * strain, with the component order
// (xx, yy, zz, xy, yz, zx) and engineering shear strains (gamma = 2 * epsilon):
//   D = E / ((1 + nu)(1 - 2 nu)) * [[1-nu, nu, nu], [nu, 1-nu, nu], [nu, nu, 1-nu]] (normal block)
//   D_shear = G = E / (2 (1 + nu)) on the diagonal of the shear block.
#include <string>

#include <Eigen/Core>

namespace kinetofem::fem {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

struct IsotropicMaterial {
  std::string name = "steel";
  double youngs_modulus_pa = 210e9;
  double poisson_ratio = 0.3;
  double density_kg_m3 = 7850.0;

  // Throws Error unless E > 0, -1 < nu < 0.5 and density >= 0, all finite.
  void validate() const;
  Matrix6d elasticity_matrix() const;
  double shear_modulus_pa() const { return youngs_modulus_pa / (2.0 * (1.0 + poisson_ratio)); }
};

}  // namespace kinetofem::fem
