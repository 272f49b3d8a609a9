#pragma once
// How the parts' factorizations are made (PartFactors, part_factors.hpp, owns
// and lends them): every part's stiffness with its 3-2-1 support
// (SupportedPart) assembled, analysed and factorized once for the whole
// motion; the per-part stress, the elastic assembly and the vibration borrow them.
//
// Both cores busy: CHOLMOD 3.0 has no tree-level parallelism and two BLAS
// threads speed one supernodal factorization up by only about 1.4x, so
// independent parts are factorized side by side, one BLAS thread each
// (fem::BlasThreadLimit), when
//   - there are at least two parts on the direct path, and
//   - solver.concurrent_parts allows more than one at a time, and
//   - their predicted factors (CHOLMOD's symbolic analysis) fit the factor
//     memory limit together (fem::factor_memory_limit_bytes: the peak then is
//     their sum, not the largest one).
// Otherwise the factorizations are left to the caller, one part at a time
// (SupportedPart::analysis().factorize() right before the part is used, so a
// factor can be freed before the next one is made). Either way the factors
// are the same: the symbolic analysis and the factorization's arithmetic do
// not depend on the thread that runs them (a test checks the statistics bit
// for bit and the solutions).
#include <memory>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::pipeline {

// What factorize_parts decided and measured.
struct PartFactorizationReport {
  int side_by_side = 1;           // parts factorized at a time (1: left to the caller)
  std::string why;                // the reason for that choice, for the log
  double predicted_factor_bytes = 0;  // sum over the direct parts (symbolic analysis)
  double limit_bytes = 0;             // fem::factor_memory_limit_bytes
  double seconds = 0;             // wall time of the concurrent factorizations (0 if none)
  double flops = 0;               // their flops
  double gflops() const { return seconds > 0 ? flops / seconds * 1e-9 : 0.0; }
};

// One SupportedPart per part, in the order of `parts`, factorized side by side
// when the rules above allow it, else analysed only. Errors (a factor above the
// limit on the direct path, a matrix that is not positive definite) name the part.
std::vector<std::unique_ptr<SupportedPart>> factorize_parts(const std::vector<Part>& parts,
                                                            const fem::StaticSolverOptions& solver, const Log& log,
                                                            PartFactorizationReport* report = nullptr);

}  // namespace kinetofem::pipeline
