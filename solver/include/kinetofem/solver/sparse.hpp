#pragma once
// Sparse matrix type of the solver: compressed sparse column, 64-bit indices
// (models of several million DoFs), holding only the UPPER triangle of a
// symmetric matrix (row <= column), which is what CHOLMOD reads with stype = +1.
#include <cstdint>

#include <Eigen/SparseCore>

namespace kinetofem::fem {

using SymmetricUpperMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, std::int64_t>;

}  // namespace kinetofem::fem
