#include "kinetofem/mechanisms/q_manipulator.hpp"

#include <cmath>
#include <utility>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {
namespace {

Eigen::Vector2d unit(double t) { return {std::cos(t), std::sin(t)}; }
Eigen::Vector2d unit_perp(double t) { return {-std::sin(t), std::cos(t)}; }

}  // namespace

QManipulator::QManipulator(std::vector<double> lengths_m, std::vector<double> ratios,
                           std::vector<double> initial_relative_angles_rad,
                           Eigen::Vector2d origin_m)
    : lengths_(std::move(lengths_m)), ratios_(std::move(ratios)), origin_(origin_m) {
  const std::size_t n = lengths_.size();
  require(n >= 1, "Q-manipulator: needs at least one link");
  for (std::size_t k = 0; k < n; ++k)
    require(std::isfinite(lengths_[k]) && lengths_[k] > 0.0,
            "Q-manipulator: length l_{} = {} m must be positive", k + 1, lengths_[k]);
  require(ratios_.size() + 1 == n, "Q-manipulator: {} links need {} CTM ratios, got {}", n, n - 1,
          ratios_.size());
  for (std::size_t k = 0; k < ratios_.size(); ++k)
    require(std::isfinite(ratios_[k]), "Q-manipulator: ratio i_{} is not finite", k + 1);
  if (initial_relative_angles_rad.empty()) initial_relative_angles_rad.assign(n, 0.0);
  require(initial_relative_angles_rad.size() == n,
          "Q-manipulator: {} links need {} initial relative angles, got {}", n, n,
          initial_relative_angles_rad.size());
  require(origin_.allFinite(), "Q-manipulator: non-finite origin");

  // K_k = sum_{j<=k} (-1)^(j-1) prod_{m<j} i_m, accumulated link by link.
  rates_.resize(n);
  alpha_abs_.resize(n);
  double relative_rate = 1.0;  // d phi_{j,j-1} / dP
  double rate = 0.0, alpha = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    if (j > 0) relative_rate *= -ratios_[j - 1];
    rate += relative_rate;
    alpha += initial_relative_angles_rad[j];
    rates_[j] = rate;
    alpha_abs_[j] = alpha;
  }
}

double QManipulator::link_angle_rad(std::size_t k, double lever_angle_rad) const {
  require(k >= 1 && k <= lengths_.size(), "Q-manipulator: link {} out of range 1..{}", k,
          lengths_.size());
  return alpha_abs_[k - 1] + rates_[k - 1] * lever_angle_rad;
}

PointKinematics QManipulator::point_h(double lever_angle_rad) const {
  PointKinematics h;
  h.p = origin_;
  for (std::size_t k = 0; k < lengths_.size(); ++k) {
    const double t = alpha_abs_[k] + rates_[k] * lever_angle_rad;
    h.p += lengths_[k] * unit(t);
    h.d1 += lengths_[k] * rates_[k] * unit_perp(t);
    h.d2 -= lengths_[k] * rates_[k] * rates_[k] * unit(t);
  }
  return h;
}

std::vector<double> QManipulator::find_cusps(double p_lo_rad, double p_hi_rad,
                                             std::size_t n_samples, double rel_tol) const {
  require(p_hi_rad > p_lo_rad, "Q-manipulator cusps: empty range [{}, {}]", p_lo_rad, p_hi_rad);
  require(n_samples >= 3, "Q-manipulator cusps: need at least 3 samples");
  double scale = 0.0;
  for (std::size_t k = 0; k < lengths_.size(); ++k) scale += std::abs(lengths_[k] * rates_[k]);
  auto speed_sq = [&](double p) { return point_h(p).d1.squaredNorm(); };
  const double dp = (p_hi_rad - p_lo_rad) / static_cast<double>(n_samples - 1);
  std::vector<double> f(n_samples);
  for (std::size_t s = 0; s < n_samples; ++s) f[s] = speed_sq(p_lo_rad + dp * s);
  std::vector<double> cusps;
  for (std::size_t s = 0; s < n_samples; ++s) {
    const bool left_ok = s == 0 || f[s] <= f[s - 1];
    const bool right_ok = s + 1 == n_samples || f[s] < f[s + 1];
    if (!(left_ok && right_ok)) continue;
    // Golden-section search for the minimum of |H'|^2 in the bracketing cell.
    double lo = std::max(p_lo_rad, p_lo_rad + dp * (static_cast<double>(s) - 1.0));
    double hi = std::min(p_hi_rad, p_lo_rad + dp * (static_cast<double>(s) + 1.0));
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    double f1 = speed_sq(x1), f2 = speed_sq(x2);
    for (int it = 0; it < 200 && hi - lo > 1e-14 * (1.0 + std::abs(lo)); ++it) {
      if (f1 < f2) {
        hi = x2; x2 = x1; f2 = f1; x1 = hi - g * (hi - lo); f1 = speed_sq(x1);
      } else {
        lo = x1; x1 = x2; f1 = f2; x2 = lo + g * (hi - lo); f2 = speed_sq(x2);
      }
    }
    const double p = 0.5 * (lo + hi);
    if (std::sqrt(speed_sq(p)) <= rel_tol * scale) {
      if (cusps.empty() || std::abs(p - cusps.back()) > 2.0 * dp) cusps.push_back(p);
    }
  }
  return cusps;
}

QManipulator make_two_link_q_manipulator(double l1_m, double l2_m, double ratio,
                                         double alpha21_rad) {
  return QManipulator({l1_m, l2_m}, {ratio}, {0.0, alpha21_rad});
}

QManipulator make_three_link_q_manipulator(double l1_m, double l2_m, double l3_m, double i21,
                                           double i32) {
  return QManipulator({l1_m, l2_m, l3_m}, {i21, i32});
}

bool two_link_has_cusps(double l1_m, double l2_m, double ratio, double rel_tol) {
  require(l1_m > 0.0 && l2_m > 0.0, "Q-manipulator: lengths l1 = {}, l2 = {} must be positive",
          l1_m, l2_m);
  return std::abs(l1_m - std::abs(l2_m * (1.0 - ratio))) <= rel_tol * l1_m;
}

IsokinematicEquivalent isokinematic_equivalent(const QManipulator& m) {
  require(m.link_count() == 2, "isokinematic equivalent: defined for 2 links, got {}",
          m.link_count());
  const double i = m.ratios()[0];
  require(std::abs(1.0 - i) > 1e-12,
          "isokinematic equivalent: ratio i = {} makes 1 - i zero (link 2 translates)", i);
  const double scale = 1.0 - i;
  const double i_prime = 1.0 - 1.0 / scale;
  const auto& alpha = m.initial_absolute_angles_rad();
  const Eigen::Vector2d origin = m.point_h(0.0).p - m.lengths_m()[0] * unit(alpha[0]) -
                                 m.lengths_m()[1] * unit(alpha[1]);
  QManipulator eq({m.lengths_m()[1], m.lengths_m()[0]}, {i_prime},
                  {alpha[1], alpha[0] - alpha[1]}, origin);
  return {std::move(eq), scale};
}

}  // namespace kinetofem::mech
