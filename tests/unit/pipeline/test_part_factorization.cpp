// Stage "one factorization per part" (pipeline/part_factorization.hpp):
// side by side (one BLAS thread each) gives the same factors as one after the
// other. Reference: the sequential factorization of the same parts; required
// by the docs: factor statistics bit for bit. The solutions agree to round-off
// only: one after the other runs on two BLAS threads, side by side on one, and
// OpenBLAS splits its dense kernels differently (measured: up to 1.8e-11 of the
// peak on these beams); required 1e-9 of the peak, far below any discretization
// error and far above a wrong factor.
#include <gtest/gtest.h>

#include "kinetofem/pipeline/part_factorization.hpp"
#include "kinetofem/solver/blas_threads.hpp"
#include "kinetofem/testing/captured_log.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

Eigen::MatrixXd unit_loads(const SupportedPart& part) {
  const Eigen::Index dofs = 3 * part.model().mesh.node_count();
  Eigen::MatrixXd f = Eigen::MatrixXd::Zero(dofs, 2);
  f(dofs - 2, 0) = 1000.0;  // a tip force along y and one along z (N)
  f(dofs - 1, 1) = 1000.0;
  return f;
}

TEST(FactorizeParts, SideBySideGivesTheFactorsOfOneAfterTheOther) {
  const std::vector<Part> parts = test::three_beams();
  fem::StaticSolverOptions sequential_options, concurrent_options;
  sequential_options.concurrent_parts = 1;
  concurrent_options.concurrent_parts = 2;
  PartFactorizationReport sequential_report, concurrent_report;
  auto sequential = factorize_parts(parts, sequential_options, test::quiet_log(), &sequential_report);
  auto concurrent = factorize_parts(parts, concurrent_options, test::quiet_log(), &concurrent_report);
  EXPECT_EQ(sequential_report.side_by_side, 1);
  EXPECT_EQ(concurrent_report.side_by_side, 2) << concurrent_report.why;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    EXPECT_FALSE(sequential[k]->analysis().is_factorized()) << "left to the caller";
    EXPECT_TRUE(concurrent[k]->analysis().is_factorized());
    sequential[k]->analysis().factorize();
    const fem::CholmodStatistics& a = sequential[k]->analysis().solver_statistics();
    const fem::CholmodStatistics& b = concurrent[k]->analysis().solver_statistics();
    EXPECT_EQ(a.equations, b.equations);
    EXPECT_EQ(a.factor_nonzeros, b.factor_nonzeros);
    EXPECT_EQ(a.factorization_flops, b.factorization_flops);
    EXPECT_EQ(a.factor_bytes, b.factor_bytes);
    const auto ua = sequential[k]->analysis().solve_forces(unit_loads(*sequential[k]));
    const auto ub = concurrent[k]->analysis().solve_forces(unit_loads(*concurrent[k]));
    for (std::size_t c = 0; c < ua.size(); ++c)
      EXPECT_LE((ua[c] - ub[c]).cwiseAbs().maxCoeff(), 1e-9 * ua[c].cwiseAbs().maxCoeff()) << parts[k].body();
  }
  EXPECT_GT(concurrent_report.flops, 0.0);
}

TEST(FactorizeParts, FactorsAboveTheLimitTogetherGoOneAfterTheOther) {
  const std::vector<Part> parts = test::three_beams();
  fem::StaticSolverOptions probe;
  probe.concurrent_parts = 1;
  PartFactorizationReport sizes;
  factorize_parts(parts, probe, test::quiet_log(), &sizes);
  fem::StaticSolverOptions tight;
  tight.concurrent_parts = 2;
  tight.direct.max_factor_bytes = 0.9 * sizes.predicted_factor_bytes;  // each fits alone, not all together
  PartFactorizationReport report;
  const auto supported = factorize_parts(parts, tight, test::quiet_log(), &report);
  EXPECT_EQ(report.side_by_side, 1);
  EXPECT_NE(report.why.find("exceed"), std::string::npos) << report.why;
  for (const auto& s : supported) EXPECT_FALSE(s->analysis().is_factorized());
}

// A linkage without FE parts reaches the stage with none: it prints nothing
// (a "factorization" line there would tell a reader of parts that do not exist).
TEST(FactorizeParts, NoPartsPrintNothing) {
  const testing::CapturedLog log;
  PartFactorizationReport report;
  EXPECT_TRUE(factorize_parts({}, fem::StaticSolverOptions{}, log.log(), &report).empty());
  EXPECT_EQ(log.text(), "");
}

TEST(FactorizeParts, SolvingBeforeADeferredFactorizationIsAnError) {
  const std::vector<Part> parts = test::three_beams();
  fem::StaticSolverOptions options;
  options.concurrent_parts = 1;
  auto supported = factorize_parts(parts, options, test::quiet_log());
  EXPECT_THROW(supported[0]->analysis().solve_forces(unit_loads(*supported[0])), Error);
}

TEST(BlasThreadLimit, RestoresTheThreadCount) {
  if (!fem::BlasThreadLimit::available()) GTEST_SKIP() << "the BLAS is not OpenBLAS";
  const int before = fem::BlasThreadLimit::threads();
  {
    const fem::BlasThreadLimit one(1);
    EXPECT_EQ(fem::BlasThreadLimit::threads(), 1);
  }
  EXPECT_EQ(fem::BlasThreadLimit::threads(), before);
}

}  // namespace
}  // namespace kinetofem::pipeline
