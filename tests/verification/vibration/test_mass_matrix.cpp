// Consistent mass matrix (solver/mass_matrix.hpp) of every element type:
// total mass = rho V and the kinetic energy of a rigid velocity field
// v = v0 + omega x x against the part's mass properties (solver/rigid_body.hpp),
// 1/2 m |v_c|^2 + 1/2 omega^T I_c omega, on a distorted box (corners moved
// at random, straight edges: both are exact there, so to round-off).
// Plus the bad inputs of the eigen solve: zero density, modes <= 0,
// non-convergence.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "beam_models.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::vibration_tests {
namespace {

class MassMatrixTest : public ::testing::TestWithParam<fem::ElementType> {};

TEST_P(MassMatrixTest, TotalMassAndRigidKineticEnergyMatchMassProperties) {
  verification::BoxMeshOptions options;
  options.length_m = {0.6, 0.25, 0.15};
  options.divisions = {4, 2, 2};
  options.type = GetParam();
  options.random_perturbation = 0.15;
  const fem::Mesh mesh = verification::box_mesh(options);
  const fem::IsotropicMaterial steel{"steel", 210e9, 0.3, 7850.0};
  const fem::DofMap dofs(mesh.node_count(), {});
  const fem::SymmetricUpperMatrix M = fem::assemble_mass(mesh, steel, dofs);
  const auto Ms = M.selfadjointView<Eigen::Upper>();
  const fem::MassProperties props = fem::mass_properties(mesh, steel);
  const double rho_v = steel.density_kg_m3 * fem::mesh_volume(mesh);

  // Reference: rho V (the mesh volume); tolerance 1e-12 relative (round-off).
  for (int c = 0; c < 3; ++c) {
    Eigen::Vector3d t = Eigen::Vector3d::Zero();
    t[c] = 1.0;
    const Eigen::VectorXd v = fem::rigid_body_field(mesh, t, Eigen::Vector3d::Zero());
    const double mass = v.dot(Ms * v);
    EXPECT_NEAR(mass / rho_v, 1.0, 1e-12) << "direction " << c;
  }
  const Eigen::Vector3d v0(0.3, -1.2, 0.7), omega(2.0, -0.5, 1.5);
  const Eigen::VectorXd v = fem::rigid_body_field(mesh, v0, omega);
  const double kinetic = 0.5 * v.dot(Ms * v);
  const Eigen::Vector3d vc = v0 + omega.cross(props.centre_of_mass_m);
  const double reference = 0.5 * props.mass_kg * vc.squaredNorm() +
                           0.5 * omega.dot(props.inertia_about_com_kgm2 * omega);
  std::printf("%s: mass properties %.12g kg (rho V %.12g), rigid kinetic energy %.12g J (mass properties "
              "%.12g, error %.1e)\n",
              fem::name_of(GetParam()), props.mass_kg, rho_v, kinetic, reference,
              kinetic / reference - 1.0);
  // Reference: mass_properties' kinetic energy; tolerance 1e-12 relative.
  EXPECT_NEAR(kinetic / reference, 1.0, 1e-12);
}

INSTANTIATE_TEST_SUITE_P(AllElements, MassMatrixTest,
                         ::testing::Values(fem::ElementType::Tet4, fem::ElementType::Tet10,
                                           fem::ElementType::Hex8, fem::ElementType::Hex20),
                         [](const auto& info) { return std::string(fem::name_of(info.param)); });

Matrices small_cantilever(double density) {
  BeamGeometry g;
  g.density_kg_m3 = density;
  const fem::FeModel model = beam_model(g, fem::ElementType::Hex8, {8, 2, 1}, true);
  return assemble(model, fem::DofMap(model.mesh.node_count(), model.supports));
}

TEST(EigenSolveErrors, ZeroDensityIsAnError) {
  const Matrices m = small_cantilever(0.0);
  fem::EigenOptions options;
  options.label = "link 2";
  try {
    fem::solve_generalized_eigen(m.stiffness, m.mass, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    std::printf("zero density: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("mass matrix of 'link 2' is not positive"),
              std::string::npos);
  }
}

TEST(EigenSolveErrors, ModesMustBePositive) {
  const Matrices m = small_cantilever(7850.0);
  for (int modes : {0, -3}) {
    fem::EigenOptions options;
    options.modes = modes;
    EXPECT_THROW(fem::solve_generalized_eigen(m.stiffness, m.mass, options), Error);
  }
}

TEST(EigenSolveErrors, NonConvergenceNamesTheModesConverged) {
  const Matrices m = small_cantilever(7850.0);
  fem::EigenOptions options;
  options.modes = 20;
  options.lanczos_vectors = 21;
  options.max_restarts = 1;
  options.tolerance = 1e-15;
  options.label = "link 3";
  try {
    fem::solve_generalized_eigen(m.stiffness, m.mass, options);
    FAIL() << "converged with 1 restart";
  } catch (const fem::EigenNotConverged& e) {
    std::printf("non-convergence: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("'link 3' did not converge"), std::string::npos);
    EXPECT_LT(e.statistics().converged, 20);
    EXPECT_NE(std::string(e.what()).find(fmt::format("{} of 20 modes converged",
                                                     e.statistics().converged)),
              std::string::npos);
  }
}

TEST(EigenSolveErrors, ShiftAboveTheLowestEigenvalueIsAnError) {
  const Matrices m = small_cantilever(7850.0);
  fem::EigenOptions options;
  options.modes = 3;
  options.shift_rad2_s2 = std::pow(2.0 * 3.141592653589793 * 200.0, 2);  // above f1 ~ 42 Hz
  try {
    fem::solve_generalized_eigen(m.stiffness, m.mass, options);
    FAIL() << "no error";
  } catch (const Error& e) {
    std::printf("shift too high: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("not positive definite"), std::string::npos);
  }
}

}  // namespace
}  // namespace kinetofem::vibration_tests
