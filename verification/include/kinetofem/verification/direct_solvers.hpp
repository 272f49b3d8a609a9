#pragma once
// CHOLMOD against an independent sparse factorization (Eigen's
// SimplicialLDLT) on the same system K_ff u = f - K_fp u_p: two direct
// factorizations of one SPD system agree to round-off (1e-10 relative).
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::verification {

inline constexpr double kDirectSolverTolerance = 1e-10;

struct DirectSolverComparison {
  double relative_difference = 0.0;  // |u_cholmod - u_ldlt| / |u_ldlt|
  double relative_residual = 0.0;    // |K u_cholmod - f| / |f|
  double factor_nonzeros = 0.0;      // of CHOLMOD's factor
  double matrix_nonzeros = 0.0;      // of K_ff (upper triangle)
};
// Assembles model and load (one load case) and solves with both; Error if
// the LDLT factorization fails.
DirectSolverComparison compare_cholmod_with_ldlt(const fem::FeModel& model, const fem::LoadCase& load);

}  // namespace kinetofem::verification
