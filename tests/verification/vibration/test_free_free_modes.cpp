// Vibration verification 2 (docs/vibration.md): a free-free part. The beam of
// test_cantilever_modes.cpp (L = 1 m, D = 0.1 m, t = 0.05 m, nu = 0) with no
// support, HEX20 16 x 4 x 2: the shift-invert Lanczos with a negative shift
// (K - sigma M positive definite although K is singular) gives the six
// rigid-body modes at numerically zero frequency, then the first elastic one:
// bending in the thickness plane, against the free-free Timoshenko beam
// (verification/beam_vibration.hpp; Euler-Bernoulli beta L = 4.7300 printed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "beam_models.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/verification/beam_vibration.hpp"

namespace kinetofem::vibration_tests {
namespace {

namespace kv = kinetofem::verification;

TEST(FreeFreeModes, SixRigidBodyModesThenTheFreeFreeBeamFrequency) {
  const BeamGeometry g;
  const fem::FeModel model = beam_model(g, fem::ElementType::Hex20, {16, 4, 2}, false);
  const fem::DofMap dofs(model.mesh.node_count(), {});
  const Matrices m = assemble(model, dofs);
  const kv::TimoshenkoBeam beam = g.timoshenko(g.second_moment_z_m4());
  const double reference = kv::timoshenko_frequencies_hz(beam, kv::BeamEnds::FreeFree, 1)[0];
  const double euler = kv::euler_bernoulli_frequency_hz(beam, kv::BeamEnds::FreeFree, 1);

  fem::EigenOptions options;
  options.modes = 9;
  // A shift of -(2 pi 50 Hz)^2: below the rigid-body modes' zero, a fifth of
  // the first elastic frequency (~265 Hz) away from it. Much closer to zero
  // makes K - sigma M ill-conditioned (-(2 pi 10 Hz)^2: CHOLMOD's solve
  // residual 1.04e-8, above its 1e-8 limit).
  options.shift_rad2_s2 = -std::pow(2.0 * std::numbers::pi * 50.0, 2);
  options.label = "free-free beam";
  const Log log;
  const fem::EigenSolution s =
      fem::solve_generalized_eigen(m.stiffness, m.mass, options, nullptr, &log);
  for (int i = 0; i < options.modes; ++i) {
    const Eigen::Vector3d e = component_energy(m.mass, dofs, s.modes.col(i));
    std::printf("mode %d: %.6g Hz (omega^2 %.3e), energy x %.3f y %.3f z %.3f\n", i + 1,
                s.frequency_hz[i], s.omega2_rad2_s2[i], e[0], e[1], e[2]);
  }
  const double first_elastic = s.frequency_hz[6];
  // Reference: zero; "numerically zero" = below 1e-4 of the first elastic
  // frequency (the shift-invert eigenvalues carry |sigma| x the Lanczos
  // tolerance as absolute error in omega^2).
  for (int i = 0; i < 6; ++i)
    EXPECT_LT(std::abs(s.frequency_hz[i]), 1e-4 * first_elastic) << "rigid-body mode " << i + 1;
  const Eigen::Vector3d e = component_energy(m.mass, dofs, s.modes.col(6));
  EXPECT_EQ(bending_direction(e), 2) << "the first elastic mode is bending in the thickness plane";
  std::printf("first elastic: %.4f Hz, free-free Timoshenko %.4f Hz (error %+.3e), "
              "Euler-Bernoulli %.4f Hz; %lld DoFs, %.2f s\n",
              first_elastic, reference, first_elastic / reference - 1.0, euler,
              static_cast<long long>(dofs.free_count()), s.statistics.seconds);
  // Reference: free-free Timoshenko beam; tolerance 1 %.
  EXPECT_NEAR(first_elastic / reference, 1.0, 0.01);
  EXPECT_LT(s.statistics.max_orthogonality_error, 1e-8);
}

}  // namespace
}  // namespace kinetofem::vibration_tests
