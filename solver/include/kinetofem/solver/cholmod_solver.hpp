#pragma once
// CholmodSolver — sparse symmetric positive-definite direct solver: CHOLMOD
// supernodal Cholesky K = L L^T with METIS (nested dissection) ordering, either
// CHOLMOD's own (METIS on the DoF matrix's graph) or one given by the caller
// (e.g. METIS on the mesh's node graph, node_graph_ordering.hpp).
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
#include <vector>

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
  // Fill-reducing ordering.
  //   NodeGraphMetis  METIS nested dissection of the mesh's node graph,
  //                   expanded to the DoFs (node_graph_ordering.hpp): about
  //                   the fill of Metis (+2 %), a 1.6-2x faster analysis.
  //                   It needs the mesh, so the caller computes it and passes it to
  //                   analyze(matrix, ordering), as LinearStaticAnalysis does;
  //                   analyze(matrix) alone, without a mesh, falls back to Metis.
  //   Metis           CHOLMOD's METIS on the graph of the DoF matrix.
  //   Amd             CHOLMOD's approximate minimum degree.
  //   Best            CHOLMOD's default strategy: AMD, then METIS if AMD fills much.
  enum class Ordering { Metis, Amd, Best, NodeGraphMetis };
  Ordering ordering = Ordering::NodeGraphMetis;
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
  // Normwise backward error ||K x - b|| / (||K|| ||x|| + ||b||) of a solve
  // above this (after one step of iterative refinement): an error.
  double max_relative_residual = 1e-8;
};

// The memory a numeric factor may take under `options`, bytes: max_factor_bytes,
// or 80 % of the machine's physical memory when that is 0.
double factor_memory_limit_bytes(const CholmodOptions& options);

struct CholmodStatistics {
  std::int64_t equations = 0;
  std::int64_t matrix_nonzeros = 0;       // nnz of the stored upper triangle
  double factor_nonzeros = 0.0;           // nnz(L)
  double factor_bytes = 0.0;              // memory of the numeric factor
  double factorization_flops = 0.0;
  double analyze_seconds = 0.0;           // ordering + symbolic factorization
  double ordering_seconds = 0.0;          // a given ordering's own time (part of analyze_seconds)
  double factorize_seconds = 0.0;
  double last_solve_seconds = 0.0;
  std::int64_t last_solve_rhs = 0;
  double last_relative_residual = 0.0;    // ||K x - b|| / ||b||, worst checked column
  double last_backward_error = 0.0;       // ||K x - b|| / (||K|| ||x|| + ||b||), worst checked column
  std::int64_t refinement_steps = 0;      // solves refined once (their first residual above the bound)
  double reciprocal_condition = 0.0;
  std::string ordering;                   // ordering used: "METIS", "AMD", "METIS (node graph)"
  double factorize_gflops() const {
    return factorize_seconds > 0 ? factorization_flops / factorize_seconds * 1e-9 : 0.0;
  }
};

// A fill-reducing ordering computed outside CHOLMOD (node_graph_ordering.hpp).
struct GivenOrdering {
  // permutation[k] = equation eliminated k-th: a permutation of 0..n-1, the
  // factor is that of K(p, p) (CHOLMOD still postorders its elimination tree).
  std::vector<std::int64_t> permutation;
  std::string name = "given";  // for the statistics and the log
  double seconds = 0.0;        // time spent computing it, s; counted in analyze_seconds
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
  // The same with the caller's ordering (cholmod_l_analyze_p), whatever
  // options.ordering says. Throws Error unless it is a permutation of the
  // matrix's equations.
  void analyze(const SymmetricUpperMatrix& matrix, const GivenOrdering& ordering);
  // Numeric factorization; analyze() first (or the matrix's pattern must not
  // have changed). The matrix must stay alive until the last solve().
  void factorize(const SymmetricUpperMatrix& matrix);
  // X = K^{-1} B for all columns of B at once.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs);
  // Frees the numeric factor (its memory, statistics().factor_bytes) and keeps
  // the symbolic analysis: factorize() makes the same factor again, bit for
  // bit. solve() is an Error until then. A no-op before factorize().
  void release_factor();
  bool has_numeric_factor() const;

  const CholmodStatistics& statistics() const { return stats_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  CholmodOptions options_;
  const Log* log_;
  CholmodStatistics stats_;

  void analyze_with(const SymmetricUpperMatrix& matrix, const GivenOrdering* ordering);
};

}  // namespace kinetofem::fem
