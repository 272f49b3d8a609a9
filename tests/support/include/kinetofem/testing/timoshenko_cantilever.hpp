#pragma once
// Moved to the verification library
// (kinetofem/verification/timoshenko_cantilever.hpp). These names stay for
// tests/large/cantilever_convergence_test.cpp.
#include "kinetofem/verification/timoshenko_cantilever.hpp"

namespace kinetofem::testing {
using verification::CantileverSolution;
using verification::solve_cantilever;
using verification::TimoshenkoCantilever;
}  // namespace kinetofem::testing
