#include "kinetofem/mechanisms/time_grid.hpp"

#include <cmath>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

std::vector<double> equally_spaced_times(double end_time_s, long count) {
  require(count >= 2, "equally_spaced_times: need at least 2 times, got {}", count);
  require(std::isfinite(end_time_s) && end_time_s > 0.0,
          "equally_spaced_times: end time must be finite and positive, got {} s", end_time_s);
  std::vector<double> times(static_cast<std::size_t>(count));
  const double intervals = static_cast<double>(count - 1);
  times.front() = 0.0;
  for (long k = 1; k + 1 < count; ++k)
    times[static_cast<std::size_t>(k)] = end_time_s * static_cast<double>(k) / intervals;
  times.back() = end_time_s;
  return times;
}

}  // namespace kinetofem::mech
