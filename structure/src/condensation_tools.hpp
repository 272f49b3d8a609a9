#pragma once
// Pieces shared by the condensed elastic assemblies of structure/ (the planar
// ElasticAssembly and the SpatialElasticAssembly), in namespace detail: the
// scaling of their small dense pose system and the nodal stress of solved
// columns.
#include <algorithm>
#include <cmath>

#include <Eigen/Core>

#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::structure::detail {

// Ruiz equilibration of As (at most 30 sweeps, until every row and column
// maximum is within 1e-3 of 1); Dr and Dc take on the row and column scalings.
inline void ruiz_equilibrate(Eigen::MatrixXd& As, Eigen::VectorXd& Dr, Eigen::VectorXd& Dc) {
  const Eigen::Index n = As.rows();
  for (int it = 0; it < 30; ++it) {
    const Eigen::VectorXd rmax = As.cwiseAbs().rowwise().maxCoeff(),
                          cmax = As.cwiseAbs().colwise().maxCoeff().transpose();
    double worst = 0.0;
    Eigen::VectorXd sr(n), sc(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      sr(i) = rmax(i) > 0 ? 1.0 / std::sqrt(rmax(i)) : 1.0;
      sc(i) = cmax(i) > 0 ? 1.0 / std::sqrt(cmax(i)) : 1.0;
      worst = std::max({worst, std::abs(1.0 - rmax(i)), std::abs(1.0 - cmax(i))});
    }
    if (worst < 1e-3) break;
    As = sr.asDiagonal() * As * sc.asDiagonal();
    Dr = Dr.cwiseProduct(sr);
    Dc = Dc.cwiseProduct(sc);
  }
}

// The nodal stress (6N, node-major Voigt, Pa) of each displacement column of
// Z (3N each, m).
inline Eigen::MatrixXd nodal_stress_columns(const fem::Mesh& mesh, const fem::ElementMaterials& materials,
                                            const Eigen::MatrixXd& Z) {
  const fem::Index N = mesh.node_count();
  Eigen::MatrixXd S(6 * N, Z.cols());
  for (Eigen::Index k = 0; k < Z.cols(); ++k) {
    const fem::DisplacementField u = Eigen::Map<const fem::DisplacementField>(Z.col(k).data(), N, 3);
    S.col(k) = Eigen::Map<const Eigen::VectorXd>(fem::recover_nodal_stress(mesh, materials, u).stress_pa.data(), 6 * N);
  }
  return S;
}

}  // namespace kinetofem::structure::detail
