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
#include "kinetofem/verification/spec4_q_manipulator.hpp"

namespace km = kinetofem::mech;
namespace s4 = kinetofem::verification::spec4;

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
  // the sampling chord (|H'| max * step) of the other set. The rose, the
  // sampling and the distances are those of `kinetofem verify`
  // (kinetofem/verification/spec4_q_manipulator.hpp).
  const km::QManipulator q = s4::rose();
  const km::IsokinematicEquivalent eq = km::isokinematic_equivalent(q);
  const int n = 6000;
  // |H'| <= l1 + 3 l2 = 1.1; step 2 pi / 6000: chord <= 1.2e-3.
  const double hausdorff = s4::rose_pair_hausdorff(q, eq, n);
  fmt::print("SPEC4 isokinematic rose i = 4: Hausdorff distance {:.3e} m (i' = {:.6f})\n", hausdorff,
             eq.manipulator.ratios()[0]);
  EXPECT_LT(hausdorff, 1.2e-3);
  // The reparametrisation P' = (1 - i) P maps them point by point (round-off).
  EXPECT_LT(s4::pointwise_distance(q, eq, 100, 0.0628), 1e-14);
}
