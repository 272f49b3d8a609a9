#pragma once
// LinearStaticAnalysis — K u = f for one FeModel and any number of load
// cases. The stiffness is assembled, analysed and factorized once at
// construction; solve() takes all load cases as one block of right-hand
// sides. Prints DoFs, nnz(K), nnz(L), flops and times through the Log.
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::fem {

struct StaticTimings {
  double assembly_seconds = 0.0;
  double load_assembly_seconds = 0.0;
};

class LinearStaticAnalysis {
 public:
  // The model must outlive the analysis.
  LinearStaticAnalysis(const FeModel& model, const Log& log, CholmodOptions options = {});

  // Displacement (N x 3, m) for each load case, in the order given.
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
  const CholmodStatistics& solver_statistics() const { return solver_.statistics(); }
  const StaticTimings& timings() const { return timings_; }

 private:
  const FeModel& model_;
  const Log& log_;
  DofMap dofs_;
  AssembledStiffness stiffness_;
  CholmodSolver solver_;
  StaticTimings timings_;
};

}  // namespace kinetofem::fem
