#include "kinetofem/solver/stress_recovery.hpp"

#include <cmath>

#include <Eigen/Eigenvalues>

#include "element_kernels.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

namespace {

// Strain (Voigt, engineering shear) from physical gradients and element displacements.
template <int NPE>
Vector6d strain_at(const Eigen::Matrix<double, NPE, 3>& G, const Eigen::Matrix<double, NPE, 3>& U) {
  const Eigen::Matrix3d grad = U.transpose() * G;  // du_i / dx_j
  Vector6d e;
  e << grad(0, 0), grad(1, 1), grad(2, 2), grad(0, 1) + grad(1, 0), grad(1, 2) + grad(2, 1),
      grad(2, 0) + grad(0, 2);
  return e;
}

}  // namespace

GaussPointStress gauss_point_stress(const Mesh& mesh, const ElementMaterials& materials,
                                    const DisplacementField& displacement) {
  require(displacement.rows() == mesh.node_count(), "displacement has {} rows, mesh {} nodes",
          displacement.rows(), mesh.node_count());
  std::vector<Matrix6d> D_of;  // by material index
  for (const IsotropicMaterial& m : materials.materials()) D_of.push_back(m.elasticity_matrix());
  GaussPointStress out;
  out.first_point_of_element.push_back(0);
  for (const auto& block : mesh.blocks)
    for (Index e = 0; e < block.size(); ++e)
      out.first_point_of_element.push_back(out.first_point_of_element.back() +
                                           Index(quadrature(block.type).size()));
  const Index total = out.first_point_of_element.back();
  out.points_m.resize(total, 3);
  out.stress_pa.resize(total, 6);
  Index first_element = 0;
  for (const auto& block : mesh.blocks) {
    detail::dispatch_block(block.type, [&]<int NPE>() {
      const detail::RuleTable<NPE> rule(block.type, quadrature(block.type));
#pragma omp parallel for schedule(static)
      for (Index e = 0; e < block.size(); ++e) {
        const auto nodes = block.element(e);
        const auto X = detail::element_coordinates<NPE>(mesh, nodes);
        const Matrix6d& D = D_of[size_t(materials.index_of(first_element + e))];
        Eigen::Matrix<double, NPE, 3> U, G;
        for (int a = 0; a < NPE; ++a) U.row(a) = displacement.row(nodes[size_t(a)]);
        Index row = out.first_point_of_element[size_t(first_element + e)];
        for (size_t q = 0; q < rule.size(); ++q, ++row) {
          detail::physical_gradients<NPE>(X, rule.dN[q], G);
          out.points_m.row(row) = (X.transpose() * rule.N[q]).transpose();
          out.stress_pa.row(row) = (D * strain_at<NPE>(G, U)).transpose();
        }
      }
    });
    first_element += block.size();
  }
  return out;
}

NodalStress recover_nodal_stress(const Mesh& mesh, const ElementMaterials& materials,
                                 const DisplacementField& displacement) {
  const GaussPointStress gp = gauss_point_stress(mesh, materials, displacement);
  const Index n = mesh.node_count();
  StressField sum = StressField::Zero(n, 6);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(n);
  Index first_element = 0;
  for (const auto& block : mesh.blocks) {
    const Eigen::MatrixXd E = corner_extrapolation(block.type);
    const int corners = corner_nodes(block.type);
    const int npe = nodes_per_element(block.type);
    // Serial scatter: cheap next to the Gauss-point stresses, and race-free.
    for (Index e = 0; e < block.size(); ++e) {
      const auto nodes = block.element(e);
      const Index first = gp.first_point_of_element[size_t(first_element + e)];
      const Eigen::MatrixXd corner_stress = E * gp.stress_pa.middleRows(first, E.cols());
      for (int a = 0; a < corners; ++a) {
        sum.row(nodes[size_t(a)]) += corner_stress.row(a);
        count[nodes[size_t(a)]] += 1.0;
      }
      for (int m = corners; m < npe; ++m) {
        const auto ends = edge_corners(block.type, m);
        sum.row(nodes[size_t(m)]) += 0.5 * (corner_stress.row(ends[0]) + corner_stress.row(ends[1]));
        count[nodes[size_t(m)]] += 1.0;
      }
    }
    first_element += block.size();
  }
  NodalStress out;
  out.stress_pa.resize(n, 6);
  out.von_mises_pa.resize(n);
  out.principal_pa.resize(n, 3);
#pragma omp parallel for schedule(static)
  for (Index i = 0; i < n; ++i) {
    const Vector6d s = count[i] > 0 ? Vector6d(sum.row(i).transpose() / count[i]) : Vector6d::Zero();
    out.stress_pa.row(i) = s.transpose();
    out.von_mises_pa[i] = von_mises(s);
    out.principal_pa.row(i) = principal_stresses(s).transpose();
  }
  return out;
}

double von_mises(const Vector6d& s) {
  const double dxy = s[0] - s[1], dyz = s[1] - s[2], dzx = s[2] - s[0];
  return std::sqrt(0.5 * (dxy * dxy + dyz * dyz + dzx * dzx) +
                   3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
}

Eigen::Vector3d principal_stresses(const Vector6d& s) {
  Eigen::Matrix3d T;
  T << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(T, Eigen::EigenvaluesOnly);
  const Eigen::Vector3d ascending = solver.eigenvalues();
  return Eigen::Vector3d(ascending[2], ascending[1], ascending[0]);
}

Eigen::VectorXd displacement_magnitude(const DisplacementField& displacement) {
  return displacement.rowwise().norm();
}

}  // namespace kinetofem::fem
