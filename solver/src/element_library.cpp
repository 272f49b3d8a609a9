#include "kinetofem/solver/element_library.hpp"

#include <array>
#include <cmath>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

namespace {

// Mid-edge nodes as pairs of corners, Gmsh ordering (element_traits.hpp).
constexpr const auto& kTetEdges = element_tables::tet_edges;
constexpr const auto& kHexEdges = element_tables::hex_edges;
constexpr double kHexCorners[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                      {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
constexpr double kQuadCorners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};

std::vector<QuadraturePoint> gauss_legendre_box(int dims, int points) {
  static const double x2[2] = {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)};
  static const double w2[2] = {1.0, 1.0};
  static const double x3[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  static const double w3[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double* x = points == 2 ? x2 : x3;
  const double* w = points == 2 ? w2 : w3;
  std::vector<QuadraturePoint> rule;
  const int kmax = dims == 3 ? points : 1;
  for (int k = 0; k < kmax; ++k)
    for (int j = 0; j < points; ++j)
      for (int i = 0; i < points; ++i)
        rule.push_back({Eigen::Vector3d(x[i], x[j], dims == 3 ? x[k] : 0.0),
                        w[i] * w[j] * (dims == 3 ? w[k] : 1.0)});
  return rule;
}

}  // namespace

const std::vector<QuadraturePoint>& quadrature(ElementType type) {
  static const std::vector<QuadraturePoint> tet1 = {{Eigen::Vector3d(0.25, 0.25, 0.25), 1.0 / 6.0}};
  static const std::vector<QuadraturePoint> tet4 = [] {
    const double a = 0.5854101966249685, b = 0.1381966011250105;
    return std::vector<QuadraturePoint>{{Eigen::Vector3d(b, b, b), 1.0 / 24.0},
                                        {Eigen::Vector3d(a, b, b), 1.0 / 24.0},
                                        {Eigen::Vector3d(b, a, b), 1.0 / 24.0},
                                        {Eigen::Vector3d(b, b, a), 1.0 / 24.0}};
  }();
  static const std::vector<QuadraturePoint> hex2 = gauss_legendre_box(3, 2);
  static const std::vector<QuadraturePoint> hex3 = gauss_legendre_box(3, 3);
  switch (type) {
    case ElementType::Tet4: return tet1;
    case ElementType::Tet10: return tet4;
    case ElementType::Hex8: return hex2;
    case ElementType::Hex20: return hex3;
  }
  return tet1;
}

const std::vector<QuadraturePoint>& curved_tet_quadrature() {
  // 14 points, degree 5, all weights positive (Walkington / Keast): exact
  // for the stiffness integrand of a TET10 with curved edges, whose
  // adj(J)^T dN/dxi terms are cubic.
  static const std::vector<QuadraturePoint> rule = [] {
    std::vector<QuadraturePoint> r;
    const double a = 0.0455037041256496, b = 0.4544962958743504, wab = 0.007091003462846911;
    const double pairs[6][3] = {{a, a, b}, {a, b, a}, {b, a, a}, {a, b, b}, {b, a, b}, {b, b, a}};
    for (const auto& p : pairs) r.push_back({Eigen::Vector3d(p[0], p[1], p[2]), wab});
    for (auto [c, w] : {std::pair{0.0927352503108912, 0.01224884051939366},
                        std::pair{0.3108859192633006, 0.01878132095300264}}) {
      const double d = 1.0 - 3.0 * c;
      r.push_back({Eigen::Vector3d(c, c, c), w});
      r.push_back({Eigen::Vector3d(d, c, c), w});
      r.push_back({Eigen::Vector3d(c, d, c), w});
      r.push_back({Eigen::Vector3d(c, c, d), w});
    }
    return r;
  }();
  return rule;
}

const std::vector<QuadraturePoint>& load_quadrature(ElementType type) {
  // Degree 3 on tetrahedra (Keast, with a negative centroid weight): exact for
  // quadratic shape functions times a linear body-force field (rigid-body
  // inertia loads are affine in x).
  static const std::vector<QuadraturePoint> tet5 = [] {
    const double s = 1.0 / 6.0, h = 0.5;
    return std::vector<QuadraturePoint>{{Eigen::Vector3d(0.25, 0.25, 0.25), -2.0 / 15.0},
                                        {Eigen::Vector3d(s, s, s), 3.0 / 40.0},
                                        {Eigen::Vector3d(h, s, s), 3.0 / 40.0},
                                        {Eigen::Vector3d(s, h, s), 3.0 / 40.0},
                                        {Eigen::Vector3d(s, s, h), 3.0 / 40.0}};
  }();
  switch (element_facts(type).shape) {
    case ElementShape::Tetrahedron: return tet5;
    case ElementShape::Hexahedron: return quadrature(type);
  }
  return quadrature(type);
}

const std::vector<QuadraturePoint>& mass_quadrature(ElementType type) {
  switch (type) {
    case ElementType::Tet4: return load_quadrature(type);     // degree 3 >= 2
    case ElementType::Tet10: return curved_tet_quadrature();  // degree 5 >= 4
    case ElementType::Hex8:                                   // 2x2x2: degree 3 per direction
    case ElementType::Hex20: return quadrature(type);         // 3x3x3: degree 5 per direction
  }
  return quadrature(type);
}

Eigen::MatrixXd corner_extrapolation(ElementType type) {
  const auto& rule = quadrature(type);
  const Eigen::MatrixXd ref = reference_nodes(type);
  const ElementShape shape = element_facts(type).shape;
  const int corners = corner_nodes(type);
  auto basis = [&](const Eigen::Vector3d& x) {
    Eigen::VectorXd p;
    switch (shape) {
      case ElementShape::Tetrahedron:
        p.resize(4);
        p << 1, x[0], x[1], x[2];
        break;
      case ElementShape::Hexahedron:
        p.resize(8);
        p << 1, x[0], x[1], x[2], x[0] * x[1], x[1] * x[2], x[2] * x[0], x[0] * x[1] * x[2];
        break;
    }
    return p;
  };
  const int g = int(rule.size());
  if (g == 1) return Eigen::MatrixXd::Ones(corners, 1);  // TET4: constant stress
  const int m = int(basis(rule[0].xi).size());
  Eigen::MatrixXd P(g, m);
  for (int q = 0; q < g; ++q) P.row(q) = basis(rule[size_t(q)].xi).transpose();
  const Eigen::MatrixXd fit = P.completeOrthogonalDecomposition().pseudoInverse();  // m x g
  Eigen::MatrixXd E(corners, g);
  for (int a = 0; a < corners; ++a) E.row(a) = basis(ref.row(a).transpose()).transpose() * fit;
  return E;
}

const std::vector<QuadraturePoint>& quadrature(FaceType type) {
  static const std::vector<QuadraturePoint> tri1 = {
      {Eigen::Vector3d(1.0 / 3.0, 1.0 / 3.0, 0.0), 0.5}};
  static const std::vector<QuadraturePoint> tri3 = {
      {Eigen::Vector3d(1.0 / 6.0, 1.0 / 6.0, 0.0), 1.0 / 6.0},
      {Eigen::Vector3d(2.0 / 3.0, 1.0 / 6.0, 0.0), 1.0 / 6.0},
      {Eigen::Vector3d(1.0 / 6.0, 2.0 / 3.0, 0.0), 1.0 / 6.0}};
  static const std::vector<QuadraturePoint> quad2 = gauss_legendre_box(2, 2);
  static const std::vector<QuadraturePoint> quad3 = gauss_legendre_box(2, 3);
  switch (type) {
    case FaceType::Tri3: return tri1;
    case FaceType::Tri6: return tri3;
    case FaceType::Quad4: return quad2;
    case FaceType::Quad8: return quad3;
  }
  return tri1;
}

void shape_functions(ElementType type, const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                     Eigen::MatrixXd& dN) {
  const int n = nodes_per_element(type);
  N.resize(n);
  dN.resize(n, 3);
  if (type == ElementType::Tet4 || type == ElementType::Tet10) {
    // Barycentric coordinates L0 = 1 - xi - eta - zeta, L1 = xi, L2 = eta, L3 = zeta.
    const double L[4] = {1.0 - xi[0] - xi[1] - xi[2], xi[0], xi[1], xi[2]};
    const double dL[4][3] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    if (type == ElementType::Tet4) {
      for (int a = 0; a < 4; ++a) {
        N[a] = L[a];
        for (int d = 0; d < 3; ++d) dN(a, d) = dL[a][d];
      }
      return;
    }
    for (int a = 0; a < 4; ++a) {
      N[a] = L[a] * (2.0 * L[a] - 1.0);
      for (int d = 0; d < 3; ++d) dN(a, d) = (4.0 * L[a] - 1.0) * dL[a][d];
    }
    for (int e = 0; e < 6; ++e) {
      const int i = kTetEdges[e][0], j = kTetEdges[e][1];
      N[4 + e] = 4.0 * L[i] * L[j];
      for (int d = 0; d < 3; ++d) dN(4 + e, d) = 4.0 * (dL[i][d] * L[j] + L[i] * dL[j][d]);
    }
    return;
  }
  if (type == ElementType::Hex8) {
    for (int a = 0; a < 8; ++a) {
      const double* c = kHexCorners[a];
      const double f[3] = {1 + c[0] * xi[0], 1 + c[1] * xi[1], 1 + c[2] * xi[2]};
      N[a] = 0.125 * f[0] * f[1] * f[2];
      dN(a, 0) = 0.125 * c[0] * f[1] * f[2];
      dN(a, 1) = 0.125 * f[0] * c[1] * f[2];
      dN(a, 2) = 0.125 * f[0] * f[1] * c[2];
    }
    return;
  }
  // HEX20 (serendipity): corners, then mid-edge nodes.
  for (int a = 0; a < 8; ++a) {
    const double* c = kHexCorners[a];
    const double f[3] = {1 + c[0] * xi[0], 1 + c[1] * xi[1], 1 + c[2] * xi[2]};
    const double s = c[0] * xi[0] + c[1] * xi[1] + c[2] * xi[2] - 2.0;
    N[a] = 0.125 * f[0] * f[1] * f[2] * s;
    dN(a, 0) = 0.125 * c[0] * (f[1] * f[2] * s + f[0] * f[1] * f[2]);
    dN(a, 1) = 0.125 * c[1] * (f[0] * f[2] * s + f[0] * f[1] * f[2]);
    dN(a, 2) = 0.125 * c[2] * (f[0] * f[1] * s + f[0] * f[1] * f[2]);
  }
  for (int e = 0; e < 12; ++e) {
    const double* p = kHexCorners[kHexEdges[e][0]];
    const double* q = kHexCorners[kHexEdges[e][1]];
    double c[3];
    int zero_axis = 0;
    for (int d = 0; d < 3; ++d) {
      c[d] = 0.5 * (p[d] + q[d]);
      if (c[d] == 0.0) zero_axis = d;
    }
    // N = 1/4 (1 - xi_k^2) prod_{d != k} (1 + c_d xi_d), k the edge's axis.
    double value = 0.25 * (1.0 - xi[zero_axis] * xi[zero_axis]);
    double grad[3];
    for (int d = 0; d < 3; ++d) {
      if (d == zero_axis) continue;
      value *= 1.0 + c[d] * xi[d];
    }
    for (int d = 0; d < 3; ++d) {
      double g = 0.25;
      for (int k = 0; k < 3; ++k) {
        if (k == zero_axis)
          g *= (k == d) ? -2.0 * xi[k] : 1.0 - xi[k] * xi[k];
        else
          g *= (k == d) ? c[k] : 1.0 + c[k] * xi[k];
      }
      grad[d] = g;
    }
    N[8 + e] = value;
    for (int d = 0; d < 3; ++d) dN(8 + e, d) = grad[d];
  }
}

void shape_functions(FaceType type, const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                     Eigen::MatrixXd& dN) {
  const int n = nodes_per_face(type);
  N.resize(n);
  dN.resize(n, 2);
  if (type == FaceType::Tri3 || type == FaceType::Tri6) {
    const double L[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
    const double dL[3][2] = {{-1, -1}, {1, 0}, {0, 1}};
    if (type == FaceType::Tri3) {
      for (int a = 0; a < 3; ++a) {
        N[a] = L[a];
        dN(a, 0) = dL[a][0];
        dN(a, 1) = dL[a][1];
      }
      return;
    }
    for (int a = 0; a < 3; ++a) {
      N[a] = L[a] * (2.0 * L[a] - 1.0);
      for (int d = 0; d < 2; ++d) dN(a, d) = (4.0 * L[a] - 1.0) * dL[a][d];
    }
    for (int e = 0; e < 3; ++e) {
      const int i = e, j = (e + 1) % 3;
      N[3 + e] = 4.0 * L[i] * L[j];
      for (int d = 0; d < 2; ++d) dN(3 + e, d) = 4.0 * (dL[i][d] * L[j] + L[i] * dL[j][d]);
    }
    return;
  }
  if (type == FaceType::Quad4) {
    for (int a = 0; a < 4; ++a) {
      const double* c = kQuadCorners[a];
      N[a] = 0.25 * (1 + c[0] * xi[0]) * (1 + c[1] * xi[1]);
      dN(a, 0) = 0.25 * c[0] * (1 + c[1] * xi[1]);
      dN(a, 1) = 0.25 * (1 + c[0] * xi[0]) * c[1];
    }
    return;
  }
  // QUAD8: corners, then mid-edge nodes 4 (0-1), 5 (1-2), 6 (2-3), 7 (3-0).
  for (int a = 0; a < 4; ++a) {
    const double* c = kQuadCorners[a];
    const double f0 = 1 + c[0] * xi[0], f1 = 1 + c[1] * xi[1];
    const double s = c[0] * xi[0] + c[1] * xi[1] - 1.0;
    N[a] = 0.25 * f0 * f1 * s;
    dN(a, 0) = 0.25 * c[0] * f1 * (s + f0);
    dN(a, 1) = 0.25 * c[1] * f0 * (s + f1);
  }
  for (int e = 0; e < 4; ++e) {
    const double* p = kQuadCorners[e];
    const double* q = kQuadCorners[(e + 1) % 4];
    const double c[2] = {0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])};
    if (c[0] == 0.0) {
      N[4 + e] = 0.5 * (1 - xi[0] * xi[0]) * (1 + c[1] * xi[1]);
      dN(4 + e, 0) = -xi[0] * (1 + c[1] * xi[1]);
      dN(4 + e, 1) = 0.5 * (1 - xi[0] * xi[0]) * c[1];
    } else {
      N[4 + e] = 0.5 * (1 - xi[1] * xi[1]) * (1 + c[0] * xi[0]);
      dN(4 + e, 0) = 0.5 * (1 - xi[1] * xi[1]) * c[0];
      dN(4 + e, 1) = -xi[1] * (1 + c[0] * xi[0]);
    }
  }
}

Eigen::MatrixXd reference_nodes(ElementType type) {
  // Corners of the reference cell, then each mid-edge node halfway along its edge.
  static constexpr double tet_corners[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const ElementFacts& facts = element_facts(type);
  Eigen::MatrixXd X(facts.nodes, 3);
  for (int a = 0; a < facts.corners; ++a) {
    const double* corner = nullptr;
    switch (facts.shape) {
      case ElementShape::Tetrahedron: corner = tet_corners[a]; break;
      case ElementShape::Hexahedron: corner = kHexCorners[a]; break;
    }
    X.row(a) << corner[0], corner[1], corner[2];
  }
  for (int m = facts.corners; m < facts.nodes; ++m) {
    const auto& edge = facts.edges[size_t(m - facts.corners)];
    X.row(m) = 0.5 * (X.row(edge[0]) + X.row(edge[1]));
  }
  return X;
}

std::array<int, 2> edge_corners(ElementType type, int mid_node) {
  const ElementFacts& facts = element_facts(type);
  require(mid_node >= facts.corners && mid_node < facts.nodes, "{} has no mid-edge node {}",
          facts.name, mid_node);
  return facts.edges[size_t(mid_node - facts.corners)];
}

}  // namespace kinetofem::fem
