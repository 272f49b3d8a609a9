#pragma once
// Rainflow cycle counting of a stress history, ASTM E1049-85 (reapproved
// 2011), section 5.4.4 "Rainflow Counting" (the three-point algorithm).
//
// Units: stresses in Pa, counts as doubles (0.5 for a half cycle, 1.0 for a
// full cycle).
//
// 1. turning_points(): the history reduced to its peaks and valleys. Repeated
//    values (plateaus) are dropped first; the first and the last point are
//    kept (the standard counts from the first point S of the history and
//    ends at its last point), and an interior point is kept where the slope
//    changes sign.
// 2. rainflow_count(), on the turning points, with X the range of the two
//    most recent points and Y the range before it (5.4.4):
//      X < Y                           read the next point;
//      X >= Y and Y holds the start S  count Y as 1/2 cycle, discard the
//                                      first point of Y, S moves on;
//      X >= Y otherwise                count Y as 1 cycle, discard its two
//                                      points.
//    At the end of the history each remaining range (the residue) counts as
//    1/2 cycle, as the standard does (Residue::HalfCycles). For a history
//    that repeats (one period of a periodic load), Residue::Periodic counts
//    the history rotated to start and end at its largest turning point: the
//    residue then closes and every range of the repeated history is counted
//    once per period (the pairs of half cycles left are equal ranges).
//
// Range = |a - b|, mean = (a + b) / 2 of the two points of a counted range.
// Worked example: the history -2, 1, -3, 5, -1, 3, -4, 4, -2 of ASTM E1049
// fig. 6 counts ranges 3 (0.5), 4 (1.5), 6 (0.5), 8 (1.0), 9 (0.5)
// (tests/verification/fatigue/test_rainflow_astm.cpp).
#include <span>
#include <vector>

namespace kinetofem::fatigue {

struct Cycle {
  double range_pa = 0.0;  // |a - b| >= 0
  double mean_pa = 0.0;   // (a + b) / 2
  double count = 0.0;     // 0.5 (half cycle) or 1.0 (full cycle)
};

enum class Residue {
  HalfCycles,  // ASTM E1049-85 5.4.4: the residue counts as half cycles
  Periodic,    // the history is one period of a repeated load (see above)
};

// Peaks and valleys of the history (plateaus removed, end points kept).
// Empty for an empty history. Error on a value that is not finite.
std::vector<double> turning_points(std::span<const double> history_pa);

// Rainflow cycles of the history in the order the algorithm counts them.
// Empty for a history of fewer than two distinct values.
std::vector<Cycle> rainflow_count(std::span<const double> history_pa,
                                  Residue residue = Residue::HalfCycles);

// Counted cycles summed per range, for printing: sorted by range ascending;
// ranges within tolerance_pa of the first range of a group merge into it
// (tolerance_pa = 0: only equal ranges merge). Error if tolerance_pa < 0.
struct RangeCount {
  double range_pa = 0.0;
  double count = 0.0;
};
std::vector<RangeCount> merge_ranges(std::span<const Cycle> cycles, double tolerance_pa = 0.0);

// Sum of the counts (cycles of the spectrum).
double total_count(std::span<const Cycle> cycles);

}  // namespace kinetofem::fatigue
