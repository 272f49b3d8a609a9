// The EN 1993-1-9:2005 S-N curve for direct stress ranges (7.1(3), figure
// 7.1) at its three corner points, for every detail category of tables
// 8.1-8.10 (71 and 160 among them):
//   N(Delta sigma_C) = 2e6, N(Delta sigma_D) = 5e6, N(Delta sigma_L) = 1e8,
//   Delta sigma_D = (2/5)^(1/3) Delta sigma_C (= 0.737 Delta sigma_C),
//   Delta sigma_L = (5/100)^(1/5) Delta sigma_D (= 0.549 Delta sigma_D = 0.405 Delta sigma_C).
// Exact formulas to round-off (1e-12 relative); the standard's rounded
// factors to their 3 digits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/sn_curve.hpp"

namespace kinetofem::fatigue {
namespace {

constexpr double kRel = 1e-12;

void expect_rel(double actual, double expected, double rel) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected));
}

TEST(SnCurveEn1993, CornerPointsOfEveryDetailCategory) {
  std::vector<double> categories(detail_categories_mpa().begin(), detail_categories_mpa().end());
  ASSERT_EQ(categories.size(), 14u);
  for (double category : categories) {
    SCOPED_TRACE(category);
    const SnCurve curve({.detail_category_mpa = category});
    const double c = category * units::kMpa;
    const double d = std::cbrt(2.0 / 5.0) * c;
    const double l = std::pow(5.0 / 100.0, 1.0 / 5.0) * d;
    expect_rel(curve.detail_category_pa(), c, kRel);
    expect_rel(curve.constant_amplitude_limit_pa(), d, kRel);
    expect_rel(curve.cut_off_limit_pa(), l, kRel);
    expect_rel(curve.constant_amplitude_limit_pa(), 0.737 * c, 1e-3);
    expect_rel(curve.cut_off_limit_pa(), 0.549 * d, 1e-3);
    expect_rel(curve.cut_off_limit_pa(), 0.405 * c, 1.5e-3);
    expect_rel(curve.characteristic_endurance(c), 2e6, kRel);
    expect_rel(curve.characteristic_endurance(d), 5e6, kRel);
    expect_rel(curve.characteristic_endurance(l), 1e8, kRel);
    // Slopes: m = 3 above Delta sigma_D, m = 5 between Delta sigma_L and Delta sigma_D.
    expect_rel(curve.characteristic_endurance(2.0 * c), 2e6 / 8.0, kRel);
    const double mid = std::sqrt(d * l);
    expect_rel(curve.characteristic_endurance(mid), 5e6 * std::pow(d / mid, 5.0), kRel);
    EXPECT_EQ(curve.characteristic_endurance(l * (1.0 - 1e-12)),
              std::numeric_limits<double>::infinity());
    EXPECT_EQ(curve.characteristic_endurance(0.0), std::numeric_limits<double>::infinity());
  }
}

TEST(SnCurveEn1993, Categories71And160InNumbers) {
  const SnCurve c71({.detail_category_mpa = 71});
  const SnCurve c160({.detail_category_mpa = 160});
  // 71 * 0.7368063 = 52.313 MPa, * 0.5492803 = 28.734 MPa.
  EXPECT_NEAR(c71.constant_amplitude_limit_pa() / units::kMpa, 52.3132, 1e-4);
  EXPECT_NEAR(c71.cut_off_limit_pa() / units::kMpa, 28.7346, 1e-4);
  EXPECT_NEAR(c160.constant_amplitude_limit_pa() / units::kMpa, 117.8890, 1e-4);
  EXPECT_NEAR(c160.cut_off_limit_pa() / units::kMpa, 64.7541, 1e-4);
}

// gamma_Ff on the range, gamma_Mf on the resistance: the design endurance of
// Delta sigma is the characteristic one of gamma_Ff gamma_Mf Delta sigma; at
// Delta sigma = Delta sigma_C / (gamma_Ff gamma_Mf) it is N_C.
TEST(SnCurveEn1993, PartialFactorsScaleTheRange) {
  const SnCurve curve({.detail_category_mpa = 71, .gamma_ff = 1.1, .gamma_mf = 1.35});
  const double c = 71 * units::kMpa;
  expect_rel(curve.endurance(c / (1.1 * 1.35)), 2e6, kRel);
  expect_rel(curve.endurance(c), 2e6 / std::pow(1.1 * 1.35, 3.0), kRel);
  // Cut-off of the design curve: gamma_Ff Delta sigma < Delta sigma_L / gamma_Mf.
  EXPECT_EQ(curve.endurance(0.99 * curve.cut_off_limit_pa() / (1.1 * 1.35)),
            std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isfinite(curve.endurance(1.01 * curve.cut_off_limit_pa() / (1.1 * 1.35))));
}

// Size effect k_s = (25/t)^0.2 scales the whole curve (Delta sigma_C,red).
TEST(SnCurveEn1993, SizeFactorScalesTheWholeCurve) {
  const double ks = thickness_size_factor(0.040);
  expect_rel(ks, std::pow(25.0 / 40.0, 0.2), kRel);
  const SnCurve curve({.detail_category_mpa = 90, .size_factor = ks});
  expect_rel(curve.detail_category_pa(), ks * 90 * units::kMpa, kRel);
  expect_rel(curve.characteristic_endurance(ks * 90 * units::kMpa), 2e6, kRel);
  expect_rel(curve.characteristic_endurance(curve.cut_off_limit_pa()), 1e8, kRel);
}

}  // namespace
}  // namespace kinetofem::fatigue
