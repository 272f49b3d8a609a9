// Unit tests of the lever-chain manipulator model (SPEC §1) and the path
// straightness measure.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/path_straightness.hpp"

namespace km = kinetofem::mech;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// SPEC §1 example in metres.
km::LeverChainGeometry example() { return km::make_lever_chain_geometry(0.5, 0.35, 0.1, 0.075); }

// Central difference of f at x with step h (truncation error ~ h^2 f'''/6).
template <typename F>
auto central(F f, double x, double h) {
  return (f(x + h) - f(x - h)) / (2.0 * h);
}

}  // namespace

TEST(LeverChain, RejectsBadGeometry) {
  EXPECT_THROW(km::make_lever_chain_geometry(0.0, 0.35, 0.1, 0.075), kinetofem::Error);
  EXPECT_THROW(km::make_lever_chain_geometry(0.5, -0.35, 0.1, 0.075), kinetofem::Error);
  EXPECT_THROW(km::make_lever_chain_geometry(0.5, 0.35, -0.1, 0.075), kinetofem::Error);
  EXPECT_THROW(km::make_lever_chain_geometry(0.5, 0.35, 0.1, 0.0), kinetofem::Error);
  EXPECT_THROW(km::make_lever_chain_geometry(NAN, 0.35, 0.1, 0.075), kinetofem::Error);
  km::LeverChainGeometry g = example();
  g.b0_m *= 1.01;  // inconsistent with (1)
  EXPECT_THROW(km::LeverChain{g}, kinetofem::Error);
}

TEST(LeverChain, DesignPositionMatchesConstruction) {
  const km::LeverChainGeometry g = example();
  const km::LeverChain lc(g);
  const km::LeverChainPose p = lc.pose(0.0);
  // Exact geometry of the design position (SPEC §1 figure): tolerance = rounding.
  EXPECT_NEAR(p.ctm.dpsi_rad, 0.0, 1e-14);
  EXPECT_NEAR(p.ctm.b_m, g.b0_m, 1e-14);
  EXPECT_NEAR(p.ctm.beta_rad, 0.5 * std::numbers::pi, 1e-14);
  EXPECT_NEAR((p.c.p - Eigen::Vector2d(-g.c_m, g.a_m)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((p.h.p - Eigen::Vector2d(-g.c_m, g.a_m + g.h_m)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((p.tangent_point.p - Eigen::Vector2d(g.r_m, g.a_m)).norm(), 0.0, 1e-14);
  EXPECT_NEAR((g.b0_point_m - g.l0_m * Eigen::Vector2d(std::cos(g.alpha0_rad),
                                                       std::sin(g.alpha0_rad))).norm(),
              0.0, 1e-14);
  // First-order osculation: the path of every arm point is horizontal there.
  EXPECT_NEAR(p.theta_d1, 0.0, 1e-14);
  EXPECT_NEAR(p.c.d1.y(), 0.0, 1e-14);
  EXPECT_NEAR(p.h.d1.y(), 0.0, 1e-14);
}

TEST(LeverChain, ChainGeometryStaysTangent) {
  const km::LeverChainGeometry g = example();
  const km::LeverChain lc(g);
  for (double deg = -70.0; deg <= 90.0; deg += 10.0) {
    const km::LeverChainPose p = lc.pose(deg * kDeg);
    const Eigen::Vector2d ab = p.tangent_point.p - p.a.p;
    const Eigen::Vector2d bb0 = g.b0_point_m - p.tangent_point.p;
    // |AB| = r, |BB0| = b, AB perpendicular to BB0: round-off tolerances.
    EXPECT_NEAR(ab.norm(), g.r_m, 1e-13) << deg;
    EXPECT_NEAR(bb0.norm(), p.ctm.b_m, 1e-13) << deg;
    EXPECT_NEAR(ab.dot(bb0), 0.0, 1e-13) << deg;
    EXPECT_NEAR(std::atan2(-bb0.y(), -bb0.x()),
                std::remainder(p.chain_angle_rad, 2.0 * std::numbers::pi), 1e-12);
  }
}

TEST(LeverChain, AnalyticDerivativesMatchFiniteDifferences) {
  const km::LeverChain lc(example());
  const double h = 1e-5;
  // Central differences of an O(1) smooth function with h = 1e-5 have error
  // ~1e-10 (truncation) + 1e-16/1e-5 (round-off); 1e-7 leaves a wide margin.
  const double tol = 1e-7;
  for (double deg = -72.0; deg <= 90.0; deg += 6.0) {
    const double x = deg * kDeg;
    const km::LeverChainPose p = lc.pose(x);
    auto ctm = [&](double t) { return lc.ctm(t); };
    EXPECT_NEAR(p.ctm.dpsi_d1, central([&](double t) { return ctm(t).dpsi_rad; }, x, h), tol);
    EXPECT_NEAR(p.ctm.dpsi_d2, central([&](double t) { return ctm(t).dpsi_d1; }, x, h), tol);
    EXPECT_NEAR(p.ctm.b_d1, central([&](double t) { return ctm(t).b_m; }, x, h), tol);
    EXPECT_NEAR(p.ctm.b_d2, central([&](double t) { return ctm(t).b_d1; }, x, h), tol);
    EXPECT_NEAR(p.ctm.beta_d1, central([&](double t) { return ctm(t).beta_rad; }, x, h), tol);
    EXPECT_NEAR(p.ctm.beta_d2, central([&](double t) { return ctm(t).beta_d1; }, x, h), tol);
    for (int which = 0; which < 3; ++which) {
      auto pick = [&](const km::LeverChainPose& q) -> const km::PointKinematics& {
        return which == 0 ? q.c : which == 1 ? q.h : q.tangent_point;
      };
      const Eigen::Vector2d fd1 =
          (pick(lc.pose(x + h)).p - pick(lc.pose(x - h)).p) / (2.0 * h);
      const Eigen::Vector2d fd2 =
          (pick(lc.pose(x + h)).d1 - pick(lc.pose(x - h)).d1) / (2.0 * h);
      EXPECT_LT((pick(p).d1 - fd1).norm(), tol) << "point " << which << " at " << deg;
      EXPECT_LT((pick(p).d2 - fd2).norm(), tol) << "point " << which << " at " << deg;
    }
  }
}

TEST(LeverChain, ThrowsWhenChainCannotWrap) {
  // a - l0 < r: at dphi = alpha0 - 90 deg, |A B0| = a - l0 is smaller than r.
  const auto g = km::make_lever_chain_geometry(0.1, 0.35, 0.0, 0.075);
  ASSERT_LT(g.a_m - g.l0_m, g.r_m);
  const km::LeverChain lc(g);
  const double bad = g.alpha0_rad - 0.5 * std::numbers::pi;
  EXPECT_FALSE(lc.can_assemble(bad));
  EXPECT_TRUE(lc.can_assemble(0.0));
  try {
    (void)lc.pose(bad);
    FAIL() << "expected kinetofem::Error";
  } catch (const kinetofem::Error& e) {
    EXPECT_NE(std::string(e.what()).find("dphi"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)lc.ctm(NAN), kinetofem::Error);
}

TEST(LeverChain, SynthesisRecoversTheExample) {
  // H0 and Hf taken from the mechanism itself; the synthesis (SPEC §1) must
  // return its a, c, h (round-off tolerance).
  const km::LeverChainGeometry g = example();
  const km::LeverChain lc(g);
  for (double phi_of_deg : {20.0, 45.0, 60.0, -40.0}) {
    const double phi_of = phi_of_deg * kDeg;
    const Eigen::Vector2d h0 = lc.pose(0.0).h.p;
    const Eigen::Vector2d hf = lc.pose(phi_of).h.p;
    const km::PrimaryChainSynthesis s = km::synthesize_primary_chain(h0, hf, phi_of);
    EXPECT_NEAR(s.a_m, g.a_m, 1e-12) << phi_of_deg;
    EXPECT_NEAR(s.c_m, g.c_m, 1e-12) << phi_of_deg;
    EXPECT_NEAR(s.h_m, g.h_m, 1e-12) << phi_of_deg;
    const km::LeverChainGeometry g2 = km::synthesize_lever_chain(h0, hf, phi_of, g.r_m);
    EXPECT_NEAR(g2.b0_m, g.b0_m, 1e-12);
  }
}

TEST(LeverChain, SynthesisRejectsBadInput) {
  EXPECT_THROW(km::synthesize_primary_chain({0.1, 0.6}, {-0.5, 0.6}, 0.5), kinetofem::Error);
  // Hf1 at the same height as H0: the bisector is vertical, A undetermined.
  EXPECT_THROW(km::synthesize_primary_chain({-0.35, 0.6}, {-0.5, 0.6}, 0.0), kinetofem::Error);
}

TEST(LeverChain, PointMotionFollowsChainRule) {
  const km::LeverChain lc(example());
  const double x = 15.0 * kDeg, w = 1.3, al = -0.7;
  const km::LeverChainPose p = lc.pose(x);
  const km::PointMotion m = km::point_motion(p.h, w, al);
  EXPECT_NEAR((m.velocity_mps - w * p.h.d1).norm(), 0.0, 1e-15);
  EXPECT_NEAR((m.acceleration_mps2 - (w * w * p.h.d2 + al * p.h.d1)).norm(), 0.0, 1e-14);
  // Tangential acceleration = d(speed)/dt for dphi(t) = x + w t + al t^2 / 2 at t = 0.
  const double dt = 1e-6;
  auto speed = [&](double t) {
    const double ph = x + w * t + 0.5 * al * t * t;
    return km::point_motion(lc.pose(ph).h, w + al * t, al).speed_mps;
  };
  EXPECT_NEAR(m.tangential_acceleration_mps2, (speed(dt) - speed(-dt)) / (2.0 * dt), 1e-6);
}

TEST(PathStraightness, MeasuresAKnownBump) {
  // y = 0.02 sin(pi x) on x in [0, 1], flat y = 0 on [-1, 0]: a 1.0 window fits
  // on the flat part (deviation 0); every 1.5 window inside [-1, 1] contains the
  // bump's peak 0.02 at x = 0.5.
  std::vector<Eigen::Vector2d> path;
  for (int k = -1000; k <= 1000; ++k) {
    const double x = k * 1e-3;
    path.emplace_back(x, x > 0.0 ? 0.02 * std::sin(std::numbers::pi * x) : 0.0);
  }
  EXPECT_NEAR(km::horizontal_extent(path), 2.0, 1e-12);
  const auto flat = km::horizontal_straightness(path, 1.0, 0.0);
  ASSERT_TRUE(flat.window_found);
  EXPECT_NEAR(flat.max_deviation_m, 0.0, 1e-15);
  const auto bump = km::horizontal_straightness(path, 1.5, 0.0);
  ASSERT_TRUE(bump.window_found);
  EXPECT_NEAR(bump.max_deviation_m, 0.02, 1e-9);
  EXPECT_NEAR(bump.max_above_m, 0.02, 1e-9);
  EXPECT_NEAR(bump.max_below_m, 0.0, 1e-15);
  EXPECT_FALSE(km::horizontal_straightness(path, 3.0, 0.0).window_found);
  EXPECT_THROW(km::horizontal_straightness(path, 0.0, 0.0), kinetofem::Error);
  EXPECT_THROW(km::horizontal_extent({}), kinetofem::Error);
}

TEST(LeverChain, SampledPathIsContinuous) {
  const km::LeverChain lc(example());
  const auto range = km::lever_chain_published_range();
  const auto path = km::sample_lever_chain_path(lc, range.lo_rad, range.hi_rad, 1631);
  ASSERT_EQ(path.c_m.size(), 1631u);
  // Step 0.1 deg; |C'| <= a + c (|theta'| <= ~2 here): jumps stay below 0.1 deg * 2 m.
  for (std::size_t k = 1; k < path.c_m.size(); ++k)
    EXPECT_LT((path.c_m[k] - path.c_m[k - 1]).norm(), 0.1 * kDeg * 2.0);
  EXPECT_THROW(km::sample_lever_chain_path(lc, 0.1, 0.0, 10), kinetofem::Error);
}
