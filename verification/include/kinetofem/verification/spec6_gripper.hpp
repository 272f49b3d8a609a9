#pragma once
// SPEC §6 (seeds/004, Pogrebnyak & Pogrebnyak 2019): the crank-slider
// gripper's operating ranges by the energy transmission index
// (|U_V - 1| <= 0.05), without and with the pressure-angle limits, and the
// design example, as published.
#include <vector>

#include "kinetofem/mechanisms/crank_slider_gripper.hpp"
#include "kinetofem/verification/published_value.hpp"

namespace kinetofem::verification::spec6 {

// Range ends are published to the degree (read from a plot): 1 deg.
inline constexpr double kRangeTolerance_deg = 1.0;
inline constexpr const char* kRangeWhy = "published to the degree: 1 deg";

struct PublishedRanges {
  double sigma = 0.0, gamma = 0.0;
  const char* source = "";
  double from_deg = 0.0, to_deg = 0.0;                  // |U_V - 1| <= 0.05
  double limited_from_deg = 0.0, limited_to_deg = 0.0;  // with the pressure-angle limits
};
// r = e (gamma = e/l = r/l = sigma): 142 .. 170 deg; 142 .. 154 deg with
// theta12 <= 30 deg.
inline constexpr PublishedRanges kREqualsE{0.905, 0.905, "SPEC §6, r = e, sigma = 0.905", 142, 170, 142, 154};
// The best design: 139 .. 165 deg; 139 .. 163 deg with the pressure limits.
inline constexpr PublishedRanges kBestDesign{1.1, 0.82, "SPEC §6, sigma = 1.1, gamma = 0.82", 139, 165, 139, 163};

// The computed ranges of a published design (default GripperRangeOptions).
struct ComputedRanges {
  std::vector<mech::PhiInterval> free, limited;  // without / with the pressure-angle limits
};
ComputedRanges operating_ranges(const PublishedRanges& design);

// Design example: e = H/2 = 50 mm with sigma = 1.1, gamma = 0.82 gives
// l = e/gamma = 60.98 mm and r = sigma l = 67.07, printed 67 mm; printed
// ratios l = 0.91 r, e = 0.745 r; jaw travel h = 2 r |sin 163 - sin 139|
// printed 0.728 r from 3-digit sines (2 (0.656 - 0.292)), each +-0.0005.
inline constexpr double kExampleOffset_m = 0.050;
inline constexpr PublishedValue kRodLength{60.98, 0.005, "mm", "SPEC §6, l = 60.98 mm",
                                           "half a unit of the printed digit"};
inline constexpr PublishedValue kCrankRadius{67.0, 0.5, "mm", "SPEC §6, r = 67 mm", "printed to the mm: half a unit"};
inline constexpr PublishedValue kRodOverCrank{0.91, 0.005, "1", "SPEC §6, l = 0.91 r", kHalfLastDigit};
inline constexpr PublishedValue kOffsetOverCrank{0.745, 0.0005, "1", "SPEC §6, e = 0.745 r", kHalfLastDigit};
inline constexpr double kTravelFrom_deg = 139.0, kTravelTo_deg = 163.0;
inline constexpr PublishedValue kJawTravel{0.728, 0.002, "1", "SPEC §6, h = 0.728 r",
                                           "source used 3-digit sines: +-0.002"};

}  // namespace kinetofem::verification::spec6
