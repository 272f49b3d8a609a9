#pragma once
// Gauss integration over boundary faces (internal to the solver library).
#include <span>
#include <vector>

#include <Eigen/Geometry>

#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem::detail {

// Calls visit(nodes of the face, reference coordinates xi of the point, N at
// the point, x at the point (m), area weight dA = w |t1 x t2| (m^2)) for
// every Gauss point of every face.
template <typename Visit>
void for_each_face_quadrature_point(const Mesh& mesh, const std::vector<FaceBlock>& faces, Visit&& visit) {
  Eigen::VectorXd N;
  Eigen::MatrixXd dN;
  for (const auto& block : faces) {
    const int n = nodes_per_face(block.type);
    for (Index f = 0; f < block.size(); ++f) {
      const auto nodes = block.face(f);
      Eigen::MatrixXd X(n, 3);
      for (int a = 0; a < n; ++a) X.row(a) = mesh.nodes.row(nodes[size_t(a)]);
      for (const auto& qp : quadrature(block.type)) {
        shape_functions(block.type, qp.xi, N, dN);
        const Eigen::Vector3d t1 = X.transpose() * dN.col(0), t2 = X.transpose() * dN.col(1);
        const Eigen::Vector3d x = X.transpose() * N;
        visit(nodes, qp.xi, N, x, qp.weight * t1.cross(t2).norm());
      }
    }
  }
}

// The same without the reference coordinates: visit(nodes, N, x, dA).
template <typename Visit>
void for_each_face_point(const Mesh& mesh, const std::vector<FaceBlock>& faces, Visit&& visit) {
  for_each_face_quadrature_point(mesh, faces, [&](std::span<const Index> nodes, const Eigen::Vector3d&,
                                                  const Eigen::VectorXd& N, const Eigen::Vector3d& x, double dA) {
    visit(nodes, N, x, dA);
  });
}

}  // namespace kinetofem::fem::detail
