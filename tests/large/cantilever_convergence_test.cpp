// Cantilever under end shear, finer refinement study (h/2, h/4, h/8; up to
// ~210 k DoFs for TET10): the asymptotic convergence order of the compliance
// of TET10 and HEX20. Problem and exact solution:
// kinetofem/testing/timoshenko_cantilever.hpp. Not in CI (label large).
#include <gtest/gtest.h>

#include <cstdio>

#include "kinetofem/testing/fe_probes.hpp"
#include "kinetofem/testing/timoshenko_cantilever.hpp"

namespace kinetofem::fem {
namespace {

class CantileverConvergence : public ::testing::TestWithParam<ElementType> {};

TEST_P(CantileverConvergence, ComplianceConvergesAtFourthOrder) {
  const testing::TimoshenkoCantilever beam;
  const double compliance = beam.exact_compliance_nm(), delta = beam.beam_deflection_m();
  testing::CantileverSolution r[3];
  for (int level = 0; level < 3; ++level) {
    r[level] = testing::solve_cantilever(beam, GetParam(), 2 << level);
    std::printf("%s h/%d: %lld DoFs, deflection error %+.3e, compliance error %+.3e, %.1f s\n",
                name_of(GetParam()), 2 << level, r[level].free_dofs,
                r[level].deflection_m / delta - 1.0, r[level].compliance_nm / compliance - 1.0,
                r[level].solve_seconds);
    // Reference: Timoshenko beam theory with Cowper's kappa (exact, nu = 0); 0.1 %.
    EXPECT_NEAR(r[level].deflection_m / delta, 1.0, 1e-3);
  }
  // Reference: O(h^4) energy convergence of quadratic elements on a smooth
  // solution (Richardson from the FE values); tolerance +-0.3.
  const double order =
      testing::observed_order(r[0].compliance_nm, r[1].compliance_nm, r[2].compliance_nm);
  std::printf("%s observed order: %.3f (expected 4)\n", name_of(GetParam()), order);
  EXPECT_NEAR(order, 4.0, 0.3);
}

INSTANTIATE_TEST_SUITE_P(QuadraticElements, CantileverConvergence,
                         ::testing::Values(ElementType::Tet10, ElementType::Hex20),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace kinetofem::fem
