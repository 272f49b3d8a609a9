#include "kinetofem/loads/load_patterns.hpp"

#include <algorithm>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::loads {

LoadPatterns::LoadPatterns(const fem::FeModel& model)
    : mesh_(&model.mesh), motion_loads_(model.mesh, fem::element_materials(model)) {
  const fem::Mesh& mesh = model.mesh;
  length_scale_ = std::max(1e-3, (mesh.nodes.colwise().maxCoeff() - mesh.nodes.colwise().minCoeff()).norm());
  const Eigen::MatrixXd& basis = motion_loads_.basis();
  for (int k = 0; k < 12; ++k) {
    Eigen::Vector3d F, M;
    fem::resultant(mesh, basis.col(k), Eigen::Vector3d::Zero(), F, M);
    body_force_resultants_.col(k) << F, M;
  }
}

int LoadPatterns::coupling_on(const std::string& face_set) {
  for (std::size_t j = 0; j < face_sets_.size(); ++j)
    if (face_sets_[j] == face_set) return int(j);
  couplings_.push_back(std::make_unique<fem::DistributingCoupling>(*mesh_, face_set));
  face_sets_.push_back(face_set);
  return int(couplings_.size()) - 1;
}

std::vector<std::string> LoadPatterns::names() const {
  std::vector<std::string> names = {"body_force.c_x", "body_force.c_y", "body_force.c_z"};
  for (const char* row : {"x", "y", "z"})
    for (const char* col : {"x", "y", "z"}) names.push_back(fmt::format("body_force.A_{}{}", row, col));
  for (const auto& face : face_sets_)
    for (const char* c : {"F_x", "F_y", "F_z", "M_x", "M_y", "M_z"}) names.push_back(fmt::format("{}.{}", face, c));
  return names;
}

Eigen::MatrixXd LoadPatterns::forces() const {
  const Eigen::MatrixXd& basis = motion_loads_.basis();
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(basis.rows(), count());
  P.leftCols(12) = basis;
  for (std::size_t j = 0; j < couplings_.size(); ++j)
    for (int k = 0; k < 6; ++k) {
      Vector6d unit = Vector6d::Zero();
      unit[k] = 1.0;
      couplings_[j]->add(unit.head<3>(), unit.tail<3>(), couplings_[j]->centroid(),
                         P.col(12 + 6 * Eigen::Index(j) + k));
    }
  return P;
}

Eigen::VectorXd LoadPatterns::nodal_forces(const BodyForce& body_force, const std::vector<Vector6d>& coupling) const {
  Eigen::VectorXd f = motion_loads_.basis() * body_force;
  for (std::size_t j = 0; j < couplings_.size(); ++j)
    couplings_[j]->add(coupling[j].head<3>(), coupling[j].tail<3>(), couplings_[j]->centroid(), f);
  return f;
}

Eigen::VectorXd LoadPatterns::coefficients(const BodyForce& body_force, const std::vector<Vector6d>& coupling) const {
  Eigen::VectorXd c(count());
  c.head<12>() = body_force;
  for (std::size_t j = 0; j < couplings_.size(); ++j) c.segment<6>(12 + 6 * Eigen::Index(j)) = coupling[j];
  return c;
}

LoadPatterns::Vector6d LoadPatterns::resultant(const BodyForce& body_force,
                                               const std::vector<Vector6d>& coupling) const {
  Vector6d total = body_force_resultants_ * body_force;
  for (std::size_t j = 0; j < couplings_.size(); ++j) {
    const Vector6d& r = coupling[j];
    total.head<3>() += r.head<3>();
    total.tail<3>() += r.tail<3>() + couplings_[j]->centroid().cross(r.head<3>());
  }
  return total;
}

}  // namespace kinetofem::loads
