#include "kinetofem/fatigue/mean_stress.hpp"

#include <algorithm>
#include <cmath>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fatigue {

double effective_range(const Cycle& cycle, MeanStressTreatment treatment) {
  require(std::isfinite(cycle.range_pa) && cycle.range_pa >= 0.0,
          "fatigue: stress range {} Pa must be finite and >= 0", cycle.range_pa);
  require(std::isfinite(cycle.mean_pa), "fatigue: mean stress {} Pa is not finite", cycle.mean_pa);
  if (treatment == MeanStressTreatment::None) return cycle.range_pa;
  const double max_pa = cycle.mean_pa + 0.5 * cycle.range_pa;
  const double min_pa = cycle.mean_pa - 0.5 * cycle.range_pa;
  const double tensile = std::max(max_pa, 0.0) - std::max(min_pa, 0.0);
  const double compressive = std::min(max_pa, 0.0) - std::min(min_pa, 0.0);
  return tensile + kCompressionFactor * compressive;
}

std::vector<Cycle> apply_mean_stress(std::span<const Cycle> cycles, MeanStressTreatment treatment) {
  std::vector<Cycle> out(cycles.begin(), cycles.end());
  for (Cycle& c : out) c.range_pa = effective_range(c, treatment);
  return out;
}

}  // namespace kinetofem::fatigue
