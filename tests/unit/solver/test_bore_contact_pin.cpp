// fem::ElasticPin and fem::pin_mesh: the pin's mesh, its compliance on a
// bore's pressure basis (symmetric, positive semidefinite, exact under a
// uniform pressure), the mortar map's error on matching and non-matching
// meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/solver/bore_contact_pin.hpp"

namespace kinetofem::fem {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(PinMesh, IsASolidCylinderWithItsSurfaceOnTheCircle) {
  const Mesh mesh = pin_mesh(0.01, 0.02, 24, 3, 2);
  check_element_jacobians(mesh);  // throws on an inverted element
  // Volume and lateral area of the cylinder; the quadratic elements' arcs
  // differ from the circle by O(h^4): 1e-5 at 24 around.
  EXPECT_NEAR(mesh_volume(mesh) / (kPi * 0.01 * 0.01 * 0.02), 1.0, 1e-5);
  EXPECT_NEAR(surface_area(mesh, mesh.face_set("surface")) / (2 * kPi * 0.01 * 0.02), 1.0, 1e-5);
  EXPECT_THROW(pin_mesh(0.01, 0.02, 10, 3, 2), Error);  // not a multiple of 4
  EXPECT_THROW(pin_mesh(-0.01, 0.02, 24, 3, 2), Error);
}

// A pin in a "bore" that is the surface of a cylinder of the same radius
// (the bore's geometry is all the pin's flexibility needs).
struct UniformPressure {
  double worst = 0.0;      // |A 1 - area R (1 - nu) / E| / (area R (1 - nu) / E), worst corner
  double asymmetry = 0.0;  // before ElasticPin's symmetrization it is round-off; after, 0
  double lowest = 0.0;     // lowest eigenvalue over the highest
  double mapping = 0.0;
};
UniformPressure uniform_pressure(int pin_around, int pin_along) {
  const double R = 0.01, L = 0.015;
  const Mesh bore_mesh = pin_mesh(R, L, 48, 3, 3);
  const BoreContactSurface bore(bore_mesh, "surface", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  IsotropicMaterial steel;
  ElasticPinOptions options;
  options.circumferential_elements = pin_around;
  options.axial_elements = pin_along;
  const Log log = Log::quiet();
  const ElasticPin pin(bore_mesh, bore, steel, 0.0, log, options);
  const Eigen::MatrixXd& A = pin.compliance();
  // A uniform pressure p on a free cylinder: sigma_rr = sigma_tt = -p,
  // sigma_zz = 0 everywhere (exact in 3D, free ends included), so the
  // surface moves in by p R (1 - nu) / E and each corner's weighted gap
  // opens by its area times that.
  const Eigen::VectorXd expected =
      bore.corner_area_m2() * R * (1 - steel.poisson_ratio) / steel.youngs_modulus_pa;
  const Eigen::VectorXd gap = A * Eigen::VectorXd::Ones(A.rows());
  UniformPressure out;
  out.worst = (gap - expected).cwiseQuotient(expected).cwiseAbs().maxCoeff();
  out.asymmetry = (A - A.transpose()).cwiseAbs().maxCoeff() / A.cwiseAbs().maxCoeff();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(A);
  out.lowest = eig.eigenvalues().minCoeff() / eig.eigenvalues().maxCoeff();
  out.mapping = pin.mapping_error();
  return out;
}

TEST(ElasticPin, AUniformPressureCompressesThePinAsTheElasticitySolution) {
  // Matching meshes (the pin's faces are the bore's). Reference: the free
  // cylinder under lateral pressure. The FE model reproduces the homogeneous
  // stress exactly, but the nodal forces take each node's own radial
  // direction (as BoreContactSurface does), an O(spacing^2) error in the
  // pressure's direction: 1.2e-4 at 7.5 degrees; tolerance 3e-4. The map's
  // area error is the curved faces' quadrature (|t1 x t2| is not a
  // polynomial): 1e-7 measured, 1e-6 allowed.
  const UniformPressure matching = uniform_pressure(48, 3);
  std::printf("matching pin: worst corner %.2e, mapping error %.2e\n", matching.worst, matching.mapping);
  EXPECT_LE(matching.mapping, 1e-6);
  EXPECT_LE(matching.worst, 3e-4);
  EXPECT_EQ(matching.asymmetry, 0.0);
  EXPECT_GE(matching.lowest, -1e-12);
}

TEST(ElasticPin, NonMatchingMeshesKeepTheMortarMapsErrorSmall) {
  // 40 pin faces against 48 bore faces around: the pin's shape functions are
  // integrated across their kinks by a subdivided Gauss rule (4 x 4 parts
  // of degree 5), so Q is not exact. Reference: the same elasticity
  // solution; tolerance 1e-3 per corner (measured 6.2e-4; the map's area
  // error, printed, is 1.4e-3 in sum over the pin's nodes).
  const UniformPressure shifted = uniform_pressure(40, 2);
  std::printf("non-matching pin: worst corner %.2e, mapping error %.2e, lowest eigenvalue %.2e\n", shifted.worst,
              shifted.mapping, shifted.lowest);
  EXPECT_LE(shifted.worst, 1e-3);
  EXPECT_GE(shifted.lowest, -1e-12);
}

TEST(ElasticPin, AClearanceAsLargeAsTheBoreIsAnError) {
  const Mesh bore_mesh = pin_mesh(0.01, 0.01, 16, 2, 1);
  const BoreContactSurface bore(bore_mesh, "surface", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ());
  const Log log = Log::quiet();
  EXPECT_THROW(ElasticPin(bore_mesh, bore, IsotropicMaterial{}, 0.02, log), Error);
  IsotropicMaterial soft;
  soft.youngs_modulus_pa = -1;
  EXPECT_THROW(ElasticPin(bore_mesh, bore, soft, 0.0, log), Error);
}

}  // namespace
}  // namespace kinetofem::fem
