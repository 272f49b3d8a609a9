// The CHOLMOD solve's check: the normwise backward error
// ||K x - b|| / (||K|| ||x|| + ||b||), not the relative residual ||K x - b|| /
// ||b||. A chain of springs from the ground whose stiffnesses fall by ten
// decades (cond(K) ~ 1e12) is regular and solved backward-stably: its backward
// error is round-off whatever the conditioning, while the relative residual
// of a load at the soft end scales with cond x eps. Reference: Higham,
// Accuracy and Stability of Numerical Algorithms (2002), thm. 10.4 (Cholesky
// is normwise backward stable, ~ n eps); the test requires 1e-13.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <Eigen/SparseCore>

#include "kinetofem/solver/cholmod_solver.hpp"

namespace kinetofem::fem {
namespace {

TEST(CholmodSolver, AStiffButRegularChainPassesOnItsBackwardError) {
  const int n = 200;
  std::vector<double> k(n);
  for (int i = 0; i < n; ++i) k[size_t(i)] = std::pow(10.0, -10.0 * i / (n - 1));  // 1 .. 1e-10 N/m
  // Spring i joins node i-1 (the ground for i = 0) and node i.
  std::vector<Eigen::Triplet<double, std::int64_t>> t;
  for (int i = 0; i < n; ++i) {
    t.emplace_back(i, i, k[size_t(i)] + (i + 1 < n ? k[size_t(i + 1)] : 0.0));
    if (i + 1 < n) t.emplace_back(i, i + 1, -k[size_t(i + 1)]);
  }
  SymmetricUpperMatrix K(n, n);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  CholmodSolver solver;
  solver.analyze(K);
  solver.factorize(K);
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(n, 2);
  b(n - 1, 0) = 1.0;                                // a unit load at the soft end
  b.col(1).setConstant(1e-3);                       // a load everywhere
  const Eigen::MatrixXd x = solver.solve(b);
  // The end's displacement is the sum of the springs' compliances.
  double compliance = 0.0;
  for (const double ki : k) compliance += 1.0 / ki;
  EXPECT_NEAR(x(n - 1, 0), compliance, 1e-6 * compliance);
  const CholmodStatistics& s = solver.statistics();
  std::printf("  backward error %.2e, relative residual %.2e, refinement steps %lld\n", s.last_backward_error,
              s.last_relative_residual, static_cast<long long>(s.refinement_steps));
  EXPECT_LT(s.last_backward_error, 1e-13);
  EXPECT_GE(s.last_relative_residual, s.last_backward_error);
}

}  // namespace
}  // namespace kinetofem::fem
