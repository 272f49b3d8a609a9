// PartFactors (pipeline/part_factors.hpp): the one owner of every part's
// factorization decides side by side or one at a time, lends each factor,
// and frees it after its last user, on three small beams.
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/pipeline/part_factors.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

// A factor limit that each part fits alone but not all of them together.
fem::StaticSolverOptions tight_for(const std::vector<Part>& parts) {
  fem::StaticSolverOptions probe;
  probe.concurrent_parts = 1;
  PartFactorizationReport sizes;
  factorize_parts(parts, probe, test::quiet_log(), &sizes);
  fem::StaticSolverOptions tight;
  tight.direct.max_factor_bytes = 0.9 * sizes.predicted_factor_bytes;
  return tight;
}

TEST(PartFactors, StressOnlyFreesEachPartAfterItsStress) {
  const std::vector<Part> parts = test::three_beams();
  PartFactors factors(parts, fem::StaticSolverOptions{}, FactorStages{}, "case.toml", test::quiet_log());
  EXPECT_TRUE(factors.factors_fit_together());
  EXPECT_TRUE(factors.lend_analysis(0).is_factorized());
  factors.done(0, FactorUser::Stress);
  EXPECT_EQ(factors.held(0), nullptr);
  EXPECT_NE(factors.held(1), nullptr);
  EXPECT_THROW(factors.lend(0), Error);
}

TEST(PartFactors, TheAssemblyKeepsAFactorOnlyWhileItsPosesSolveWithIt) {
  const std::vector<Part> parts = test::three_beams();
  PartFactors factors(parts, fem::StaticSolverOptions{}, FactorStages{.assembly = true}, "case.toml", test::quiet_log());
  factors.lend(0);
  factors.done(0, FactorUser::Stress);
  ASSERT_NE(factors.held(0), nullptr);
  EXPECT_TRUE(factors.held(0)->is_factorized());
  factors.done(0, FactorUser::AssemblySetUp, /*still_needed=*/true);
  EXPECT_TRUE(factors.held(0)->is_factorized());
  factors.lend(1);
  factors.done(1, FactorUser::Stress);
  factors.done(1, FactorUser::AssemblySetUp, /*still_needed=*/false);
  ASSERT_NE(factors.held(1), nullptr);
  EXPECT_FALSE(factors.held(1)->is_factorized()) << "superposed: no pose needs it";
  factors.done_all(FactorUser::Assembly);
  EXPECT_EQ(factors.held(0), nullptr);
}

TEST(PartFactors, TheVibrationKeepsEveryFactorUntilItIsDone) {
  const std::vector<Part> parts = test::three_beams();
  PartFactors factors(parts, fem::StaticSolverOptions{}, FactorStages{.assembly = true, .vibration = true}, "case.toml",
                      test::quiet_log());
  factors.lend(0);
  factors.done(0, FactorUser::Stress);
  factors.done(0, FactorUser::AssemblySetUp, false);
  factors.done_all(FactorUser::Assembly);
  ASSERT_NE(factors.held(0), nullptr);
  EXPECT_TRUE(factors.held(0)->is_factorized());
  factors.done_all(FactorUser::Vibration);
  EXPECT_EQ(factors.held(0), nullptr);
}

TEST(PartFactors, FactorsNotFittingTogetherGoOneAtATimeAndForceSuperposition) {
  const std::vector<Part> parts = test::three_beams();
  const fem::StaticSolverOptions tight = tight_for(parts);
  PartFactors factors(parts, tight, FactorStages{.assembly = true}, "case.toml", test::quiet_log());
  EXPECT_FALSE(factors.factors_fit_together());
  EXPECT_EQ(factors.report().side_by_side, 1);
  EXPECT_TRUE(factors.superpose_assembly_loads(2));
  EXPECT_FALSE(factors.held(0)->is_factorized()) << "made right before its part's stress";
  EXPECT_TRUE(factors.lend_analysis(0).is_factorized());

  PartFactors fitting(parts, fem::StaticSolverOptions{}, FactorStages{.assembly = true}, "case.toml", test::quiet_log());
  EXPECT_FALSE(fitting.superpose_assembly_loads(kMinSuperposedPoses - 1));
  EXPECT_TRUE(fitting.superpose_assembly_loads(kMinSuperposedPoses));
}

TEST(PartFactors, TheVibrationWithFactorsNotFittingTogetherBorrowsThemOneAtATime) {
  const std::vector<Part> parts = test::three_beams();
  PartFactors factors(parts, tight_for(parts), FactorStages{.assembly = true, .vibration = true}, "case.toml",
                      test::quiet_log());
  EXPECT_FALSE(factors.factors_fit_together());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    factors.lend(k);
    factors.done(k, FactorUser::Stress);
    factors.lend(k);
    factors.done(k, FactorUser::AssemblySetUp);
    ASSERT_NE(factors.held(k), nullptr) << "kept for the vibration";
    EXPECT_EQ(factors.held(k)->is_factorized(), k + 1 == parts.size())
        << "freed after the assembly's set-up, but the last, which the vibration uses first";
  }
  vibration::PartFactorLender& lender = factors.vibration_lender();
  EXPECT_TRUE(lender.lend(parts[1].body()).is_factorized()) << "made again for the vibration";
  lender.give_back(parts[1].body());
  EXPECT_FALSE(factors.held(1)->is_factorized()) << "freed between the reductions' uses";
  EXPECT_THROW(lender.lend("no such body"), Error);

  PartFactors fitting(parts, fem::StaticSolverOptions{}, FactorStages{.assembly = true, .vibration = true},
                      "case.toml", test::quiet_log());
  fitting.done(0, FactorUser::AssemblySetUp);
  fitting.vibration_lender().give_back(parts[0].body());
  EXPECT_TRUE(fitting.held(0)->is_factorized()) << "factors that fit together stay";
}

}  // namespace
}  // namespace kinetofem::pipeline
