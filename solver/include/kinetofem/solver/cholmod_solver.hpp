#pragma once
// CholmodSolver — sparse symmetric positive-definite direct solver: CHOLMOD
// supernodal Cholesky K = L L^T with METIS (nested dissection) ordering.
//
// analyze() (ordering, symbolic factor; reusable for every matrix of the same
// pattern) / factorize() (numeric) / solve() (any number of right-hand sides
// in one call) are separate so the symbolic and numeric factors are reused.
// Every failure is an Error: a matrix that is not positive definite (e.g. a
// model with rigid-body modes left) names the equation where the
// factorization broke down; a nearly singular one (reciprocal condition
// estimate below the threshold) is also rejected, never solved into NaNs.
// Each solve checks its relative residual ||K x - b|| / ||b||.
#include <cstdint>
#include <memory>
#include <string>

#include <Eigen/Core>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/sparse.hpp"

namespace kinetofem::fem {

// Thrown when the matrix is not positive definite or singular to working
// precision; `equation` is where the factorization broke down (-1 when the
// condition estimate gave it away).
class NotPositiveDefinite : public Error {
 public:
  NotPositiveDefinite(const std::string& message, std::int64_t equation)
      : Error(message), equation_(equation) {}
  std::int64_t equation() const { return equation_; }

 private:
  std::int64_t equation_;
};

struct CholmodOptions {
  enum class Ordering { Metis, Amd, Best };
  Ordering ordering = Ordering::Metis;
  // Memory allowed for the numeric factor; analyze() throws when the
  // symbolic analysis predicts more. 0 = 80 % of the machine's physical memory.
  double max_factor_bytes = 0.0;
  // Relaxed supernodal amalgamation (CHOLMOD's Common.nrelax / zrelax): two
  // supernodes are merged when the merged one has fewer than relax_columns[k]
  // columns and at most relax_zero_fraction[k] explicit zeros (k = 0, 1, 2
  // for increasing sizes). Larger supernodes mean fewer, bigger dense BLAS
  // calls at the price of some zeros. Defaults are CHOLMOD's own.
  int relax_columns[3] = {4, 16, 48};
  double relax_zero_fraction[3] = {0.8, 0.1, 0.05};
  double min_reciprocal_condition = 1e-13;  // below: treated as singular
  double max_relative_residual = 1e-8;      // above: the solve is an error
};

struct CholmodStatistics {
  std::int64_t equations = 0;
  std::int64_t matrix_nonzeros = 0;       // nnz of the stored upper triangle
  double factor_nonzeros = 0.0;           // nnz(L)
  double factor_bytes = 0.0;              // memory of the numeric factor
  double factorization_flops = 0.0;
  double analyze_seconds = 0.0;
  double factorize_seconds = 0.0;
  double last_solve_seconds = 0.0;
  std::int64_t last_solve_rhs = 0;
  double last_relative_residual = 0.0;
  double reciprocal_condition = 0.0;
  std::string ordering;                   // ordering CHOLMOD used
  double factorize_gflops() const {
    return factorize_seconds > 0 ? factorization_flops / factorize_seconds * 1e-9 : 0.0;
  }
};

class CholmodSolver {
 public:
  explicit CholmodSolver(CholmodOptions options = {}, const Log* log = nullptr);
  ~CholmodSolver();
  CholmodSolver(const CholmodSolver&) = delete;
  CholmodSolver& operator=(const CholmodSolver&) = delete;

  // Ordering and symbolic factorization of the pattern of `matrix` (upper
  // triangle stored). Throws if the predicted factor exceeds max_factor_bytes.
  void analyze(const SymmetricUpperMatrix& matrix);
  // Numeric factorization; analyze() first (or the matrix's pattern must not
  // have changed). The matrix must stay alive until the last solve().
  void factorize(const SymmetricUpperMatrix& matrix);
  // X = K^{-1} B for all columns of B at once.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs);

  const CholmodStatistics& statistics() const { return stats_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  CholmodOptions options_;
  const Log* log_;
  CholmodStatistics stats_;
};

}  // namespace kinetofem::fem
