// SPEC §2: the hinged four-bar equivalent to the lever-chain manipulator (the
// "lever manipulator"), with the §1 example dimensions.
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/four_bar.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"
#include "kinetofem/verification/spec2_four_bar.hpp"

namespace km = kinetofem::mech;
namespace kv = kinetofem::verification;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
km::LeverChainGeometry example() { return kv::spec1::example_geometry(); }
}  // namespace

TEST(Spec2FourBar, EquivalentToLeverChainUpToSecondOrderAtDesign) {
  const km::LeverChain lc(example());
  const km::FourBar fb = km::make_equivalent_four_bar(example());
  const km::LeverChainPose p = lc.pose(0.0);
  const km::FourBarPose q = fb.pose_at_rotation(0.0);
  fmt::print("SPEC2 design: theta' chain {:.3e} / four-bar {:.3e}; theta'' chain {:.9f} / "
             "four-bar {:.9f}\n", p.theta_d1, q.coupler_d1, p.theta_d2, q.coupler_d2);
  // SPEC §2: equivalent up to second derivatives; both are closed forms, so the
  // tolerance is round-off (1e-12 relative to the O(1) values).
  EXPECT_NEAR(q.coupler_angle_rad, p.theta_rad, 1e-12);
  EXPECT_NEAR(q.coupler_d1, p.theta_d1, 1e-12);
  EXPECT_NEAR(q.coupler_d2, p.theta_d2, 1e-12);
  const km::PointKinematics* chain_pts[2] = {&p.c, &p.h};
  for (int k = 0; k < 2; ++k) {
    const auto& a = *chain_pts[k];
    const auto& b = q.coupler_points[static_cast<std::size_t>(k)];
    EXPECT_LT((a.p - b.p).norm(), 1e-12) << k;
    EXPECT_LT((a.d1 - b.d1).norm(), 1e-12) << k;
    EXPECT_LT((a.d2 - b.d2).norm(), 1e-12) << k;
  }
  // Third order is not matched: compare theta''' by central differences of the
  // analytic second derivatives (error ~1e-8 for h = 1e-4).
  const double h = 1e-4;
  const double t3_chain = (lc.pose(h).theta_d2 - lc.pose(-h).theta_d2) / (2 * h);
  const double t3_fb = (fb.pose_at_rotation(h).coupler_d2 - fb.pose_at_rotation(-h).coupler_d2) /
                       (2 * h);
  fmt::print("SPEC2 design: theta''' chain {:.6f} / four-bar {:.6f}\n", t3_chain, t3_fb);
  EXPECT_GT(std::abs(t3_chain - t3_fb), 1e-3);
  // Away from the design position the two mechanisms separate.
  EXPECT_GT(std::abs(lc.pose(20 * kDeg).theta_rad - fb.pose_at_rotation(20 * kDeg).coupler_angle_rad),
            1e-4);
}

TEST(Spec2FourBar, ExampleIsNonGrashofWithAssemblyLimits) {
  const auto g = example();
  const km::FourBar fb = km::make_equivalent_four_bar(g);
  // SPEC §2: 500 + 75 > 411.8 + 115.8: non-Grashof, no link turns fully.
  EXPECT_NEAR(fb.crank_length_m(), 0.5, 1e-15);
  EXPECT_NEAR(fb.coupler_length_m(), 0.075, 1e-15);
  EXPECT_NEAR(fb.rocker_length_m(), g.b0_m, 1e-15);
  EXPECT_NEAR(fb.ground_length_m(), g.l0_m, 1e-15);
  EXPECT_EQ(fb.grashof(), km::GrashofClass::triple_rocker);
  const km::AssemblyRange r = fb.assembly_range();
  ASSERT_FALSE(r.full_rotation);
  const double lo = (r.lo_rad - fb.design_input_rad()) / kDeg;
  const double hi = (r.hi_rad - fb.design_input_rad()) / kDeg;
  fmt::print("SPEC2 four-bar assembles for lever rotation dphi in [{:.4f}, {:.4f}] deg\n", lo, hi);
  // At each limit |A B0| reaches l2 + l3 or |l2 - l3| (bisection to 1e-12 rad):
  // the margin vanishes and coupler and rocker are collinear.
  for (double lim : {r.lo_rad, r.hi_rad}) {
    EXPECT_NEAR(fb.assembly_margin_m(lim), 0.0, 1e-11);
    const double mu = fb.pose(lim).transmission_angle_rad;
    EXPECT_LT(std::min(mu, std::numbers::pi - mu), 1e-4);
  }
  // Closed-form check of the limits: |A(phi) B0|^2 = a^2 + l0^2 - 2 a l0 cos(phi - alpha0)
  // (kinetofem/verification/spec2_four_bar.hpp).
  for (double lim : {r.lo_rad, r.hi_rad}) {
    const double dist = kv::spec2::crank_pin_to_b0_m(g, lim);
    const double to_bound = std::min(std::abs(dist - (g.r_m + g.b0_m)),
                                     std::abs(dist - std::abs(g.r_m - g.b0_m)));
    EXPECT_LT(to_bound, 1e-11);
  }
}

TEST(Spec2FourBar, SideBySideStudy) {
  const auto range = km::lever_chain_published_range();
  const km::LeverVsFourBarStudy s =
      km::compare_lever_chain_with_four_bar(example(), range.lo_rad, range.hi_rad, 1631, 0.3);
  fmt::print("SPEC2 study: four-bar range dphi [{:.2f}, {:.2f}] deg; H extent chain {:.1f} mm, "
             "four-bar {:.1f} mm\n",
             s.four_bar_range_dphi.lo_rad / kDeg, s.four_bar_range_dphi.hi_rad / kDeg,
             s.h_extent_lever_chain_m * 1e3, s.h_extent_four_bar_m * 1e3);
  fmt::print("SPEC2 study: 300 mm window deviation of H: chain {:.3f} mm, four-bar {:.3f} mm; "
             "four-bar transmission angle in [{:.1f}, {:.1f}] deg\n",
             s.h_lever_chain.max_deviation_m * 1e3, s.h_four_bar.max_deviation_m * 1e3,
             s.min_transmission_angle_four_bar_rad / kDeg,
             s.max_transmission_angle_four_bar_rad / kDeg);
  // SPEC §1/§2: the chain's transmission angle is 90 deg throughout (round-off).
  for (const auto& sample : s.samples)
    EXPECT_NEAR(sample.transmission_angle_lever_chain_rad, 0.5 * std::numbers::pi, 1e-12);
  // SPEC §2: the four-bar's transmission angle varies and its range is limited.
  EXPECT_GT(s.max_transmission_angle_four_bar_rad - s.min_transmission_angle_four_bar_rad,
            10 * kDeg);
  EXPECT_LT(s.h_extent_four_bar_m, s.h_extent_lever_chain_m);
  ASSERT_TRUE(s.h_lever_chain.window_found);
}
