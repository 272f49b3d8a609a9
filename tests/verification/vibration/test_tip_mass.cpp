// Vibration verification 3 (docs/vibration.md): a point mass with rotary inertia at the tip of
// a slender cantilever, attached through a distributing coupling reference
// (the elastic assembly's interface type), against the single-degree-of-
// freedom frequency with the beam's effective mass.
//
// Beam L = 1 m, depth 0.04 m (y), thickness 0.02 m (z), steel (E = 210 GPa,
// nu = 0.3, rho = 7850 kg/m^3), HEX20 50 x 2 x 1, clamped at x = 0. Tip mass
// m_p = 5 m_beam at the centroid of the face x = L, rotary inertia
// J = 0.4 m_p r^2 (a sphere, r = 0.05 m) about each axis. Bending in the
// thickness plane (z), the lowest mode:
//   k = 1 / (L^3 / (3 E I) + L / (kappa G A))  (tip stiffness, Timoshenko; Cowper kappa)
//   m_eff = m_p + 33/140 m_beam + J (3 / (2 L))^2
// (Rayleigh with the static tip-load shape: the beam's kinetic energy and
// the tip rotation 3 delta / 2L turning J), f = sqrt(k / m_eff) / 2 pi.
// For m_p = 5 m_beam Rayleigh's quotient is within 1e-4 of the exact
// Euler-Bernoulli frequency. Tolerance 1 %.
// The point mass enters the full model as the low-rank mass G C G^T
// (generalized_eigen.hpp), G the coupling's 6 columns.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "beam_models.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/verification/beam_vibration.hpp"
#include "kinetofem/vibration/craig_bampton.hpp"
#include "tip_mass_model.hpp"

namespace kinetofem::vibration_tests {
namespace {

TEST(TipMass, FirstFrequencyMatchesSdofWithEffectiveBeamMass) {
  const TipMassBeam b;
  const fem::FeModel model = b.model(true);
  const fem::DofMap dofs(model.mesh.node_count(), model.supports);
  const Matrices m = assemble(model, dofs);
  const fem::LowRankMass point = b.point_mass(model, dofs);
  fem::EigenOptions options;
  options.modes = 3;
  options.label = "cantilever + tip mass";
  const Log log;
  const fem::EigenSolution s = fem::solve_generalized_eigen(m.stiffness, m.mass, options, &point, &log);

  const BeamGeometry& g = b.geometry;
  const double E = g.youngs_modulus_pa, G = E / (2.0 * (1.0 + g.poisson_ratio)), L = g.length_m;
  const double kappa = verification::cowper_rectangle_shear_coefficient(g.poisson_ratio);
  const double k = 1.0 / (L * L * L / (3.0 * E * g.second_moment_z_m4()) + L / (kappa * G * g.area_m2()));
  const double theta_per_delta = 3.0 / (2.0 * L);
  const double m_eff = b.tip_mass_kg() + 33.0 / 140.0 * g.mass_kg() +
                       b.tip_inertia_kgm2() * theta_per_delta * theta_per_delta;
  const double reference = std::sqrt(k / m_eff) / (2.0 * std::numbers::pi);
  const Eigen::Vector3d e = component_energy(m.mass, dofs, s.modes.col(0));
  std::printf("tip mass %.4f kg, beam %.4f kg (33/140: %.4f kg), J %.4g kg m^2; k %.6g N/m, "
              "m_eff %.6g kg\n",
              b.tip_mass_kg(), g.mass_kg(), 33.0 / 140.0 * g.mass_kg(), b.tip_inertia_kgm2(), k,
              m_eff);
  std::printf("first frequency %.5f Hz (beam energy x %.3f y %.3f z %.3f), SDOF %.5f Hz, error "
              "%+.3e; %lld DoFs, %.2f s\n",
              s.frequency_hz[0], e[0], e[1], e[2], reference, s.frequency_hz[0] / reference - 1.0,
              static_cast<long long>(dofs.free_count()), s.statistics.seconds);
  // Reference: SDOF with the effective beam mass (header); tolerance 1 %.
  EXPECT_NEAR(s.frequency_hz[0] / reference, 1.0, 0.01);
  EXPECT_EQ(bending_direction(e), 2);
}

}  // namespace
}  // namespace kinetofem::vibration_tests
