// SPEC §1 (seeds/001, Slavkov, Savchev, Galabov): the lever-chain manipulator's
// published example a = 500, c = 350, h = 100, r = 75 mm. The published
// numbers, their tolerances and the path study are those of `kinetofem
// verify` (kinetofem/verification/spec1_lever_chain.hpp).
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"

namespace km = kinetofem::mech;
namespace s1 = kinetofem::verification::spec1;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kMm = 1e-3;
}  // namespace

TEST(Spec1LeverChain, DesignGeometryMatchesPrintedDigits) {
  const auto g = s1::example_geometry();
  fmt::print("SPEC1 b0 = {:.4f} mm, l0 = {:.4f} mm, alpha0 = {:.4f} deg\n", g.b0_m / kMm,
             g.l0_m / kMm, g.alpha0_rad / kDeg);
  // Printed to 3 decimals: b0 = 411.765 mm, l0 = 115.804 mm, alpha0 = 49.635 deg;
  // tolerance = half a unit of the last printed digit.
  EXPECT_NEAR(g.b0_m / kMm, s1::kB0.value, s1::kB0.tolerance);
  EXPECT_NEAR(g.l0_m / kMm, s1::kL0.value, s1::kL0.tolerance);
  EXPECT_NEAR(g.alpha0_rad / kDeg, s1::kAlpha0.value, s1::kAlpha0.tolerance);
}

TEST(Spec1LeverChain, FirstTransferFunctionMatchesPublishedValues) {
  const km::LeverChain lc(s1::example_geometry());
  const double at0 = lc.ctm(0.0).dpsi_d1;
  const double at20 = lc.ctm(s1::kTransferSecondAngle_deg * kDeg).dpsi_d1;
  fmt::print("SPEC1 dpsi'(0) = {:.6f}, dpsi'(20 deg) = {:.6f}\n", at0, at20);
  // SPEC §1: -1.0000 at 0 and -1.38380 at 20 deg; half a unit of the last digit.
  EXPECT_NEAR(at0, s1::kTransferAt0.value, s1::kTransferAt0.tolerance);
  EXPECT_NEAR(at20, s1::kTransferAt20.value, s1::kTransferAt20.tolerance);
  // SPEC §1: |(9)| = |1 - (a/r) cos(beta)| has the same magnitude (the source's
  // (9) is written for the inverted input -dphi).
  for (double deg : {0.0, 20.0, -30.0, 60.0}) {
    const auto s = lc.ctm(deg * kDeg);
    EXPECT_NEAR(std::abs(s.dpsi_d1), std::abs(1.0 - 0.5 / 0.075 * std::cos(s.beta_rad)), 1e-12)
        << deg;
  }
}

TEST(Spec1LeverChain, TrajectoryExtentsAndStraightness) {
  // 0.01 deg steps over the published range; narrowest 800 mm horizontal
  // band, deviations from the design tangent (y = a for C, a + h for H).
  const s1::PathStudy study = s1::path_study();
  const auto& range = study.range;
  const double ext_c = study.extent_c_mm, ext_h = study.extent_h_mm;
  const auto& sc = study.c;
  const auto& sh = study.h;
  ASSERT_TRUE(sc.window_found);
  ASSERT_TRUE(sh.window_found);
  fmt::print("SPEC1 range [{:.1f}, {:.1f}] deg: extent C = {:.1f} mm, H = {:.1f} mm\n",
             range.lo_rad / kDeg, range.hi_rad / kDeg, ext_c, ext_h);
  fmt::print("SPEC1 800 mm window C: x in [{:.1f}, {:.1f}] mm, max dev {:.2f} mm (above {:.2f}, "
             "below {:.2f}), band {:.2f} mm\n",
             sc.x_min_m / kMm, sc.x_max_m / kMm, sc.max_deviation_m / kMm, sc.max_above_m / kMm,
             sc.max_below_m / kMm, sc.band_height_m / kMm);
  fmt::print("SPEC1 800 mm window H: x in [{:.1f}, {:.1f}] mm, max dev {:.2f} mm (above {:.2f}, "
             "below {:.2f}), band {:.2f} mm\n",
             sh.x_min_m / kMm, sh.x_max_m / kMm, sh.max_deviation_m / kMm, sh.max_above_m / kMm,
             sh.max_below_m / kMm, sh.band_height_m / kMm);
  // SPEC §1: "about 1230 mm and 1270 mm": printed to tens of mm, so +-5 mm.
  // These two numbers fixed the lever range (one unknown, the lower limit, see
  // lever_chain.hpp); the check is that one range reproduces both at once.
  EXPECT_NEAR(ext_c, s1::kExtentC.value, s1::kExtentC.tolerance);
  EXPECT_NEAR(ext_h, s1::kExtentH.value, s1::kExtentH.tolerance);
  // SPEC §1: deviations "about 45 mm (C) and 20 mm (H)" from a horizontal line
  // "in the positive Y direction", printed as round numbers (multiples of 5 mm):
  // +-2.5 mm on the deviation above the design tangent in the narrowest 800 mm
  // band, and what lies below the tangent must stay under that rounding too.
  EXPECT_NEAR(sc.max_above_m / kMm, s1::kDeviationC.value, s1::kDeviationC.tolerance);
  EXPECT_NEAR(sh.max_above_m / kMm, s1::kDeviationH.value, s1::kDeviationH.tolerance);
  EXPECT_LT(sc.max_below_m / kMm, s1::kDeviationBelow.tolerance);
  EXPECT_LT(sh.max_below_m / kMm, s1::kDeviationBelow.tolerance);
}
