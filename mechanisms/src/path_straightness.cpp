#include "kinetofem/mechanisms/path_straightness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

double horizontal_extent(const std::vector<Eigen::Vector2d>& path_m) {
  require(!path_m.empty(), "horizontal extent: empty path");
  double lo = path_m.front().x(), hi = lo;
  for (const auto& p : path_m) {
    lo = std::min(lo, p.x());
    hi = std::max(hi, p.x());
  }
  return hi - lo;
}

HorizontalStraightness horizontal_straightness(const std::vector<Eigen::Vector2d>& path_m,
                                               double window_length_m, double reference_y_m) {
  require(path_m.size() >= 2, "path straightness: need at least 2 samples, got {}",
          path_m.size());
  require(std::isfinite(window_length_m) && window_length_m > 0.0,
          "path straightness: window length {} m must be positive", window_length_m);
  HorizontalStraightness best;
  best.window_length_m = window_length_m;
  best.reference_y_m = reference_y_m;
  const std::size_t n = path_m.size();
  // The window kept is the one with the narrowest horizontal band (max y - min y),
  // the straightness zone of metrology with the direction fixed to X.
  // O(n * window) scan: paths here have a few thousand samples.
  double best_band = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i) {
    double x_lo = path_m[i].x(), x_hi = x_lo;
    double y_lo = path_m[i].y(), y_hi = y_lo;
    for (std::size_t k = i + 1; k < n; ++k) {
      x_lo = std::min(x_lo, path_m[k].x());
      x_hi = std::max(x_hi, path_m[k].x());
      y_lo = std::min(y_lo, path_m[k].y());
      y_hi = std::max(y_hi, path_m[k].y());
      if (y_hi - y_lo >= best_band) break;  // cannot beat the best window
      if (x_hi - x_lo >= window_length_m) {
        best.window_found = true;
        best.first_index = i;
        best.last_index = k;
        best_band = y_hi - y_lo;
        break;
      }
    }
  }
  if (!best.window_found) return best;
  double y_lo = std::numeric_limits<double>::infinity();
  double y_hi = -y_lo;
  best.x_min_m = std::numeric_limits<double>::infinity();
  best.x_max_m = -best.x_min_m;
  for (std::size_t k = best.first_index; k <= best.last_index; ++k) {
    const auto& p = path_m[k];
    y_lo = std::min(y_lo, p.y());
    y_hi = std::max(y_hi, p.y());
    best.x_min_m = std::min(best.x_min_m, p.x());
    best.x_max_m = std::max(best.x_max_m, p.x());
  }
  best.max_above_m = std::max(0.0, y_hi - reference_y_m);
  best.max_below_m = std::max(0.0, reference_y_m - y_lo);
  best.band_height_m = y_hi - y_lo;
  best.max_deviation_m = std::max(best.max_above_m, best.max_below_m);
  return best;
}

}  // namespace kinetofem::mech
