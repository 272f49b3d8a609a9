// Unit tests of Q-manipulators with constant-ratio CTMs (SPEC §4).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/q_manipulator.hpp"

namespace km = kinetofem::mech;

TEST(QManipulator, TwoLinkMatchesSpecFormula) {
  const double l1 = 0.7, l2 = 0.3, i = 2.5;
  const km::QManipulator q = km::make_two_link_q_manipulator(l1, l2, i);
  for (double p = -3.0; p <= 3.0; p += 0.37) {
    const Eigen::Vector2d h = q.point_h(p).p;
    // SPEC §4: xH = l1 cos(P) + l2 cos(P (1 - i)), same with sin for yH.
    EXPECT_NEAR(h.x(), l1 * std::cos(p) + l2 * std::cos(p * (1 - i)), 1e-15);
    EXPECT_NEAR(h.y(), l1 * std::sin(p) + l2 * std::sin(p * (1 - i)), 1e-15);
  }
}

TEST(QManipulator, ThreeLinkMatchesII24) {
  const double L1 = 0.5, L2 = 0.3, L3 = 0.2, i21 = 1.5, i32 = 0.75;
  const km::QManipulator q = km::make_three_link_q_manipulator(L1, L2, L3, i21, i32);
  EXPECT_DOUBLE_EQ(q.angle_rates()[2], 1 - i21 + i21 * i32);
  for (double p = -2.0; p <= 2.0; p += 0.25) {
    const Eigen::Vector2d h = q.point_h(p).p;
    const double t3 = p * (1 - i21 + i21 * i32);
    EXPECT_NEAR(h.x(), L1 * std::cos(p) + L2 * std::cos(p * (1 - i21)) + L3 * std::cos(t3), 1e-15);
    EXPECT_NEAR(h.y(), L1 * std::sin(p) + L2 * std::sin(p * (1 - i21)) + L3 * std::sin(t3), 1e-15);
  }
}

TEST(QManipulator, GeneralRatesFollowAlternatingProducts) {
  // K_4 = 1 - i1 + i1 i2 - i1 i2 i3 ((II.23) with (-1)^(j-1)).
  const km::QManipulator q({1, 1, 1, 1}, {2.0, 3.0, 0.5}, {0.1, 0.2, 0.3, 0.4});
  EXPECT_DOUBLE_EQ(q.angle_rates()[3], 1 - 2.0 + 6.0 - 3.0);
  EXPECT_NEAR(q.link_angle_rad(4, 0.0), 1.0, 1e-15);
  EXPECT_NEAR(q.link_angle_rad(2, 1.0), 0.3 + (1 - 2.0), 1e-15);
}

TEST(QManipulator, DerivativesMatchFiniteDifferences) {
  const km::QManipulator q({0.4, 0.3, 0.2}, {1.7, -0.6}, {0.2, -0.4, 1.0});
  const double h = 1e-5;  // central-difference error ~1e-10 for O(1) data
  for (double p = -3.0; p <= 3.0; p += 0.5) {
    const auto k = q.point_h(p);
    EXPECT_LT((k.d1 - (q.point_h(p + h).p - q.point_h(p - h).p) / (2 * h)).norm(), 1e-8);
    EXPECT_LT((k.d2 - (q.point_h(p + h).d1 - q.point_h(p - h).d1) / (2 * h)).norm(), 1e-8);
  }
}

TEST(QManipulator, CuspsOfTwoLinkChains) {
  const double pi = std::numbers::pi;
  // l2 (1 - i) = -l1 (i = 3, l2 = l1/2): cusps at P = 2 j pi / i.
  const km::QManipulator rose = km::make_two_link_q_manipulator(1.0, 0.5, 3.0);
  EXPECT_TRUE(km::two_link_has_cusps(1.0, 0.5, 3.0));
  const auto c1 = rose.find_cusps(-0.1, 2 * pi - 0.1);
  ASSERT_EQ(c1.size(), 3u);
  for (std::size_t j = 0; j < 3; ++j) EXPECT_NEAR(c1[j], 2 * pi * j / 3.0, 1e-6);
  // l2 (1 - i) = +l1 (i = 0.5, l2 = 2 l1): cusps at P = (2j + 1) pi / i.
  const km::QManipulator q2 = km::make_two_link_q_manipulator(1.0, 2.0, 0.5);
  EXPECT_TRUE(km::two_link_has_cusps(1.0, 2.0, 0.5));
  const auto c2 = q2.find_cusps(0.0, 8 * pi, 8000);
  ASSERT_EQ(c2.size(), 2u);
  EXPECT_NEAR(c2[0], 2 * pi, 1e-6);
  EXPECT_NEAR(c2[1], 6 * pi, 1e-6);
  // Off the condition there are no cusps.
  EXPECT_FALSE(km::two_link_has_cusps(1.0, 0.45, 3.0));
  EXPECT_TRUE(km::make_two_link_q_manipulator(1.0, 0.45, 3.0).find_cusps(0, 2 * pi).empty());
}

TEST(QManipulator, IsokinematicEquivalentTracesTheSameCurve) {
  for (double i : {3.0, 0.4, -1.5}) {
    const km::QManipulator q = km::make_two_link_q_manipulator(0.6, 0.25, i, 0.3);
    const km::IsokinematicEquivalent eq = km::isokinematic_equivalent(q);
    EXPECT_DOUBLE_EQ(eq.manipulator.lengths_m()[0], 0.25);
    EXPECT_DOUBLE_EQ(eq.manipulator.lengths_m()[1], 0.6);
    // 1 - i' = 1 / (1 - i).
    EXPECT_NEAR(1 - eq.manipulator.ratios()[0], 1 / (1 - i), 1e-15);
    EXPECT_DOUBLE_EQ(eq.lever_angle_scale, 1 - i);
    for (double p = -4.0; p <= 4.0; p += 0.1) {
      const Eigen::Vector2d a = q.point_h(p).p;
      const Eigen::Vector2d b = eq.manipulator.point_h(eq.lever_angle_scale * p).p;
      EXPECT_NEAR((a - b).norm(), 0.0, 1e-14) << "i = " << i << ", P = " << p;
    }
  }
}

TEST(QManipulator, RejectsBadInput) {
  EXPECT_THROW(km::QManipulator({}, {}), kinetofem::Error);
  EXPECT_THROW(km::QManipulator({1.0, -1.0}, {2.0}), kinetofem::Error);
  EXPECT_THROW(km::QManipulator({1.0, 1.0}, {}), kinetofem::Error);
  EXPECT_THROW(km::QManipulator({1.0, 1.0}, {2.0}, {0.0}), kinetofem::Error);
  EXPECT_THROW(km::isokinematic_equivalent(km::make_two_link_q_manipulator(1, 1, 1.0)),
               kinetofem::Error);
  EXPECT_THROW(km::isokinematic_equivalent(km::make_three_link_q_manipulator(1, 1, 1, 2, 2)),
               kinetofem::Error);
  EXPECT_THROW(km::make_two_link_q_manipulator(1, 1, 2).link_angle_rad(3, 0.0), kinetofem::Error);
}
