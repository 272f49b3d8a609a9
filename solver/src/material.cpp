#include "kinetofem/solver/material.hpp"

#include <cmath>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

void IsotropicMaterial::validate() const {
  require(std::isfinite(youngs_modulus_pa) && youngs_modulus_pa > 0.0,
          "material '{}': Young's modulus {} Pa must be positive and finite", name,
          youngs_modulus_pa);
  require(std::isfinite(poisson_ratio) && poisson_ratio > -1.0 && poisson_ratio < 0.5,
          "material '{}': Poisson's ratio {} must lie in (-1, 0.5)", name, poisson_ratio);
  require(std::isfinite(density_kg_m3) && density_kg_m3 >= 0.0,
          "material '{}': density {} kg/m^3 must be non-negative and finite", name,
          density_kg_m3);
}

Matrix6d IsotropicMaterial::elasticity_matrix() const {
  const double E = youngs_modulus_pa, nu = poisson_ratio;
  const double lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  const double mu = shear_modulus_pa();
  Matrix6d D = Matrix6d::Zero();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) D(i, j) = lambda;
    D(i, i) = lambda + 2.0 * mu;
    D(i + 3, i + 3) = mu;
  }
  return D;
}

}  // namespace kinetofem::fem
