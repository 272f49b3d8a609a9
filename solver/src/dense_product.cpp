#include "kinetofem/solver/dense_product.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <cstddef>
#include <limits>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/solver/blas_threads.hpp"

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k,
                       const double* alpha, const double* a, const int* lda, const double* b, const int* ldb,
                       const double* beta, double* c, const int* ldc);

namespace kinetofem::fem {

void blas_product(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b,
                  Eigen::Ref<Eigen::MatrixXd> c, double beta) {
  require(a.cols() == b.rows() && c.rows() == a.rows() && c.cols() == b.cols(),
          "blas_product: ({} x {}) times ({} x {}) into ({} x {})", a.rows(), a.cols(), b.rows(), b.cols(), c.rows(),
          c.cols());
  if (c.size() == 0) return;
  if (a.cols() == 0) {
    c *= beta;
    return;
  }
  constexpr Eigen::Index kMax = std::numeric_limits<int>::max();
  require(a.rows() <= kMax && a.cols() <= kMax && b.cols() <= kMax && a.outerStride() <= kMax &&
              b.outerStride() <= kMax && c.outerStride() <= kMax,
          "blas_product: a dimension exceeds the BLAS integer range");
  if (!blas_buffers_fit()) {
    // Eigen's own kernel needs no BLAS thread buffers (header).
    if (beta == 0.0)
      c.noalias() = a * b;
    else {
      c *= beta;
      c.noalias() += a * b;
    }
    return;
  }
  const int m = int(a.rows()), n = int(b.cols()), k = int(a.cols());
  const int lda = int(a.outerStride()), ldb = int(b.outerStride()), ldc = int(c.outerStride());
  const double one = 1.0;
  dgemm_("N", "N", &m, &n, &k, &one, a.data(), &lda, b.data(), &ldb, &beta, c.data(), &ldc);
}

double blas_buffers_bytes() {
  constexpr double kBlasBufferBytesPerThread = double(std::size_t(64) << 20);
  return kBlasBufferBytesPerThread * std::max(1, BlasThreadLimit::threads());
}

bool blas_buffers_fit() {
  // Without an address-space limit the buffers' mapping is not refused (the
  // kernel overcommits), and the check costs one system call.
  rlimit limit{};
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur == RLIM_INFINITY) return true;
  return memory_available_to_process().bytes >= blas_buffers_bytes();
}

}  // namespace kinetofem::fem
