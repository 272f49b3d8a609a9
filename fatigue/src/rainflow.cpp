#include "kinetofem/fatigue/rainflow.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fatigue {

namespace {

Cycle make_cycle(double a, double b, double count) {
  return Cycle{.range_pa = std::abs(a - b), .mean_pa = 0.5 * (a + b), .count = count};
}

// Reduction of a sequence without non-finite values (see turning_points).
std::vector<double> reduce(std::span<const double> values) {
  std::vector<double> distinct;
  distinct.reserve(values.size());
  for (double v : values) {
    if (distinct.empty() || v != distinct.back()) distinct.push_back(v);
  }
  if (distinct.size() <= 2) return distinct;
  std::vector<double> points;
  points.reserve(distinct.size());
  points.push_back(distinct.front());
  for (std::size_t i = 1; i + 1 < distinct.size(); ++i) {
    const double before = distinct[i] - distinct[i - 1];
    const double after = distinct[i + 1] - distinct[i];
    if ((before > 0.0) != (after > 0.0)) points.push_back(distinct[i]);
  }
  points.push_back(distinct.back());
  return points;
}

// ASTM E1049-85 5.4.4 on a sequence of turning points.
std::vector<Cycle> count_turning_points(const std::vector<double>& points) {
  std::vector<Cycle> cycles;
  std::vector<double> stack;  // stack[start] is the starting point S
  stack.reserve(points.size());
  std::size_t start = 0;
  for (double p : points) {
    stack.push_back(p);
    while (stack.size() - start >= 3) {
      const std::size_t n = stack.size();
      const double x = std::abs(stack[n - 1] - stack[n - 2]);
      const double y = std::abs(stack[n - 2] - stack[n - 3]);
      if (x < y) break;
      if (n - start == 3) {
        // Y contains the starting point: half cycle, S moves to Y's second point.
        cycles.push_back(make_cycle(stack[start], stack[start + 1], 0.5));
        ++start;
      } else {
        cycles.push_back(make_cycle(stack[n - 3], stack[n - 2], 1.0));
        stack[n - 3] = stack[n - 1];
        stack.resize(n - 2);
      }
    }
  }
  for (std::size_t i = start; i + 1 < stack.size(); ++i) {
    cycles.push_back(make_cycle(stack[i], stack[i + 1], 0.5));
  }
  return cycles;
}

}  // namespace

std::vector<double> turning_points(std::span<const double> history_pa) {
  for (std::size_t i = 0; i < history_pa.size(); ++i) {
    require(std::isfinite(history_pa[i]),
            "fatigue: stress history value {} at index {} is not finite", history_pa[i], i);
  }
  return reduce(history_pa);
}

std::vector<Cycle> rainflow_count(std::span<const double> history_pa, Residue residue) {
  std::vector<double> points = turning_points(history_pa);
  if (points.size() < 2) return {};
  if (residue == Residue::Periodic) {
    // One period: rotate to start and end at the largest turning point.
    const auto peak = std::max_element(points.begin(), points.end()) - points.begin();
    std::vector<double> rotated;
    rotated.reserve(points.size() + 1);
    rotated.insert(rotated.end(), points.begin() + peak, points.end());
    rotated.insert(rotated.end(), points.begin(), points.begin() + peak + 1);
    points = reduce(rotated);
  }
  return count_turning_points(points);
}

std::vector<RangeCount> merge_ranges(std::span<const Cycle> cycles, double tolerance_pa) {
  require(std::isfinite(tolerance_pa) && tolerance_pa >= 0.0,
          "fatigue: range merge tolerance {} Pa must be >= 0", tolerance_pa);
  std::vector<Cycle> sorted(cycles.begin(), cycles.end());
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const Cycle& a, const Cycle& b) { return a.range_pa < b.range_pa; });
  std::vector<RangeCount> merged;
  for (const Cycle& c : sorted) {
    if (!merged.empty() && c.range_pa - merged.back().range_pa <= tolerance_pa) {
      merged.back().count += c.count;
    } else {
      merged.push_back(RangeCount{.range_pa = c.range_pa, .count = c.count});
    }
  }
  return merged;
}

double total_count(std::span<const Cycle> cycles) {
  double n = 0.0;
  for (const Cycle& c : cycles) n += c.count;
  return n;
}

}  // namespace kinetofem::fatigue
