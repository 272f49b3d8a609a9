// Palmgren-Miner damage of constant and two-level amplitude histories
// against the closed form D = sum n_i / N_i with N_i from EN 1993-1-9
// figure 7.1 (1e-12 relative), and the cut-off limit: a history whose range
// is below Delta sigma_L does no damage.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/miner.hpp"

namespace kinetofem::fatigue {
namespace {

// k cycles of range 2 a about mean m: m - a, m + a, m - a, ..., m - a.
std::vector<double> constant_amplitude(double mean, double a, int k) {
  std::vector<double> h;
  for (int i = 0; i < k; ++i) {
    h.push_back(mean - a);
    h.push_back(mean + a);
  }
  h.push_back(mean - a);
  return h;
}

TEST(MinerConstantAmplitude, DamageIsCyclesOverEndurance) {
  const SnCurve curve({.detail_category_mpa = 71});
  const double range = 100 * units::kMpa;
  const int k = 1000;
  const std::vector<Cycle> cycles = rainflow_count(constant_amplitude(0.0, 0.5 * range, k));
  EXPECT_EQ(total_count(cycles), k);
  const double n_r = 2e6 * std::pow(71.0 / 100.0, 3.0);
  const double d = miner_damage(cycles, curve);
  EXPECT_NEAR(d, k / n_r, 1e-12 * k / n_r);
  EXPECT_NEAR(life_repetitions(d), n_r / k, 1e-12 * n_r / k);
  // The same as one period of a repeated history.
  const std::vector<Cycle> periodic =
      rainflow_count(constant_amplitude(0.0, 0.5 * range, k), Residue::Periodic);
  EXPECT_EQ(total_count(periodic), k);
  EXPECT_NEAR(miner_damage(periodic, curve), k / n_r, 1e-12 * k / n_r);
}

TEST(MinerConstantAmplitude, RangeBelowTheCutOffDoesNoDamage) {
  const SnCurve curve({.detail_category_mpa = 71});
  const double range = 0.999 * curve.cut_off_limit_pa();
  const std::vector<Cycle> cycles = rainflow_count(constant_amplitude(50e6, 0.5 * range, 10000));
  EXPECT_EQ(miner_damage(cycles, curve), 0.0);
  EXPECT_EQ(life_repetitions(0.0), std::numeric_limits<double>::infinity());
}

// One range on the m = 3 branch, one on the m = 5 branch, one below the cut-off.
TEST(MinerConstantAmplitude, ThreeLevelsAddUp) {
  const SnCurve curve({.detail_category_mpa = 160, .gamma_ff = 1.0, .gamma_mf = 1.15});
  const double c = 160 * units::kMpa, d = curve.constant_amplitude_limit_pa(),
               l = curve.cut_off_limit_pa();
  const double r1 = 150 * units::kMpa, r2 = 90 * units::kMpa, r3 = 0.9 * l / 1.15;
  ASSERT_GT(1.15 * r1, d);
  ASSERT_LT(1.15 * r2, d);
  ASSERT_GT(1.15 * r2, l);
  const std::vector<Cycle> cycles = {
      {.range_pa = r1, .mean_pa = 0.0, .count = 1.0},
      {.range_pa = r2, .mean_pa = 0.0, .count = 0.5},
      {.range_pa = r3, .mean_pa = 0.0, .count = 1.0},
  };
  const double n1 = 2e6 * std::pow(c / (1.15 * r1), 3.0);
  const double n2 = 5e6 * std::pow(d / (1.15 * r2), 5.0);
  const double expected = 1.0 / n1 + 0.5 / n2;
  EXPECT_NEAR(miner_damage(cycles, curve), expected, 1e-12 * expected);
}

// EN 1993-1-9 7.2.1(1): a fully compressive cycle counts at 0.6 of its
// range, one through zero as sigma_max + 0.6 |sigma_min| (non-welded or
// stress-relieved details).
TEST(MinerConstantAmplitude, ReducedCompressionOfTheMeanStressOption) {
  const SnCurve curve({.detail_category_mpa = 71});
  const double range = 200 * units::kMpa;
  const std::vector<Cycle> compressive = {{.range_pa = range, .mean_pa = -100e6 - 1e6, .count = 1}};
  const std::vector<Cycle> through_zero = {{.range_pa = range, .mean_pa = 20e6, .count = 1}};
  const auto d = [&](double r) { return 1.0 / (2e6 * std::pow(71e6 / r, 3.0)); };
  EXPECT_NEAR(miner_damage(compressive, curve, MeanStressTreatment::ReducedCompression),
              d(0.6 * range), 1e-12 * d(0.6 * range));
  EXPECT_NEAR(miner_damage(through_zero, curve, MeanStressTreatment::ReducedCompression),
              d(120e6 + 0.6 * 80e6), 1e-12 * d(168e6));
  EXPECT_NEAR(miner_damage(through_zero, curve, MeanStressTreatment::None), d(range),
              1e-12 * d(range));
}

}  // namespace
}  // namespace kinetofem::fatigue
