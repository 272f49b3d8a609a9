#pragma once
// Internal: the sparse machinery shared by every assembled matrix of a part
// (stiffness, consistent mass): the upper-triangle CSC pattern of the free
// DoFs built once from the connectivity, and the scatter of an element
// matrix into it. Both matrices of one part on one DofMap get the same
// pattern, so K - sigma M is a combination of their value arrays.
#include <algorithm>
#include <array>

#include <Eigen/Core>

#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/sparse.hpp"

namespace kinetofem::fem::detail {

// Pattern of the upper triangle of the free-free block (values zeroed).
// Defined in assembly.cpp.
void build_upper_pattern(const Mesh& mesh, const DofMap& dofs, SymmetricUpperMatrix& matrix);

// Adds the element matrix Ae (n x n, DoF order of `eq`) to the upper
// triangle of `matrix` (pattern from build_upper_pattern). eq[p] is the
// equation of local DoF p, -1 when prescribed (skipped). Safe inside an
// OpenMP loop over elements (atomic adds).
template <int N>
void scatter_upper(const std::array<Index, N>& eq, const Eigen::Matrix<double, N, N>& Ae,
                   SymmetricUpperMatrix& matrix) {
  const auto* col_start = matrix.outerIndexPtr();
  const auto* rows = matrix.innerIndexPtr();
  double* values = matrix.valuePtr();
  for (int q = 0; q < N; ++q) {
    const Index col = eq[size_t(q)];
    if (col < 0) continue;
    const auto* begin = rows + col_start[col];
    const auto* end = rows + col_start[col + 1];
    for (int p = 0; p < N; ++p) {
      const Index row = eq[size_t(p)];
      if (row < 0 || row > col) continue;
      const auto* hit = std::lower_bound(begin, end, row);
#pragma omp atomic
      values[hit - rows] += Ae(p, q);
    }
  }
}

}  // namespace kinetofem::fem::detail
