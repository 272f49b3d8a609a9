#pragma once
// Mean stress treatment of counted cycles, EN 1993-1-9:2005 7.2.1(1).
//
// Units: Pa.
//
// EN 1993-1-9 uses stress ranges without a mean stress correction. The one
// allowance, 7.2.1(1): for non-welded details, or welded details that are
// stress-relieved (post-weld heat treated), the compressive part of the
// stress range may be reduced to 60 % (effective range
// Delta sigma_E,2 = |sigma_max,tension| + 0.6 |sigma_min,compression|).
// For as-welded details no reduction is allowed: use MeanStressTreatment::None.
//
// For a cycle (range, mean): sigma_max = mean + range/2, sigma_min = mean - range/2,
//   tensile part     = max(sigma_max, 0) - max(sigma_min, 0)
//   compressive part = min(sigma_max, 0) - min(sigma_min, 0)
//   effective range  = tensile part + 0.6 * compressive part.
// A fully tensile cycle keeps its range, a fully compressive one is reduced
// to 0.6 of it, a cycle through zero becomes sigma_max + 0.6 |sigma_min|.
// No other mean stress correction (Goodman, Gerber, Smith-Watson-Topper) is
// part of EN 1993-1-9 and none is offered.
#include <span>
#include <vector>

#include "kinetofem/fatigue/rainflow.hpp"

namespace kinetofem::fatigue {

enum class MeanStressTreatment {
  None,                // as-welded details: the full range (EN 1993-1-9 default)
  ReducedCompression,  // non-welded or stress-relieved welded details, 7.2.1(1)
};

inline constexpr double kCompressionFactor = 0.6;  // EN 1993-1-9 7.2.1(1)

// Effective range of one cycle, Pa. Error if its range is negative or not finite.
double effective_range(const Cycle& cycle, MeanStressTreatment treatment);

// The cycles with their ranges replaced by the effective ranges (means and
// counts kept).
std::vector<Cycle> apply_mean_stress(std::span<const Cycle> cycles, MeanStressTreatment treatment);

}  // namespace kinetofem::fatigue
