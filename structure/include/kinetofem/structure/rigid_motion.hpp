#pragma once
// Small helpers shared by the condensations of structure/ and the stages and
// modes built on them (pipeline/, vibration/), in namespace detail:
// the rigid transfer and rotation of a 6-component motion, the world
// position of a part's nodes, and the block solve of K_s^-1 B as columns.
// SI units.
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/solver/mesh.hpp"

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

// The 6 x 6 rotation of a (translation, rotation) pair: blockdiag(R, R).
inline Matrix6d rotate6(const Eigen::Matrix3d& R) {
  Matrix6d Q = Matrix6d::Zero();
  Q.block<3, 3>(0, 0) = R;
  Q.block<3, 3>(3, 3) = R;
  return Q;
}

// World coordinates of a part's nodes in the rigid configuration of a frame.
inline post::FieldMatrix world_position(const fem::Mesh& mesh, const mech::BodyFrame& body) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(body.q.z(), Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d origin(body.q.x(), body.q.y(), 0.0);
  post::FieldMatrix X(mesh.node_count(), 3);
  for (fem::Index i = 0; i < mesh.node_count(); ++i) X.row(i) = (R * mesh.nodes.row(i).transpose() + origin).transpose();
  return X;
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
