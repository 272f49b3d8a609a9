#pragma once
// Straightness of a sampled planar path with respect to a horizontal line
// (SPEC §1: the lever-chain manipulator's near-horizontal path part).
//
// The path is a sequence of points (m) in the order of the input parameter.
// A window is a contiguous run of samples whose horizontal span
// (max x - min x) first reaches window_length_m. Among all windows the one with
// the narrowest horizontal band (max y - min y) is kept: the straightness zone
// of metrology with its direction fixed to X ("over a stretch of length L the
// path stays between two horizontal lines delta apart"). Its deviations from a
// reference line y = reference_y_m are then reported, above and below
// separately. For a synthesized extractor the reference is the path's tangent in
// the design position (horizontal by synthesis); the source's deviations ("about
// 45 mm for C, 20 mm for H over almost 800 mm, in the positive Y direction
// only") are read against it.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace kinetofem::mech {

// max x - min x over all samples (m). Throws on an empty path.
double horizontal_extent(const std::vector<Eigen::Vector2d>& path_m);

struct HorizontalStraightness {
  bool window_found = false;        // false: no stretch of the path spans the length
  double window_length_m = 0.0;     // requested length
  double reference_y_m = 0.0;
  std::size_t first_index = 0;      // best window, inclusive sample indices
  std::size_t last_index = 0;
  double x_min_m = 0.0, x_max_m = 0.0;   // horizontal span of the best window
  double max_deviation_m = 0.0;     // max |y - y_ref| in the best window
  double max_above_m = 0.0;         // max (y - y_ref), >= 0
  double max_below_m = 0.0;         // max (y_ref - y), >= 0
  double band_height_m = 0.0;       // max y - min y in the best window
};

// Throws when window_length_m <= 0 or the path has fewer than 2 samples.
HorizontalStraightness horizontal_straightness(const std::vector<Eigen::Vector2d>& path_m,
                                               double window_length_m, double reference_y_m);

}  // namespace kinetofem::mech
