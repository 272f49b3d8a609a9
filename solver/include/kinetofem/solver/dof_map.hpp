#pragma once
// DofMap — numbering of the 3 displacement DoFs per node (DoF 3*node + c,
// c = x, y, z) into free equations 0..n_free-1; prescribed DoFs get -1 and
// keep their prescribed value.
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::fem {

class DofMap {
 public:
  // Throws Error if a support names a node out of range, or if two supports
  // prescribe different values on the same DoF.
  DofMap(Index node_count, const std::vector<DisplacementSupport>& supports);

  Index dof_count() const { return Index(equation_.size()); }
  Index free_count() const { return free_count_; }
  Index prescribed_count() const { return dof_count() - free_count_; }
  // Equation number of a DoF, or -1 when prescribed.
  Index equation(Index dof) const { return equation_[size_t(dof)]; }
  const std::vector<Index>& equations() const { return equation_; }
  // Prescribed value of every DoF (0 for free DoFs), m.
  const Eigen::VectorXd& prescribed_values() const { return prescribed_; }

  // Full DoF vector (n_dof) from free values, filling in prescribed values.
  Eigen::VectorXd expand(const Eigen::Ref<const Eigen::VectorXd>& free_values) const;

 private:
  std::vector<Index> equation_;
  Eigen::VectorXd prescribed_;
  Index free_count_ = 0;
};

}  // namespace kinetofem::fem
