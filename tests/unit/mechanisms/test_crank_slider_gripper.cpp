// Unit tests of the crank-slider gripper energy index and its range search (SPEC §6).
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/crank_slider_gripper.hpp"

namespace km = kinetofem::mech;

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

TEST(CrankSliderGripper, CentralIsOffsetWithZeroOffset) {
  for (double sigma : {0.3, 0.7, 0.95}) {
    for (double deg = 5.0; deg < 180.0; deg += 7.0) {
      if (std::abs(deg - 90.0) <= 1.0) continue;  // tan singularity
      EXPECT_NEAR(km::gripper_index_central(deg * kDeg, sigma),
                  km::gripper_index_offset(deg * kDeg, sigma, 0.0), 1e-12)
          << sigma << " " << deg;
    }
  }
}

TEST(CrankSliderGripper, PressureAngleFormulas) {
  const double s = 0.905, phi = 150 * kDeg;
  // (8) is (9) with gamma = sigma (r = e).
  EXPECT_NEAR(km::gripper_pressure_angle_slider_rad(phi, s, s),
              std::asin(s * (1 - std::sin(phi))), 1e-15);
  EXPECT_NEAR(km::gripper_pressure_angle_rod_rocker_rad(phi, s, s),
              phi - std::asin(s * (1 - std::sin(phi))) - 0.5 * std::numbers::pi, 1e-15);
  EXPECT_THROW(km::gripper_pressure_angle_slider_rad(phi, 3.0, -2.0), kinetofem::Error);
}

TEST(CrankSliderGripper, RejectsUnassembledAndSingularPositions) {
  EXPECT_FALSE(km::gripper_assembles(-90 * kDeg, 2.0, 0.0));  // sigma |sin - gamma| = 2
  EXPECT_THROW(km::gripper_index_offset(-90 * kDeg, 2.0, 0.0), kinetofem::Error);
  EXPECT_THROW(km::gripper_index_central(90 * kDeg, 1.5), kinetofem::Error);
  EXPECT_THROW(km::gripper_index_offset(0.5 * std::numbers::pi, 0.5, 0.1), kinetofem::Error);
  EXPECT_THROW(km::gripper_index_offset(1.0, -0.5, 0.1), kinetofem::Error);
}

TEST(CrankSliderGripper, RangeBoundariesSitOnTheTolerance) {
  km::GripperRangeOptions o;
  const auto ranges = km::gripper_operating_ranges(0.905, 0.905, o);
  ASSERT_FALSE(ranges.empty());
  for (const auto& r : ranges) {
    EXPECT_GT(r.width_rad(), 0.0);
    // Each end lies where |U_V| = 1 +- tol, or on a window end: bisection to
    // 1e-10 rad with |dU/dphi| < 10 gives |U| within 1e-8 of the bound.
    for (double phi : {r.lo_rad, r.hi_rad}) {
      if (phi <= o.phi_lo_rad + 1e-12 || phi >= o.phi_hi_rad - 1e-12) continue;
      EXPECT_NEAR(std::abs(std::abs(km::gripper_index_offset(phi, 0.905, 0.905)) - 1.0), 0.05,
                  1e-8);
    }
  }
  // Pressure limits can only shrink the set.
  o.pressure_limits = true;
  const auto limited = km::gripper_operating_ranges(0.905, 0.905, o);
  double w0 = 0, w1 = 0;
  for (const auto& r : ranges) w0 += r.width_rad();
  for (const auto& r : limited) w1 += r.width_rad();
  EXPECT_LE(w1, w0);
}

TEST(CrankSliderGripper, HullAndWidest) {
  const std::vector<km::PhiInterval> rs{{1.0, 1.2}, {1.5, 1.9}, {2.0, 2.1}};
  EXPECT_DOUBLE_EQ(km::widest(rs).lo_rad, 1.5);
  EXPECT_DOUBLE_EQ(km::operating_hull(rs).lo_rad, 1.0);
  EXPECT_DOUBLE_EQ(km::operating_hull(rs).hi_rad, 2.1);
  EXPECT_DOUBLE_EQ(km::widest({}).width_rad(), 0.0);
}

TEST(CrankSliderGripper, DimensionsAndJawTravel) {
  const auto d = km::gripper_dimensions_from_offset(0.05, 1.1, 0.82);
  EXPECT_NEAR(d.l_m, 0.05 / 0.82, 1e-15);
  EXPECT_NEAR(d.r_m, 1.1 * 0.05 / 0.82, 1e-15);
  EXPECT_NEAR(km::gripper_jaw_travel_m(1.0, 139 * kDeg, 163 * kDeg),
              2 * std::abs(std::sin(163 * kDeg) - std::sin(139 * kDeg)), 1e-15);
  EXPECT_THROW(km::gripper_dimensions_from_offset(0.05, 1.1, 0.0), kinetofem::Error);
  EXPECT_THROW(km::gripper_jaw_travel_m(-1.0, 0, 1), kinetofem::Error);
}

TEST(CrankSliderGripper, DesignSearchRespectsRegionAndImprovesOnGrid) {
  km::GripperDesignSearch s;
  s.sigma_lo = 0.8;
  s.sigma_hi = 1.3;
  s.gamma_lo = 0.6;
  s.gamma_hi = 1.0;
  s.n_sigma = 6;
  s.n_gamma = 5;
  s.refinements = 0;
  s.range.step_rad = 0.2 * kDeg;
  const km::GripperDesign coarse = km::search_widest_gripper_design(s);
  s.refinements = 2;
  const km::GripperDesign fine = km::search_widest_gripper_design(s);
  EXPECT_GE(fine.range.width_rad(), coarse.range.width_rad());
  EXPECT_LE(fine.gamma, fine.sigma);  // e <= r
  EXPECT_GE(fine.sigma, s.sigma_lo);
  EXPECT_LE(fine.sigma, s.sigma_hi);
}

TEST(CrankSliderGripper, ObjectRangeAndClampAngle) {
  // SPEC §6: open 2e = 100 mm at 163 deg, r = 67 mm, range 139..163 deg:
  // thickness_min = 100 - 2 r (sin 139 - sin 163) (the source's 0.728 r).
  const double r = 0.067, open = 0.100, lo = 139 * kDeg, hi = 163 * kDeg;
  const km::GripperObjectRange range = km::gripper_object_range(open, r, lo, hi);
  EXPECT_DOUBLE_EQ(range.thickness_max_m, open);
  EXPECT_NEAR(range.thickness_min_m, open - 2 * r * (std::sin(lo) - std::sin(hi)), 1e-15);
  // The ends of the range are the ends of the operating range; inside, the
  // jaw gap at the clamp angle is the object's thickness.
  EXPECT_NEAR(km::gripper_clamp_angle_rad(open, open, r, lo, hi), hi, 1e-12);
  EXPECT_NEAR(km::gripper_clamp_angle_rad(range.thickness_min_m, open, r, lo, hi), lo, 1e-7);
  const double phi = km::gripper_clamp_angle_rad(0.070, open, r, lo, hi);
  EXPECT_GT(phi, lo);
  EXPECT_LT(phi, hi);
  EXPECT_NEAR(open - 2 * r * (std::sin(phi) - std::sin(hi)), 0.070, 1e-15);
  // Outside: an error naming the thickness and the range.
  try {
    km::gripper_clamp_angle_rad(0.120, open, r, lo, hi);
    ADD_FAILURE() << "no error for 120 mm";
  } catch (const kinetofem::Error& e) {
    EXPECT_NE(std::string(e.what()).find("120 mm thick is outside the jaws' range 51.27..100.00 mm"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(km::gripper_object_range(open, r, hi, lo), kinetofem::Error);
}
