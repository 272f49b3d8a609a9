// Unit tests of the element library: shape functions, their derivatives,
// Gauss rules and face numbering.
#include <gtest/gtest.h>

#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/mesh.hpp"

#include <Eigen/Geometry>

namespace kinetofem::fem {
namespace {

constexpr const auto& kAllTypes = all_element_types;
constexpr const auto& kAllFaces = all_face_types;

Eigen::Vector3d interior_point(ElementType type) {
  return corner_nodes(type) == 4 ? Eigen::Vector3d(0.21, 0.17, 0.33)
                                 : Eigen::Vector3d(0.3, -0.41, 0.27);
}

TEST(ShapeFunctions, AreKroneckerDeltaAtNodes) {
  for (ElementType type : kAllTypes) {
    const Eigen::MatrixXd X = reference_nodes(type);
    Eigen::VectorXd N;
    Eigen::MatrixXd dN;
    for (int a = 0; a < X.rows(); ++a) {
      shape_functions(type, X.row(a).transpose(), N, dN);
      for (int b = 0; b < X.rows(); ++b)
        EXPECT_NEAR(N[b], a == b ? 1.0 : 0.0, 1e-14) << name_of(type) << " node " << a;
    }
  }
}

TEST(ShapeFunctions, ReproduceLinearFieldsAndMatchFiniteDifferences) {
  for (ElementType type : kAllTypes) {
    const Eigen::Vector3d xi = interior_point(type);
    Eigen::VectorXd N, Np, Nm;
    Eigen::MatrixXd dN, dummy;
    shape_functions(type, xi, N, dN);
    const Eigen::MatrixXd X = reference_nodes(type);
    // Partition of unity and linear completeness: sum N = 1, sum N x_a = x.
    EXPECT_NEAR(N.sum(), 1.0, 1e-14) << name_of(type);
    EXPECT_LT((X.transpose() * N - xi).norm(), 1e-14) << name_of(type);
    // Derivatives against central differences (h = 1e-6: error ~ h^2).
    const double h = 1e-6;
    for (int d = 0; d < 3; ++d) {
      Eigen::Vector3d xp = xi, xm = xi;
      xp[d] += h;
      xm[d] -= h;
      shape_functions(type, xp, Np, dummy);
      shape_functions(type, xm, Nm, dummy);
      EXPECT_LT(((Np - Nm) / (2 * h) - dN.col(d)).cwiseAbs().maxCoeff(), 1e-8)
          << name_of(type) << " d/dxi_" << d;
    }
  }
}

TEST(ShapeFunctions, FaceFunctionsMatchFiniteDifferences) {
  for (FaceType type : kAllFaces) {
    const bool tri = type == FaceType::Tri3 || type == FaceType::Tri6;
    const Eigen::Vector3d xi = tri ? Eigen::Vector3d(0.23, 0.31, 0) : Eigen::Vector3d(0.4, -0.2, 0);
    Eigen::VectorXd N, Np, Nm;
    Eigen::MatrixXd dN, dummy;
    shape_functions(type, xi, N, dN);
    EXPECT_NEAR(N.sum(), 1.0, 1e-14) << name_of(type);
    const double h = 1e-6;
    for (int d = 0; d < 2; ++d) {
      Eigen::Vector3d xp = xi, xm = xi;
      xp[d] += h;
      xm[d] -= h;
      shape_functions(type, xp, Np, dummy);
      shape_functions(type, xm, Nm, dummy);
      EXPECT_LT(((Np - Nm) / (2 * h) - dN.col(d)).cwiseAbs().maxCoeff(), 1e-8) << name_of(type);
    }
  }
}

TEST(Quadrature, IntegratesReferenceVolumeAndPolynomials) {
  for (ElementType type : kAllTypes) {
    const bool tet = corner_nodes(type) == 4;
    double volume = 0, second_moment = 0;
    for (const auto& qp : quadrature(type)) {
      volume += qp.weight;
      second_moment += qp.weight * qp.xi[0] * qp.xi[1];
    }
    // Exact: tet volume 1/6, int xi eta = 1/120; cube [-1,1]^3 volume 8, int xi eta = 0.
    EXPECT_NEAR(volume, tet ? 1.0 / 6.0 : 8.0, 1e-14) << name_of(type);
    if (type != ElementType::Tet4) {
      EXPECT_NEAR(second_moment, tet ? 1.0 / 120.0 : 0.0, 1e-14) << name_of(type);
    }
  }
  // The degree-3 load rule of tetrahedra: int xi^2 eta = 2!1!/6! = 1/360.
  double cubic = 0;
  for (const auto& qp : load_quadrature(ElementType::Tet10))
    cubic += qp.weight * qp.xi[0] * qp.xi[0] * qp.xi[1];
  EXPECT_NEAR(cubic, 1.0 / 360.0, 1e-15);
}

TEST(Quadrature, CurvedTetRuleIsExactToDegreeFive) {
  // Reference: int_T xi^a eta^b zeta^c = a! b! c! / (a + b + c + 3)! on the unit tetrahedron.
  auto factorial = [](int n) { double f = 1; for (int k = 2; k <= n; ++k) f *= k; return f; };
  double weights = 0;
  for (const auto& qp : curved_tet_quadrature()) {
    EXPECT_GT(qp.weight, 0.0);
    weights += qp.weight;
  }
  EXPECT_NEAR(weights, 1.0 / 6.0, 1e-15);
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; a + b <= 5; ++b)
      for (int c = 0; a + b + c <= 5; ++c) {
        double sum = 0;
        for (const auto& qp : curved_tet_quadrature())
          sum += qp.weight * std::pow(qp.xi[0], a) * std::pow(qp.xi[1], b) * std::pow(qp.xi[2], c);
        const double exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
        EXPECT_NEAR(sum, exact, 1e-14) << a << b << c;
      }
}

TEST(ElementFaces, NormalsPointOutOfTheReferenceElement) {
  for (ElementType type : kAllTypes) {
    const Eigen::MatrixXd X = reference_nodes(type);
    const Eigen::Vector3d centre = X.topRows(corner_nodes(type)).colwise().mean();
    for (int f = 0; f < faces_per_element(type); ++f) {
      const auto nodes = element_face_nodes(type, f);
      ASSERT_EQ(int(nodes.size()), nodes_per_face(face_type_of(type)));
      const Eigen::Vector3d p0 = X.row(nodes[0]), p1 = X.row(nodes[1]), p2 = X.row(nodes[2]);
      const Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0);
      EXPECT_GT(normal.dot(p0 - centre), 0.0) << name_of(type) << " face " << f;
      // Mid-edge nodes of the face lie between their corners.
      const int corners = corner_nodes(type) == 4 ? 3 : 4;
      for (size_t m = size_t(corners); m < nodes.size(); ++m) {
        const Eigen::Vector3d mid = 0.5 * (X.row(nodes[m - corners]) +
                                           X.row(nodes[(m - corners + 1) % corners]));
        EXPECT_LT((X.row(nodes[m]).transpose() - mid).norm(), 1e-14);
      }
    }
  }
}

}  // namespace
}  // namespace kinetofem::fem
