// Unit tests of the planar four-bar (SPEC §2): position on the design branch,
// loop-closure derivatives, assembly limits, Grashof classes.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/four_bar.hpp"

namespace km = kinetofem::mech;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Crank-rocker: ground 0.4, crank 0.1, coupler 0.35, rocker 0.3 (s + l = 0.5 <
// p + q = 0.65), design input 60 deg, elbow-up branch.
km::FourBar crank_rocker(bool mirror = false) {
  const Eigen::Vector2d a0(0.0, 0.0), b0(0.4, 0.0);
  const Eigen::Vector2d a = 0.1 * Eigen::Vector2d(std::cos(60 * kDeg), std::sin(60 * kDeg));
  // B on the circle of radius 0.3 about B0, 0.35 from A, on the chosen side.
  const Eigen::Vector2d w = b0 - a;
  const double d = w.norm();
  const double x = (0.35 * 0.35 - 0.3 * 0.3 + d * d) / (2.0 * d);
  const double y = std::sqrt(0.35 * 0.35 - x * x);
  const Eigen::Vector2d n(-w.y() / d, w.x() / d);
  const Eigen::Vector2d b = a + x * w / d + (mirror ? -y : y) * n;
  km::FourBar fb = km::FourBar::from_design_position(a0, a, b, b0);
  fb.add_coupler_point(a + Eigen::Vector2d(0.1, 0.2));
  return fb;
}

}  // namespace

TEST(FourBar, ReproducesDesignPositionAndBranch) {
  for (bool mirror : {false, true}) {
    const km::FourBar fb = crank_rocker(mirror);
    EXPECT_EQ(fb.branch(), mirror ? -1 : 1);
    const km::FourBarPose p = fb.pose(fb.design_input_rad());
    EXPECT_NEAR((p.a_m - 0.1 * Eigen::Vector2d(0.5, std::sqrt(0.75))).norm(), 0.0, 1e-15);
    EXPECT_NEAR((p.b_m - Eigen::Vector2d(0.4, 0.0)).norm(), 0.3, 1e-14);
    EXPECT_NEAR((p.b_m - p.a_m).norm(), 0.35, 1e-14);
    EXPECT_NEAR((p.coupler_points[0].p - p.a_m - Eigen::Vector2d(0.1, 0.2)).norm(), 0.0, 1e-14);
  }
}

TEST(FourBar, DerivativesMatchFiniteDifferences) {
  const km::FourBar fb = crank_rocker();
  const double h = 1e-5, tol = 1e-7;  // central-difference error ~1e-10 + round-off 1e-11
  for (double deg = 0.0; deg < 360.0; deg += 15.0) {
    const double x = deg * kDeg;
    const km::FourBarPose p = fb.pose(x);
    const km::FourBarPose pp = fb.pose(x + h), pm = fb.pose(x - h);
    EXPECT_NEAR(p.coupler_d1,
                std::remainder(pp.coupler_angle_rad - pm.coupler_angle_rad, 2 * std::numbers::pi) /
                    (2 * h), tol) << deg;
    EXPECT_NEAR(p.rocker_d1,
                std::remainder(pp.rocker_angle_rad - pm.rocker_angle_rad, 2 * std::numbers::pi) /
                    (2 * h), tol) << deg;
    EXPECT_NEAR(p.coupler_d2, (pp.coupler_d1 - pm.coupler_d1) / (2 * h), tol) << deg;
    EXPECT_NEAR(p.rocker_d2, (pp.rocker_d1 - pm.rocker_d1) / (2 * h), tol) << deg;
    const auto& c = p.coupler_points[0];
    EXPECT_LT((c.d1 - (pp.coupler_points[0].p - pm.coupler_points[0].p) / (2 * h)).norm(), tol);
    EXPECT_LT((c.d2 - (pp.coupler_points[0].d1 - pm.coupler_points[0].d1) / (2 * h)).norm(), tol);
  }
}

TEST(FourBar, GrashofClasses) {
  auto make = [](double ground, double crank, double coupler, double rocker) {
    // Build a design position with the crank at 90 deg; B by circle intersection.
    const Eigen::Vector2d a0(0, 0), b0(ground, 0), a(0, crank);
    const Eigen::Vector2d w = b0 - a;
    const double d = w.norm();
    const double x = (coupler * coupler - rocker * rocker + d * d) / (2 * d);
    const double y = std::sqrt(coupler * coupler - x * x);
    const Eigen::Vector2d n(-w.y() / d, w.x() / d);
    return km::FourBar::from_design_position(a0, a, a + x * w / d + y * n, b0);
  };
  EXPECT_EQ(make(0.4, 0.1, 0.35, 0.3).grashof(), km::GrashofClass::crank_rocker);
  EXPECT_EQ(make(0.1, 0.3, 0.35, 0.3).grashof(), km::GrashofClass::double_crank);
  EXPECT_EQ(make(0.3, 0.25, 0.1, 0.35).grashof(), km::GrashofClass::double_rocker);
  EXPECT_EQ(make(0.3, 0.25, 0.35, 0.1).grashof(), km::GrashofClass::rocker_crank);
  EXPECT_EQ(make(0.4, 0.35, 0.3, 0.28).grashof(), km::GrashofClass::triple_rocker);
  EXPECT_EQ(make(0.4, 0.1, 0.35, 0.15).grashof(), km::GrashofClass::change_point);
}

TEST(FourBar, CrankRockerTurnsFully) {
  const km::FourBar fb = crank_rocker();
  EXPECT_TRUE(fb.assembly_range().full_rotation);
}

TEST(FourBar, TripleRockerLimitsAreFoundAndBranchIsContinuous) {
  // Non-Grashof: ground 0.4, crank 0.35, coupler 0.3, rocker 0.28 (0.68 > 0.65).
  const Eigen::Vector2d a0(0, 0), b0(0.4, 0), a(0, 0.35);
  const Eigen::Vector2d w = b0 - a;
  const double d = w.norm();
  const double x = (0.3 * 0.3 - 0.28 * 0.28 + d * d) / (2 * d);
  const double y = std::sqrt(0.3 * 0.3 - x * x);
  const Eigen::Vector2d n(-w.y() / d, w.x() / d);
  const km::FourBar fb = km::FourBar::from_design_position(a0, a, a + x * w / d + y * n, b0);
  const km::AssemblyRange r = fb.assembly_range();
  ASSERT_FALSE(r.full_rotation);
  EXPECT_LT(r.lo_rad, fb.design_input_rad());
  EXPECT_GT(r.hi_rad, fb.design_input_rad());
  // At a limit |A B0| = l2 + l3 or |l2 - l3|: the margin vanishes (bisection
  // to 1e-12 rad, margin slope <= crank length) and coupler/rocker are collinear.
  for (double lim : {r.lo_rad, r.hi_rad}) {
    EXPECT_NEAR(fb.assembly_margin_m(lim), 0.0, 1e-11);
    EXPECT_FALSE(fb.can_assemble(lim + (lim > fb.design_input_rad() ? 1e-9 : -1e-9)));
    EXPECT_THROW(fb.pose(lim + (lim > fb.design_input_rad() ? 1e-6 : -1e-6)), kinetofem::Error);
    const double mu = fb.pose(lim).transmission_angle_rad;
    EXPECT_LT(std::min(mu, std::numbers::pi - mu), 1e-4);
  }
  // Continuity on the design branch: the side of B relative to the line A->B0
  // (the branch) never changes inside the range, and between steps of 1/400 of
  // the range B moves less than |dB/dphi| * step (|dB/dphi| < 3 m/rad here away
  // from the last 2 % at each limit, where the rocker speed grows like 1/sqrt).
  auto side = [](const km::FourBarPose& p, const Eigen::Vector2d& b0v) {
    const Eigen::Vector2d u = p.b_m - p.a_m, v = b0v - p.a_m;
    return u.x() * v.y() - u.y() * v.x() < 0.0 ? 1 : -1;
  };
  const double span = r.hi_rad - r.lo_rad;
  const int design_side = side(fb.pose(fb.design_input_rad()), b0);
  Eigen::Vector2d prev = fb.pose(r.lo_rad + 0.02 * span).b_m;
  const int steps = 400;
  for (int k = 0; k <= steps; ++k) {
    const double phi = r.lo_rad + 0.02 * span + 0.96 * span * k / steps;
    const km::FourBarPose p = fb.pose(phi);
    EXPECT_EQ(side(p, b0), design_side) << phi;
    EXPECT_LT((p.b_m - prev).norm(), 3.0 * 0.96 * span / steps) << phi;
    prev = p.b_m;
  }
}

TEST(FourBar, RejectsBadDesign) {
  const Eigen::Vector2d a0(0, 0), b0(0.4, 0);
  EXPECT_THROW(km::FourBar::from_design_position(a0, a0, {0.2, 0.2}, b0), kinetofem::Error);
  EXPECT_THROW(km::FourBar::from_design_position(a0, {0, 0.1}, {0, 0.1}, b0), kinetofem::Error);
  // Collinear coupler and rocker: a limit position, branch undefined.
  EXPECT_THROW(km::FourBar::from_design_position(a0, {0, 0.1}, {0.2, 0.05}, b0),
               kinetofem::Error);
  const km::FourBar fb = crank_rocker();
  EXPECT_THROW(fb.pose(NAN), kinetofem::Error);
}
