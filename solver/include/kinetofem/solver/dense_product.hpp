#pragma once
// C = A B + beta C for column-major dense matrices, through the machine's
// BLAS dgemm (OpenBLAS, which CHOLMOD links). Why not Eigen's own product:
// the unit-load superposition's products are tall and skinny (6 N x m
// pattern fields times m x b coefficient blocks, m ~ 20, N up to 10^6) and
// dominate the cost of many output times; OpenBLAS runs them several times
// faster than Eigen's generic kernel on this machine (bench/README.md).
// Throws Error for sizes that do not fit.
#include <Eigen/Core>

namespace kinetofem::fem {

void blas_product(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b,
                  Eigen::Ref<Eigen::MatrixXd> c, double beta = 0.0);

}  // namespace kinetofem::fem
