#pragma once
// Small helpers shared by the condensations of structure/ (private header):
// the rigid transfer of a 6-component motion and the block solve of
// K_s^-1 B as columns. SI units.
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::structure::detail {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The cross-product matrix: skew(v) w = v x w.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

// Motion (translation, rotation) of a point at `arm` from a reference point
// moving by (t, w): (t + w x arm, w) = transfer(arm) (t, w).
inline Matrix6d transfer(const Eigen::Vector3d& arm) {
  Matrix6d T = Matrix6d::Identity();
  T.block<3, 3>(0, 3) = -skew(arm);
  return T;
}

// Columns of K_s^-1 B as 3 N vectors (one block solve).
inline Eigen::MatrixXd solve_columns(fem::LinearStaticAnalysis& analysis, const Eigen::MatrixXd& B) {
  Eigen::MatrixXd X(B.rows(), B.cols());
  if (B.cols() == 0) return X;
  const std::vector<fem::DisplacementField> fields = analysis.solve_forces(B);
  for (Eigen::Index c = 0; c < B.cols(); ++c)
    X.col(c) = Eigen::Map<const Eigen::VectorXd>(fields[size_t(c)].data(), B.rows());
  return X;
}

}  // namespace kinetofem::structure::detail
