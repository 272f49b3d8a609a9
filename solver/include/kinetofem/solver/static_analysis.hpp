#pragma once
// LinearStaticAnalysis — K u = f for one FeModel and any number of load
// cases. The stiffness is assembled, analysed and factorized once at
// construction; solve() takes all load cases as one block of right-hand
// sides. Prints DoFs, nnz(K), nnz(L), flops and times through the Log.
//
// Linear solver (StaticSolverOptions::method): the direct CHOLMOD
// factorization, or AMG-preconditioned CG (AmgSolver, hypre) for models whose
// Cholesky factor does not fit in memory; `Auto` runs CHOLMOD's symbolic
// analysis (cheap: ordering + factor size, no numeric work) and takes the
// iterative path only when the predicted factor exceeds max_factor_bytes,
// printing the decision and why.
//
// Ordering of the direct path: CholmodOptions::Ordering::NodeGraphMetis (the
// default) orders the mesh's node graph with METIS and gives the expanded
// permutation to CHOLMOD (node_graph_ordering.hpp); Metis, Amd and Best leave
// the ordering to CHOLMOD.
#include <memory>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/amg_solver.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::fem {

struct StaticTimings {
  double assembly_seconds = 0.0;
  double load_assembly_seconds = 0.0;
};

enum class LinearSolverMethod {
  Direct,     // CHOLMOD; an Error when the factor would exceed max_factor_bytes
  Iterative,  // AMG-preconditioned CG (hypre)
  Auto,       // Direct unless the symbolic analysis predicts a factor above the limit
};

struct StaticSolverOptions {
  LinearSolverMethod method = LinearSolverMethod::Auto;
  CholmodOptions direct;  // max_factor_bytes is also the limit Auto decides by
  AmgOptions iterative;
  // Direct path: stop after the symbolic analysis; the numeric factorization
  // is LinearStaticAnalysis::factorize(), e.g. for several parts at once
  // (pipeline::factorize_parts) once their predicted factors are known.
  bool defer_factorization = false;
  // pipeline::factorize_parts: at most this many parts factorized side by side,
  // one BLAS thread each (0: one per hardware thread; 1: one after the other).
  int concurrent_parts = 0;
};

class LinearStaticAnalysis {
 public:
  // The model must outlive the analysis. Direct solver (CHOLMOD).
  LinearStaticAnalysis(const FeModel& model, const Log& log, CholmodOptions options = {});
  // Solver chosen by options.method.
  LinearStaticAnalysis(const FeModel& model, const Log& log, const StaticSolverOptions& options);
  // The analysis keeps a reference to the log (and the model): a temporary
  // would dangle, so passing one does not compile.
  LinearStaticAnalysis(const FeModel&, Log&&, CholmodOptions = {}) = delete;
  LinearStaticAnalysis(const FeModel&, Log&&, const StaticSolverOptions&) = delete;
  LinearStaticAnalysis(FeModel&&, const Log&, CholmodOptions = {}) = delete;
  LinearStaticAnalysis(FeModel&&, const Log&, const StaticSolverOptions&) = delete;

  // The numeric factorization deferred by StaticSolverOptions::defer_factorization;
  // a no-op when it is done or the iterative path was taken. Safe to call for
  // different analyses from different threads at once (each has its own CHOLMOD
  // workspace); BLAS threads are the caller's choice (blas_threads.hpp).
  void factorize();
  bool is_factorized() const { return amg_ != nullptr || factorized_; }
  // Direct path: frees the numeric factor (the largest memory of a part) and
  // keeps the assembled stiffness and the symbolic analysis, so that
  // factorize() makes the same factor again (bit for bit) if it is needed
  // later; solve() is an Error until then. The iterative path keeps its AMG
  // hierarchy (a no-op). E.g. pipeline: a part's factor freed after its last
  // solve when the parts' factors do not fit in memory together.
  void release_factor();

  // Displacement (N x 3, m) for each load case, in the order given (factorize() first
  // when it was deferred).
  std::vector<DisplacementField> solve(const std::vector<LoadCase>& load_cases);
  // Same, for external force vectors over all DoFs (one column per case, N).
  std::vector<DisplacementField> solve_forces(const Eigen::MatrixXd& external_forces);

  // Support reactions (3 N, N; zero on free DoFs): K u - f_ext on prescribed DoFs.
  Eigen::VectorXd reactions(const DisplacementField& displacement,
                            const Eigen::VectorXd& external_force) const;

  // The same, only at the given nodes (3 per node, in their order): cheap
  // when few nodes are asked for (only the elements touching them are
  // visited), e.g. the six reactions of a 3-2-1 support.
  Eigen::VectorXd reactions_at(const DisplacementField& displacement,
                               const Eigen::VectorXd& external_force,
                               const std::vector<Index>& nodes) const;

  const DofMap& dofs() const { return dofs_; }
  const FeModel& model() const { return model_; }
  // The material of each element (element_materials(model()), checked once here).
  const ElementMaterials& materials() const { return materials_; }
  // CHOLMOD's statistics; on the iterative path only the symbolic analysis
  // (predicted factor size) when Auto ran it, else empty.
  const CholmodStatistics& solver_statistics() const { return solver_.statistics(); }
  bool uses_iterative_solver() const { return amg_ != nullptr; }
  // The AMG-PCG statistics, or nullptr on the direct path.
  const AmgStatistics* iterative_statistics() const { return amg_ ? &amg_->statistics() : nullptr; }
  const StaticTimings& timings() const { return timings_; }
  // One line on the linear solver for summaries: CHOLMOD's nnz(L), flops and
  // factorization time and rate, or the AMG hierarchy and the PCG iterations so far.
  std::string solver_summary() const;

 private:
  const FeModel& model_;
  const Log& log_;
  ElementMaterials materials_;
  DofMap dofs_;
  AssembledStiffness stiffness_;
  CholmodSolver solver_;
  std::unique_ptr<AmgSolver> amg_;  // set when the iterative path is taken
  StaticTimings timings_;
  bool factorized_ = false;

  void factorize_direct();
};

}  // namespace kinetofem::fem
