// Lame thick-walled cylinder under internal pressure, plane strain: radial
// displacement and recovered nodal hoop stress at every bore node, each
// within 1 %. Reference (Lamé; Timoshenko & Goodier sec. 33), model and the
// bore evaluation: kinetofem/verification/lame_cylinder.hpp, shared with
// `kinetofem verify` (fem.lame_cylinder).
#include <gtest/gtest.h>

#include <cstdio>

#include "kinetofem/verification/lame_cylinder.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;

TEST(LameCylinder, BoreDisplacementAndHoopStress) {
  // a = 0.1 m, b = 0.2 m, p = 100 MPa, E = 210 GPa, nu = 0.3.
  const kv::LameBoreResult r = kv::solve_lame_cylinder({});
  ASSERT_GT(r.bore_nodes, 0u);
  std::printf("Lame: %lld DoFs, %zu bore nodes, max relative error u_r(a) %.2e, sigma_tt(a) %.2e\n", r.free_dofs,
              r.bore_nodes, r.u_error, r.hoop_error);
  // Reference: Lame u_r(a) (lame_cylinder.hpp); 1 % at every bore node.
  EXPECT_LT(r.u_error, kv::kLameTolerance);
  // Reference: Lame sigma_tt(a) = p (a^2 + b^2)/(b^2 - a^2), nodal recovered; 1 %.
  EXPECT_LT(r.hoop_error, kv::kLameTolerance);
}

}  // namespace
}  // namespace kinetofem::fem
