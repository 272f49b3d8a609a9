// SPEC §6 (seeds/004, Pogrebnyak & Pogrebnyak 2019): crank-slider gripper
// operating ranges by the energy transmission index. The published ranges,
// dimensions and tolerances are those of `kinetofem verify`
// (kinetofem/verification/spec6_gripper.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/crank_slider_gripper.hpp"
#include "kinetofem/verification/spec6_gripper.hpp"

namespace km = kinetofem::mech;
namespace s6 = kinetofem::verification::spec6;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;

void print_ranges(const char* label, const std::vector<km::PhiInterval>& rs) {
  fmt::print("SPEC6 {}:", label);
  for (const auto& r : rs) fmt::print(" [{:.2f}, {:.2f}]", r.lo_rad / kDeg, r.hi_rad / kDeg);
  fmt::print("\n");
}
}  // namespace

TEST(Spec6Gripper, CentralMechanismIsUnusable) {
  // SPEC §6: the central mechanism keeps |U_V| in 1 +- 0.05 only over "about 2
  // deg" (source: "does not exceed 2 deg", for the sigma values of its fig. 2c).
  // Checked: over sigma in [0.1, 0.95] the widest interval in either quadrant
  // stays a few degrees (< 3.1 deg, against 24-28 deg for the offset designs).
  // The printed "2 deg" is only approached for the larger sigma (second quadrant,
  // sigma >= 0.5: printed below); as sigma -> 0 the width tends to
  // atan(1.05) - atan(0.95) = 2.866 deg (U_V -> -tan(phi)), checked as a limit.
  km::GripperRangeOptions all;
  all.phi_lo_rad = 0.5 * kDeg;
  all.phi_hi_rad = 179.5 * kDeg;
  double widest_all = 0, widest_q2_large_sigma = 0;
  for (double sigma = 0.1; sigma <= 0.951; sigma += 0.05) {
    widest_all = std::max(widest_all,
                          km::widest(km::gripper_operating_ranges_central(sigma, all)).width_rad());
    if (sigma >= 0.5 - 1e-9)
      widest_q2_large_sigma = std::max(
          widest_q2_large_sigma, km::widest(km::gripper_operating_ranges_central(sigma)).width_rad());
  }
  const double small_sigma =
      km::widest(km::gripper_operating_ranges_central(1e-4)).width_rad() / kDeg;
  fmt::print("SPEC6 central: widest range {:.2f} deg (0..180, sigma 0.1..0.95), {:.2f} deg "
             "(90..180, sigma 0.5..0.95), {:.3f} deg (sigma = 1e-4)\n",
             widest_all / kDeg, widest_q2_large_sigma / kDeg, small_sigma);
  EXPECT_LT(widest_all / kDeg, 3.1);
  // Limit sigma -> 0: error O(sigma) = 1e-4 rad-scale, far below 0.01 deg.
  EXPECT_NEAR(small_sigma, (std::atan(1.05) - std::atan(0.95)) / kDeg, 0.01);
}

TEST(Spec6Gripper, REqualsESigma0905) {
  // r = e means gamma = e/l = r/l = sigma, so (6) becomes (7) with sigma = gamma
  // = 0.905. SPEC §6: 142 < phi < 170 deg; 142..154 deg with theta12 <= 30 deg
  // (theta23 <= 45 deg holds throughout). Tolerance 1 deg (published to the
  // degree, read from a plot).
  const s6::PublishedRanges& p = s6::kREqualsE;
  const double tol = s6::kRangeTolerance_deg;
  const s6::ComputedRanges ranges = s6::operating_ranges(p);
  const auto& free = ranges.free;
  const auto& limited = ranges.limited;
  print_ranges("sigma = gamma = 0.905", free);
  print_ranges("sigma = gamma = 0.905, pressure limits", limited);
  ASSERT_EQ(free.size(), 1u);
  EXPECT_NEAR(free[0].lo_rad / kDeg, p.from_deg, tol);
  EXPECT_NEAR(free[0].hi_rad / kDeg, p.to_deg, tol);
  ASSERT_EQ(limited.size(), 1u);
  EXPECT_NEAR(limited[0].lo_rad / kDeg, p.limited_from_deg, tol);
  EXPECT_NEAR(limited[0].hi_rad / kDeg, p.limited_to_deg, tol);
  // The upper limit is set by theta12 (source: "the upper bound by the allowed
  // pressure angle"): |theta12| = 30 deg there (bisection tolerance 1e-10 rad).
  EXPECT_NEAR(km::gripper_pressure_angle_slider_rad(limited[0].hi_rad, p.sigma, p.gamma) / kDeg, 30.0, 1e-6);
}

TEST(Spec6Gripper, BestDesignSigma11Gamma082) {
  // SPEC §6: sigma = 1.1, gamma = 0.82: 139..165 deg, 139..163 deg with the
  // pressure limits. With the printed (2-digit) gamma, U_V dips to 0.9493 near
  // 152.7 deg, so the strict criterion gives two intervals whose hull is the
  // published range; tolerance 1 deg on the hull ends.
  const s6::PublishedRanges& p = s6::kBestDesign;
  const double tol = s6::kRangeTolerance_deg;
  const s6::ComputedRanges ranges = s6::operating_ranges(p);
  print_ranges("sigma = 1.1, gamma = 0.82", ranges.free);
  print_ranges("sigma = 1.1, gamma = 0.82, pressure limits", ranges.limited);
  const km::PhiInterval hull = km::operating_hull(ranges.free);
  const km::PhiInterval hull_lim = km::operating_hull(ranges.limited);
  EXPECT_NEAR(hull.lo_rad / kDeg, p.from_deg, tol);
  EXPECT_NEAR(hull.hi_rad / kDeg, p.to_deg, tol);
  EXPECT_NEAR(hull_lim.lo_rad / kDeg, p.limited_from_deg, tol);
  EXPECT_NEAR(hull_lim.hi_rad / kDeg, p.limited_to_deg, tol);
  // The dip: the gap is real but shallow (0.95 - min U_V < 1e-3).
  double u_min = 10.0;
  for (double deg = 145.0; deg <= 160.0; deg += 0.01)
    u_min = std::min(u_min, km::gripper_index_offset(deg * kDeg, p.sigma, p.gamma));
  fmt::print("SPEC6 sigma = 1.1, gamma = 0.82: min U_V on 145..160 deg = {:.5f}\n", u_min);
  EXPECT_LT(0.95 - u_min, 1e-3);
  // Within gamma's rounding interval [0.815, 0.825) a single interval exists:
  // gamma = 0.821 keeps U_V >= 0.95 and reproduces the published range.
  const auto single = km::gripper_operating_ranges(p.sigma, 0.821, km::GripperRangeOptions{});
  print_ranges("sigma = 1.1, gamma = 0.821", single);
  ASSERT_EQ(single.size(), 1u);
  EXPECT_NEAR(single[0].lo_rad / kDeg, p.from_deg, tol);
  EXPECT_NEAR(single[0].hi_rad / kDeg, p.to_deg, tol);
}

TEST(Spec6Gripper, DesignExampleDimensions) {
  // SPEC §6: e = H/2 = 50 mm -> l = e/gamma = 60.98 mm, r = sigma l = 67.07 ->
  // printed r = 67 mm (rounded; l = 0.91 r with r = 67 would give 60.97 mm).
  // Tolerances: half a unit of the printed digit (0.005 mm for l, 0.5 mm for r).
  const auto d = km::gripper_dimensions_from_offset(s6::kExampleOffset_m, s6::kBestDesign.sigma, s6::kBestDesign.gamma);
  fmt::print("SPEC6 design: r = {:.3f} mm, l = {:.3f} mm, e = {:.3f} mm\n", d.r_m * 1e3,
             d.l_m * 1e3, d.e_m * 1e3);
  EXPECT_NEAR(d.l_m * 1e3, s6::kRodLength.value, s6::kRodLength.tolerance);
  EXPECT_NEAR(d.r_m * 1e3, s6::kCrankRadius.value, s6::kCrankRadius.tolerance);
  // SPEC §6: l = 0.91 r, e = 0.745 r (printed to 2-3 digits).
  EXPECT_NEAR(d.l_m / d.r_m, s6::kRodOverCrank.value, s6::kRodOverCrank.tolerance);
  EXPECT_NEAR(d.e_m / d.r_m, s6::kOffsetOverCrank.value, s6::kOffsetOverCrank.tolerance);
  // Jaw travel h = 2 r |sin 163 - sin 139|: printed 0.728 r, exact 0.72737 r. The
  // source used 3-digit sines (2 (0.656 - 0.292) = 0.728), each +-0.0005, so the
  // printed value carries +-0.002.
  const double travel = km::gripper_jaw_travel_m(1.0, s6::kTravelFrom_deg * kDeg, s6::kTravelTo_deg * kDeg);
  fmt::print("SPEC6 jaw travel = {:.5f} r\n", travel);
  EXPECT_NEAR(travel, s6::kJawTravel.value, s6::kJawTravel.tolerance);
  EXPECT_NEAR(2 * (std::round(std::sin(s6::kTravelFrom_deg * kDeg) * 1e3) -
                   std::round(std::sin(s6::kTravelTo_deg * kDeg) * 1e3)) / 1e3,
              s6::kJawTravel.value, 1e-12);
}

TEST(Spec6Gripper, RefinedDesignSearchReachesThePublishedWidth) {
  // Search over the source's region (e <= r) with both pressure limits. The
  // published best single range with limits is 139..163 deg (24 deg, reading
  // the shallow dip as inside). The refined search must find a single interval
  // at least that wide minus 1 deg.
  km::GripperDesignSearch s;
  s.sigma_lo = 0.8;
  s.sigma_hi = 1.5;
  s.gamma_lo = 0.6;
  s.gamma_hi = 1.0;
  s.n_sigma = 15;
  s.n_gamma = 21;
  s.refinements = 3;
  s.range.pressure_limits = true;
  s.range.step_rad = 0.1 * kDeg;
  const km::GripperDesign best = km::search_widest_gripper_design(s);
  fmt::print("SPEC6 search: sigma = {:.4f}, gamma = {:.4f}, range [{:.2f}, {:.2f}] deg "
             "({:.2f} deg, {} evaluations)\n",
             best.sigma, best.gamma, best.range.lo_rad / kDeg, best.range.hi_rad / kDeg,
             best.range.width_rad() / kDeg, best.evaluations);
  EXPECT_GE(best.range.width_rad() / kDeg, 24.0 - 1.0);
  EXPECT_LE(best.gamma, best.sigma);
}
