#include "kinetofem/solver/cholmod_solver.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>

#include <cholmod.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/solver/blas_threads.hpp"
#include "kinetofem/solver/dense_product.hpp"

namespace kinetofem::fem {

namespace {

// The share of the memory left to the process that a factor may take by default.
constexpr double kFactorShareOfMemory = 0.8;

// The BLAS threads' work buffers (dense_product.hpp: refused, they hang the
// factorization) are kept out of the factor's share.
// The memory a factor may take by default: a share of what is left after the BLAS buffers.
double factor_share_bytes(const MemoryBudget& budget) {
  return kFactorShareOfMemory * std::max(0.0, budget.bytes - blas_buffers_bytes());
}

// Why the factor limit is what it is, for the error message.
std::string factor_limit_reason(const CholmodOptions& options) {
  const MemoryBudget budget = memory_available_to_process();
  const double share = factor_share_bytes(budget);
  if (options.max_factor_bytes > 0 && options.max_factor_bytes <= share) return "solver.max_factor_gb";
  // e.g. "80 % of the 0.0774 GB left by the address-space limit (RLIMIT_AS, ulimit -v) of 0.461 GB, 0.384 GB
  // of it mapped, less 0.134 GB for 2 BLAS threads' buffers"
  return fmt::format("80 % of the {:.3g} GB left by {}, less {:.3g} GB for {} BLAS threads' buffers{}",
                     budget.bytes * 1e-9, budget.limited_by, blas_buffers_bytes() * 1e-9,
                     std::max(1, BlasThreadLimit::threads()),
                     options.max_factor_bytes > 0 ? "; below solver.max_factor_gb" : "");
}

const char* status_text(int status) {
  switch (status) {
    case CHOLMOD_OK: return "ok";
    case CHOLMOD_NOT_INSTALLED: return "method not installed";
    case CHOLMOD_OUT_OF_MEMORY: return "out of memory";
    case CHOLMOD_TOO_LARGE: return "integer overflow (problem too large)";
    case CHOLMOD_INVALID: return "invalid input";
    case CHOLMOD_GPU_PROBLEM: return "GPU problem";
    case CHOLMOD_NOT_POSDEF: return "matrix not positive definite";
    case CHOLMOD_DSMALL: return "tiny diagonal entry";
    default: return "unknown status";
  }
}

const char* ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    default: return "other";
  }
}

}  // namespace

double factor_memory_limit_bytes(const CholmodOptions& options) {
  // Never more than the process can get: an allocation past RLIMIT_AS or the
  // cgroup limit is refused (or the process killed) in the middle of the factorization.
  const double share = factor_share_bytes(memory_available_to_process());
  return options.max_factor_bytes > 0 ? std::min(options.max_factor_bytes, share) : share;
}

struct CholmodSolver::Impl {
  cholmod_common common{};
  cholmod_factor* factor = nullptr;
  cholmod_sparse view{};  // non-owning view of the caller's matrix
  const SymmetricUpperMatrix* matrix = nullptr;

  Impl() {
    cholmod_l_start(&common);
    common.error_handler = nullptr;  // we check every status ourselves
    common.print = 0;
    common.supernodal = CHOLMOD_SUPERNODAL;
    common.final_ll = 1;
  }
  ~Impl() {
    if (factor) cholmod_l_free_factor(&factor, &common);
    cholmod_l_finish(&common);
  }

  // Throws unless the last CHOLMOD call left an acceptable status.
  void check(const char* function) const {
    if (common.status < CHOLMOD_OK)
      fail("CHOLMOD {} failed: {} (status {})", function, status_text(common.status),
           common.status);
  }

  void wrap(const SymmetricUpperMatrix& A) {
    require(A.rows() == A.cols(), "CHOLMOD: matrix is {} x {}, not square", A.rows(), A.cols());
    require(A.isCompressed(), "CHOLMOD: matrix must be in compressed storage");
    view = cholmod_sparse{};
    view.nrow = size_t(A.rows());
    view.ncol = size_t(A.cols());
    view.nzmax = size_t(A.nonZeros());
    view.p = const_cast<std::int64_t*>(A.outerIndexPtr());
    view.i = const_cast<std::int64_t*>(A.innerIndexPtr());
    view.x = const_cast<double*>(A.valuePtr());
    view.stype = 1;  // upper triangle stored
    view.itype = CHOLMOD_LONG;
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    view.sorted = 1;
    view.packed = 1;
    matrix = &A;
    norm = -1.0;  // a new matrix: its norm is computed at the next solve
  }
  // ||K||_1 (= ||K||_inf, symmetric) from the stored upper triangle, once per
  // matrix: the scale of a solve's normwise backward error.
  double norm = -1.0;
  double matrix_norm() {
    if (norm >= 0) return norm;
    Eigen::VectorXd column_sum = Eigen::VectorXd::Zero(matrix->cols());
    for (Eigen::Index j = 0; j < matrix->outerSize(); ++j)
      for (SymmetricUpperMatrix::InnerIterator it(*matrix, j); it; ++it) {
        column_sum(it.col()) += std::abs(it.value());
        if (it.row() != it.col()) column_sum(it.row()) += std::abs(it.value());
      }
    norm = column_sum.size() > 0 ? column_sum.maxCoeff() : 0.0;
    return norm;
  }
};

CholmodSolver::CholmodSolver(CholmodOptions options, const Log* log)
    : impl_(std::make_unique<Impl>()), options_(options), log_(log) {
  switch (options_.ordering) {
    case CholmodOptions::Ordering::NodeGraphMetis:  // without a given ordering: CHOLMOD's METIS
    case CholmodOptions::Ordering::Metis:
      impl_->common.nmethods = 1;
      impl_->common.method[0].ordering = CHOLMOD_METIS;
      impl_->common.postorder = 1;
      break;
    case CholmodOptions::Ordering::Amd:
      impl_->common.nmethods = 1;
      impl_->common.method[0].ordering = CHOLMOD_AMD;
      impl_->common.postorder = 1;
      break;
    case CholmodOptions::Ordering::Best:
      impl_->common.nmethods = 0;  // CHOLMOD's default strategy: AMD, then METIS if better
      break;
  }
  for (int k = 0; k < 3; ++k) {
    impl_->common.nrelax[k] = std::size_t(options_.relax_columns[k]);
    impl_->common.zrelax[k] = options_.relax_zero_fraction[k];
  }
}

CholmodSolver::~CholmodSolver() = default;

void CholmodSolver::analyze(const SymmetricUpperMatrix& matrix) { analyze_with(matrix, nullptr); }

void CholmodSolver::analyze(const SymmetricUpperMatrix& matrix, const GivenOrdering& ordering) {
  analyze_with(matrix, &ordering);
}

void CholmodSolver::analyze_with(const SymmetricUpperMatrix& matrix, const GivenOrdering* given) {
  Stopwatch clock;
  impl_->wrap(matrix);
  if (impl_->factor) cholmod_l_free_factor(&impl_->factor, &impl_->common);
  if (given) {
    // A permutation of 0..n-1, checked here so that a bad one is named as
    // such (CHOLMOD would only say "invalid input").
    const auto n = std::int64_t(matrix.rows());
    const auto& p = given->permutation;
    require(std::int64_t(p.size()) == n,
            "CHOLMOD analyze: the given ordering '{}' has {} entries, the matrix {} equations",
            given->name, p.size(), n);
    std::vector<char> seen(size_t(n), 0);
    for (std::int64_t k = 0; k < n; ++k) {
      const std::int64_t e = p[size_t(k)];
      require(e >= 0 && e < n && !seen[size_t(e)],
              "CHOLMOD analyze: the given ordering '{}' is not a permutation (entry {} is {})",
              given->name, k, e);
      seen[size_t(e)] = 1;
    }
    // Only the given permutation (then CHOLMOD's postorder of its etree); the
    // configured methods are restored afterwards for a later analyze(matrix).
    static_assert(sizeof(SuiteSparse_long) == sizeof(std::int64_t));
    cholmod_common& c = impl_->common;
    const int nmethods = c.nmethods, method0 = c.method[0].ordering, postorder = c.postorder;
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_GIVEN;
    c.postorder = 1;
    impl_->factor = cholmod_l_analyze_p(
        &impl_->view,
        const_cast<SuiteSparse_long*>(reinterpret_cast<const SuiteSparse_long*>(p.data())),
        nullptr, 0, &c);
    c.nmethods = nmethods;
    c.method[0].ordering = method0;
    c.postorder = postorder;
    impl_->check("cholmod_l_analyze_p");
    require(impl_->factor != nullptr, "CHOLMOD cholmod_l_analyze_p returned no factor");
  } else {
    impl_->factor = cholmod_l_analyze(&impl_->view, &impl_->common);
    impl_->check("cholmod_l_analyze");
    require(impl_->factor != nullptr, "CHOLMOD cholmod_l_analyze returned no factor");
  }
  stats_ = CholmodStatistics{};
  stats_.equations = matrix.rows();
  stats_.matrix_nonzeros = matrix.nonZeros();
  stats_.factor_nonzeros = impl_->common.lnz;
  stats_.factorization_flops = impl_->common.fl;
  stats_.ordering = given ? given->name : ordering_name(impl_->factor->ordering);
  // Supernodal numeric factor: xsize doubles of values plus the integer
  // structure already allocated by the symbolic analysis.
  const double values = impl_->factor->is_super ? double(impl_->factor->xsize)
                                                : impl_->common.lnz;
  stats_.factor_bytes = values * sizeof(double);
  stats_.ordering_seconds = given ? given->seconds : 0.0;
  stats_.analyze_seconds = clock.seconds() + stats_.ordering_seconds;
  const double limit = factor_memory_limit_bytes(options_);
  if (stats_.factor_bytes > limit)
    // {:.3g}: a small limit (0.001 GB) must not print as "0.0 GB".
    fail("the Cholesky factor of this {}-equation system needs {:.3g} GB (symbolic analysis, "
         "{} ordering), more than the {:.3g} GB allowed: coarsen the mesh or raise the limit (the limit: {})",
         stats_.equations, stats_.factor_bytes * 1e-9, stats_.ordering, limit * 1e-9, factor_limit_reason(options_));
  if (log_)
    log_->info("  CHOLMOD analyze: {} equations, nnz(K) {} (upper), nnz(L) {:.4g}, {:.4g} flops, "
               "factor {:.2f} GB, {} ordering, {:.2f} s",
               stats_.equations, stats_.matrix_nonzeros, stats_.factor_nonzeros,
               stats_.factorization_flops, stats_.factor_bytes * 1e-9, stats_.ordering,
               stats_.analyze_seconds);
}

void CholmodSolver::factorize(const SymmetricUpperMatrix& matrix) {
  require(impl_->factor != nullptr, "CHOLMOD factorize called before analyze");
  require(matrix.rows() == stats_.equations && matrix.nonZeros() == stats_.matrix_nonzeros,
          "CHOLMOD factorize: matrix pattern differs from the analysed one");
  Stopwatch clock;
  impl_->wrap(matrix);
  const int ok = cholmod_l_factorize(&impl_->view, impl_->factor, &impl_->common);
  impl_->check("cholmod_l_factorize");
  if (!ok) fail("CHOLMOD cholmod_l_factorize failed (status {})", impl_->common.status);
  if (impl_->common.status == CHOLMOD_NOT_POSDEF ||
      impl_->factor->minor < impl_->factor->n) {
    // L->minor is a column of the permuted matrix K(p, p); name the equation
    // of K itself.
    const auto minor = std::int64_t(impl_->factor->minor);
    const auto* perm = static_cast<const SuiteSparse_long*>(impl_->factor->Perm);
    const auto equation =
        perm && minor >= 0 && minor < stats_.equations ? std::int64_t(perm[minor]) : minor;
    throw NotPositiveDefinite(
        fmt::format("stiffness matrix is not positive definite: the Cholesky factorization "
                    "broke down at equation {} of {} (a rigid-body mode left unsupported, or an "
                    "element without stiffness)",
                    equation, stats_.equations),
        equation);
  }
  stats_.factorize_seconds = clock.seconds();
  stats_.reciprocal_condition = cholmod_l_rcond(impl_->factor, &impl_->common);
  impl_->check("cholmod_l_rcond");
  if (!(stats_.reciprocal_condition >= options_.min_reciprocal_condition))
    throw NotPositiveDefinite(
        fmt::format("stiffness matrix is singular to working precision (reciprocal condition "
                    "estimate {:.2e} < {:.0e}): the model has rigid-body modes left unsupported",
                    stats_.reciprocal_condition, options_.min_reciprocal_condition),
        -1);
  if (log_)
    log_->detail("  CHOLMOD factorize: {:.2f} s, {:.1f} GFLOP/s, rcond estimate {:.2e}",
               stats_.factorize_seconds, stats_.factorize_gflops(), stats_.reciprocal_condition);
}

void CholmodSolver::release_factor() {
  if (!has_numeric_factor()) return;
  // Supernodal numeric -> supernodal symbolic: the values are freed, the
  // ordering and the supernodes stay for the next cholmod_l_factorize.
  const int ok = cholmod_l_change_factor(CHOLMOD_PATTERN, impl_->factor->is_ll, impl_->factor->is_super, /*to_packed=*/1, /*to_monotonic=*/1,
                                         impl_->factor, &impl_->common);
  impl_->check("cholmod_l_change_factor");
  if (!ok) fail("CHOLMOD cholmod_l_change_factor (releasing the factor) failed (status {})", impl_->common.status);
  require(impl_->factor->x == nullptr && impl_->factor->xtype == CHOLMOD_PATTERN,
          "CHOLMOD kept the numeric values of a released factor");
}

bool CholmodSolver::has_numeric_factor() const {
  return impl_->factor != nullptr && impl_->factor->xtype != CHOLMOD_PATTERN;
}

Eigen::MatrixXd CholmodSolver::solve(const Eigen::MatrixXd& rhs) {
  require(has_numeric_factor() && impl_->matrix != nullptr,
          "CHOLMOD solve called before factorize (or after release_factor)");
  require(rhs.rows() == stats_.equations, "CHOLMOD solve: right-hand side has {} rows, system {}",
          rhs.rows(), stats_.equations);
  require(rhs.allFinite(), "CHOLMOD solve: right-hand side has NaN or Inf entries");
  Stopwatch clock;
  cholmod_dense b{};
  b.nrow = size_t(rhs.rows());
  b.ncol = size_t(rhs.cols());
  b.nzmax = b.nrow * b.ncol;
  b.d = b.nrow;
  b.x = const_cast<double*>(rhs.data());
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_l_solve(CHOLMOD_A, impl_->factor, &b, &impl_->common);
  impl_->check("cholmod_l_solve");
  require(x != nullptr, "CHOLMOD cholmod_l_solve returned no solution");
  Eigen::MatrixXd solution =
      Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(x->x), rhs.rows(), rhs.cols());
  cholmod_l_free_dense(&x, &impl_->common);
  stats_.last_solve_seconds = clock.seconds();
  stats_.last_solve_rhs = rhs.cols();

  // Residual check on up to four columns (first, last and two between): a
  // full check of a large block would cost more than the block solve.
  const Eigen::Index k = rhs.cols();
  std::vector<Eigen::Index> columns;
  for (Eigen::Index c : {Eigen::Index(0), k / 3, (2 * k) / 3, k - 1})
    if (c >= 0 && c < k && std::find(columns.begin(), columns.end(), c) == columns.end())
      columns.push_back(c);
  const auto K = impl_->matrix->selfadjointView<Eigen::Upper>();
  const double k_norm = impl_->matrix_norm();
  // The normwise backward error ||r|| / (||K|| ||x|| + ||b||) of each checked
  // column: round-off (~n eps) for a backward-stable Cholesky whatever the
  // conditioning, which the factorization's condition estimate checks
  // (min_reciprocal_condition); ||r|| / ||b|| would instead grow like cond x
  // eps on a regular but stiff model and fail it by chance. The plain
  // relative residual is kept in the statistics.
  double relative = 0.0;
  auto worst_residual = [&] {
    double worst = 0.0;
    relative = 0.0;
    for (Eigen::Index c : columns) {
      const double bnorm = rhs.col(c).norm();
      if (!solution.col(c).allFinite())
        fail("CHOLMOD solve produced NaN or Inf in right-hand side {}", c);
      if (bnorm == 0.0) continue;
      const Eigen::VectorXd r = K * solution.col(c) - rhs.col(c);
      worst = std::max(worst, r.norm() / (k_norm * solution.col(c).norm() + bnorm));
      relative = std::max(relative, r.norm() / bnorm);
    }
    return worst;
  };
  double worst = worst_residual();
  if (!(worst <= options_.max_relative_residual) && std::isfinite(worst)) {
    // One step of iterative refinement: it recovers a solve whose backward
    // error grew (a factor with element growth); a singular or broken factor
    // stays above the bound.
    const Eigen::MatrixXd residual = rhs - Eigen::MatrixXd(K * solution);
    cholmod_dense rb{};
    rb.nrow = b.nrow;
    rb.ncol = b.ncol;
    rb.nzmax = b.nzmax;
    rb.d = b.d;
    rb.x = const_cast<double*>(residual.data());
    rb.xtype = CHOLMOD_REAL;
    rb.dtype = CHOLMOD_DOUBLE;
    cholmod_dense* dx = cholmod_l_solve(CHOLMOD_A, impl_->factor, &rb, &impl_->common);
    impl_->check("cholmod_l_solve");
    require(dx != nullptr, "CHOLMOD cholmod_l_solve returned no solution");
    solution += Eigen::Map<Eigen::MatrixXd>(static_cast<double*>(dx->x), rhs.rows(), rhs.cols());
    cholmod_l_free_dense(&dx, &impl_->common);
    ++stats_.refinement_steps;
    worst = worst_residual();
  }
  stats_.last_relative_residual = relative;
  stats_.last_backward_error = worst;
  if (!(worst <= options_.max_relative_residual))
    fail("CHOLMOD solve: backward error {:.2e} exceeds {:.0e} (relative residual {:.2e}: a singular or broken "
         "factor)",
         worst, options_.max_relative_residual, relative);
  if (log_)
    log_->detail("  CHOLMOD solve: {} right-hand side(s) in {:.3f} s ({:.4f} s each), relative "
               "residual {:.1e}",
               k, stats_.last_solve_seconds, stats_.last_solve_seconds / double(std::max<Eigen::Index>(k, 1)),
               worst);
  return solution;
}

}  // namespace kinetofem::fem
