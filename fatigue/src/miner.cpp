#include "kinetofem/fatigue/miner.hpp"

#include <cmath>
#include <limits>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fatigue {

double miner_damage(std::span<const Cycle> cycles, const SnCurve& curve,
                    MeanStressTreatment mean_stress) {
  double damage = 0.0;
  for (const Cycle& c : cycles) {
    require(std::isfinite(c.count) && c.count >= 0.0,
            "fatigue: cycle count {} must be finite and >= 0", c.count);
    const double n = curve.endurance(effective_range(c, mean_stress));
    if (std::isfinite(n)) damage += c.count / n;
  }
  return damage;
}

double life_repetitions(double damage) {
  require(std::isfinite(damage) && damage >= 0.0,
          "fatigue: damage {} must be finite and >= 0", damage);
  return damage > 0.0 ? 1.0 / damage : std::numeric_limits<double>::infinity();
}

}  // namespace kinetofem::fatigue
