#include "kinetofem/verification/spec4_q_manipulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace kinetofem::verification::spec4 {

mech::QManipulator rose() { return mech::make_two_link_q_manipulator(0.5, 0.2, 4.0); }

double pointwise_distance(const mech::QManipulator& q, const mech::IsokinematicEquivalent& equivalent, int count,
                          double step_rad) {
  const double one_minus_i = 1.0 - q.ratios().at(0);
  double worst = 0.0;
  for (int k = 0; k < count; ++k) {
    const double p = step_rad * k;
    worst = std::max(worst, (q.point_h(p).p - equivalent.manipulator.point_h(one_minus_i * p).p).norm());
  }
  return worst;
}

namespace {

double directed_distance(const std::vector<Eigen::Vector2d>& from, const std::vector<Eigen::Vector2d>& to) {
  double worst = 0.0;
  for (const auto& p : from) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& r : to) best = std::min(best, (p - r).squaredNorm());
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

}  // namespace

double hausdorff_distance(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b) {
  return std::max(directed_distance(a, b), directed_distance(b, a));
}

double rose_pair_hausdorff(const mech::QManipulator& rose, const mech::IsokinematicEquivalent& equivalent, int n) {
  const double pi = std::numbers::pi;
  std::vector<Eigen::Vector2d> a, b;
  for (int k = 0; k < n; ++k) a.push_back(rose.point_h(2 * pi * k / n).p);
  for (int k = 0; k < 3 * n; ++k) b.push_back(equivalent.manipulator.point_h(6 * pi * k / (3 * n)).p);
  return hausdorff_distance(a, b);
}

double rose_sampling_chord(int n) { return 1.1 * 2 * std::numbers::pi / n; }

}  // namespace kinetofem::verification::spec4
