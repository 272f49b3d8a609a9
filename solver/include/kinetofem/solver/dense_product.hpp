#pragma once
// C = A B + beta C for column-major dense matrices, through the machine's
// BLAS dgemm (OpenBLAS, which CHOLMOD links). Why not Eigen's own product:
// the unit-load superposition's products are tall and skinny (6 N x m
// pattern fields times m x b coefficient blocks, m ~ 20, N up to 10^6) and
// dominate the cost of many output times; OpenBLAS runs them several times
// faster than Eigen's generic kernel on this machine (bench/README.md).
// When the process has no room left for the BLAS threads' work buffers
// (below), the product runs in Eigen's own kernel instead: slower, but the
// BLAS would hang. Throws Error for sizes that do not fit.
#include <Eigen/Core>

namespace kinetofem::fem {

void blas_product(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b,
                  Eigen::Ref<Eigen::MatrixXd> c, double beta = 0.0);

// OpenBLAS maps a work buffer per thread when a thread first runs a level-3
// kernel (64 MiB in the x86-64 builds; its BUFFER_SIZE) and, when the mapping
// is refused (an address-space limit, RLIMIT_AS), retries forever: a product
// or a factorization would hang instead of failing. The bytes those buffers
// take for the BLAS threads of this process (blas_threads.hpp):
double blas_buffers_bytes();
// Whether what is left to the process (core/process_memory.hpp) still holds
// them (always without an address-space limit). Once mapped they count as
// used, so under a limit this may say no to buffers that exist: the cost is
// Eigen's slower kernel, never a hang.
bool blas_buffers_fit();

}  // namespace kinetofem::fem
