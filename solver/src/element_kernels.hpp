#pragma once
// Internal: per-element kernels shared by assembly and stress recovery —
// Jacobian, physical shape-function gradients, element stiffness of the
// isotropic elastic solid. Templated on the node count so the small dense
// algebra has fixed sizes.
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem::detail {

// Shape functions and reference gradients of a rule, evaluated once.
template <int NPE>
struct RuleTable {
  std::vector<Eigen::Matrix<double, NPE, 1>> N;
  std::vector<Eigen::Matrix<double, NPE, 3>> dN;
  std::vector<double> weight;

  RuleTable(ElementType type, const std::vector<QuadraturePoint>& rule) {
    Eigen::VectorXd n;
    Eigen::MatrixXd d;
    for (const auto& qp : rule) {
      shape_functions(type, qp.xi, n, d);
      N.push_back(n);
      dN.push_back(d);
      weight.push_back(qp.weight);
    }
  }
  size_t size() const { return weight.size(); }
};

template <int NPE>
using NodeMatrix = Eigen::Matrix<double, NPE, 3>;

template <int NPE>
NodeMatrix<NPE> element_coordinates(const Mesh& mesh, std::span<const Index> nodes) {
  NodeMatrix<NPE> X;
  for (int a = 0; a < NPE; ++a) X.row(a) = mesh.nodes.row(nodes[size_t(a)]);
  return X;
}

// Physical gradients G = dN/dx (NPE x 3) and det J at one point.
template <int NPE>
double physical_gradients(const NodeMatrix<NPE>& X, const Eigen::Matrix<double, NPE, 3>& dN,
                          Eigen::Matrix<double, NPE, 3>& G) {
  const Eigen::Matrix3d J = X.transpose() * dN;  // J(i, j) = dx_i / dxi_j
  const double det = J.determinant();
  G.noalias() = dN * J.inverse();
  return det;
}

// Element stiffness of an isotropic solid:
//   K_(a i)(b j) = sum_gp w detJ (lambda G_ai G_bj + mu G_aj G_bi + mu delta_ij G_a . G_b).
// Returns the smallest det J met (<= 0 means inverted or degenerate).
template <int NPE>
double element_stiffness(const NodeMatrix<NPE>& X, const RuleTable<NPE>& rule, double lambda,
                         double mu, Eigen::Matrix<double, 3 * NPE, 3 * NPE>& K) {
  K.setZero();
  Eigen::Matrix<double, NPE, 3> G;
  double min_det = std::numeric_limits<double>::infinity();
  for (size_t q = 0; q < rule.size(); ++q) {
    const double det = physical_gradients<NPE>(X, rule.dN[q], G);
    min_det = std::min(min_det, det);
    const double w = rule.weight[q] * det;
    const Eigen::Matrix<double, NPE, NPE> dot = G * G.transpose();
    for (int b = 0; b < NPE; ++b) {
      for (int a = 0; a <= b; ++a) {
        for (int i = 0; i < 3; ++i) {
          for (int j = 0; j < 3; ++j) {
            double v = lambda * G(a, i) * G(b, j) + mu * G(a, j) * G(b, i);
            if (i == j) v += mu * dot(a, b);
            K(3 * a + i, 3 * b + j) += w * v;
          }
        }
      }
    }
  }
  // Fill the lower node blocks from the upper ones.
  for (int b = 0; b < NPE; ++b)
    for (int a = b + 1; a < NPE; ++a)
      K.template block<3, 3>(3 * a, 3 * b) = K.template block<3, 3>(3 * b, 3 * a).transpose();
  return min_det;
}

// Calls f.template operator()<NPE>() with the node count of `type`, a
// compile-time constant taken from the element table (one instantiation per
// row of all_element_types).
template <typename F>
void dispatch_block(ElementType type, F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    ((type == all_element_types[I]
          ? (f.template operator()<element_facts(all_element_types[I]).nodes>(), true)
          : false) ||
     ...);
  }(std::make_index_sequence<all_element_types.size()>());
}

// True when every mid-edge node of a quadratic element lies at the midpoint
// of its edge (to 1e-10 of the element size): such elements have an affine
// (TET10) or trilinear geometry and their stiffness rule is exact.
template <int NPE>
bool straight_sided(ElementType type, const NodeMatrix<NPE>& X) {
  const int corners = corner_nodes(type);
  if (corners == NPE) return true;
  const double size = (X.colwise().maxCoeff() - X.colwise().minCoeff()).norm();
  for (int m = corners; m < NPE; ++m) {
    const auto ends = edge_corners(type, m);
    if ((X.row(m) - 0.5 * (X.row(ends[0]) + X.row(ends[1]))).norm() > 1e-10 * size) return false;
  }
  return true;
}

// Stiffness rules of a block: the element's own, and for TET10 the
// degree-5 rule used on elements with curved edges.
template <int NPE>
struct StiffnessRules {
  RuleTable<NPE> regular;
  std::optional<RuleTable<NPE>> curved;
  ElementType type;
  explicit StiffnessRules(ElementType t) : regular(t, quadrature(t)), type(t) {
    if (t == ElementType::Tet10) curved.emplace(t, curved_tet_quadrature());
  }
  const RuleTable<NPE>& for_element(const NodeMatrix<NPE>& X) const {
    return curved && !straight_sided<NPE>(type, X) ? *curved : regular;
  }
};

// Lame parameters.
inline void lame(double E, double nu, double& lambda, double& mu) {
  lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  mu = E / (2.0 * (1.0 + nu));
}

}  // namespace kinetofem::fem::detail
