// SPEC §4 (seeds/002, ch. II): two- and three-link Q-manipulators, cusps and
// isokinematic equivalents.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/q_manipulator.hpp"

namespace km = kinetofem::mech;

TEST(Spec4QManipulator, CuspConditionL1EqualsL2TimesOneMinusI) {
  // SPEC §4: cusps appear when l1 = |l2 (1 - i)|. Over a set of ratios, the
  // numerical cusp finder (|H'| <= 1e-6 of its scale) finds cusps exactly when
  // the condition holds, and none when l2 is 2 % off.
  const double pi = std::numbers::pi;
  for (double i : {-2.0, -0.5, 0.25, 0.5, 2.0, 3.0, 5.0}) {
    const double l1 = 1.0, l2 = l1 / std::abs(1.0 - i);
    const double period = 2 * pi / std::abs(i) * 2;  // covers at least 2 cusp spacings
    const auto on = km::make_two_link_q_manipulator(l1, l2, i).find_cusps(0.05, 0.05 + 4 * pi / std::abs(i), 4000);
    EXPECT_GE(on.size(), 1u) << "i = " << i;
    for (double p : on)
      EXPECT_LT(km::make_two_link_q_manipulator(l1, l2, i).point_h(p).d1.norm(), 1e-6) << i;
    const auto off =
        km::make_two_link_q_manipulator(l1, 1.02 * l2, i).find_cusps(0.05, 0.05 + period, 4000);
    EXPECT_TRUE(off.empty()) << "i = " << i;
  }
}

TEST(Spec4QManipulator, IsokinematicPairTracesTheSamePointSet) {
  // SPEC §4: l1' = l2, l2' = l1, 1 - i' = 1/(1 - i) trace the same curve. For a
  // rose (i = 4, 1 - i = -3) both closed curves are sampled over their periods
  // (2 pi and 6 pi) and compared as point sets: each point of one must lie within
  // the sampling chord (|H'| max * step) of the other set.
  const double pi = std::numbers::pi;
  const km::QManipulator q = km::make_two_link_q_manipulator(0.5, 0.2, 4.0);
  const km::IsokinematicEquivalent eq = km::isokinematic_equivalent(q);
  const int n = 6000;
  std::vector<Eigen::Vector2d> a, b;
  for (int k = 0; k < n; ++k) a.push_back(q.point_h(2 * pi * k / n).p);
  for (int k = 0; k < 3 * n; ++k) b.push_back(eq.manipulator.point_h(6 * pi * k / (3 * n)).p);
  auto max_min_dist = [](const std::vector<Eigen::Vector2d>& from,
                         const std::vector<Eigen::Vector2d>& to) {
    double worst = 0.0;
    for (const auto& p : from) {
      double best = std::numeric_limits<double>::infinity();
      for (const auto& r : to) best = std::min(best, (p - r).squaredNorm());
      worst = std::max(worst, std::sqrt(best));
    }
    return worst;
  };
  // |H'| <= l1 + 3 l2 = 1.1; step 2 pi / 6000: chord <= 1.2e-3.
  const double d_ab = max_min_dist(a, b), d_ba = max_min_dist(b, a);
  fmt::print("SPEC4 isokinematic rose i = 4: Hausdorff distance {:.3e} m (i' = {:.6f})\n",
             std::max(d_ab, d_ba), eq.manipulator.ratios()[0]);
  EXPECT_LT(std::max(d_ab, d_ba), 1.2e-3);
  // The reparametrisation P' = (1 - i) P maps them point by point (round-off).
  for (int k = 0; k < 100; ++k) {
    const double p = 0.0628 * k;
    EXPECT_LT((q.point_h(p).p - eq.manipulator.point_h(-3.0 * p).p).norm(), 1e-14);
  }
}
