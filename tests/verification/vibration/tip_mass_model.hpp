#pragma once
// The slender cantilever with a tip mass of test_tip_mass.cpp and
// test_craig_bampton.cpp (geometry and mass there).
#include "beam_models.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/vibration/craig_bampton.hpp"

namespace kinetofem::vibration_tests {

struct TipMassBeam {
  BeamGeometry geometry{.length_m = 1.0,
                        .depth_m = 0.04,
                        .thickness_m = 0.02,
                        .youngs_modulus_pa = 210e9,
                        .poisson_ratio = 0.3,
                        .density_kg_m3 = 7850.0};
  std::array<int, 3> divisions = {50, 2, 1};
  double mass_ratio = 5.0;     // m_p / m_beam
  double sphere_radius_m = 0.05;

  double tip_mass_kg() const { return mass_ratio * geometry.mass_kg(); }
  double tip_inertia_kgm2() const { return 0.4 * tip_mass_kg() * sphere_radius_m * sphere_radius_m; }
  Eigen::Vector3d tip_point_m() const {
    return {geometry.length_m, 0.5 * geometry.depth_m, 0.5 * geometry.thickness_m};
  }
  // 6 x 6 mass of the reference coordinates (translation, rotation).
  Eigen::Matrix<double, 6, 6> tip_mass_matrix() const {
    Eigen::Matrix<double, 6, 1> d;
    d << tip_mass_kg(), tip_mass_kg(), tip_mass_kg(), tip_inertia_kgm2(), tip_inertia_kgm2(),
        tip_inertia_kgm2();
    return d.asDiagonal();
  }
  fem::FeModel model(bool clamp_x0) const {
    return beam_model(geometry, fem::ElementType::Hex20, divisions, clamp_x0);
  }
  vibration::PartInterface tip_interface(const fem::FeModel& m) const {
    return vibration::coupling_interface(m.mesh, "x1", tip_point_m(), "tip");
  }
  // The point mass as the low-rank term G C G^T over the free equations.
  fem::LowRankMass point_mass(const fem::FeModel& m, const fem::DofMap& dofs) const {
    const vibration::PartInterface tip = tip_interface(m);
    fem::LowRankMass out{Eigen::MatrixXd::Zero(dofs.free_count(), 6), tip_mass_matrix()};
    for (fem::Index d = 0; d < dofs.dof_count(); ++d)
      if (const fem::Index eq = dofs.equation(d); eq >= 0) out.basis.row(eq) = tip.columns.row(d);
    return out;
  }
};

}  // namespace kinetofem::vibration_tests
