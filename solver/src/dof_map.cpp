#include "kinetofem/solver/dof_map.hpp"

#include <cmath>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

DofMap::DofMap(Index node_count, const std::vector<DisplacementSupport>& supports)
    : equation_(size_t(3 * node_count), 0), prescribed_(Eigen::VectorXd::Zero(3 * node_count)) {
  std::vector<char> is_prescribed(size_t(3 * node_count), 0);
  for (const auto& support : supports) {
    for (int c = 0; c < 3; ++c)
      require(std::isfinite(support.value_m[c]), "support '{}': prescribed value is not finite",
              support.label);
    for (Index node : support.nodes) {
      require(node >= 0 && node < node_count, "support '{}' names node {} (mesh has {} nodes)",
              support.label, node, node_count);
      for (int c = 0; c < 3; ++c) {
        if (!support.fixed[size_t(c)]) continue;
        const Index dof = 3 * node + c;
        if (is_prescribed[size_t(dof)] && prescribed_[dof] != support.value_m[c])
          fail("support '{}' prescribes {} m on node {} component {}, which another support "
               "already set to {} m",
               support.label, support.value_m[c], node, "xyz"[c], prescribed_[dof]);
        is_prescribed[size_t(dof)] = 1;
        prescribed_[dof] = support.value_m[c];
      }
    }
  }
  Index next = 0;
  for (size_t dof = 0; dof < equation_.size(); ++dof)
    equation_[dof] = is_prescribed[dof] ? -1 : next++;
  free_count_ = next;
}

Eigen::VectorXd DofMap::expand(const Eigen::Ref<const Eigen::VectorXd>& free_values) const {
  require(free_values.size() == free_count_, "free DoF vector has {} entries, expected {}",
          free_values.size(), free_count_);
  Eigen::VectorXd full = prescribed_;
  for (size_t dof = 0; dof < equation_.size(); ++dof)
    if (equation_[dof] >= 0) full[Index(dof)] = free_values[equation_[dof]];
  return full;
}

}  // namespace kinetofem::fem
