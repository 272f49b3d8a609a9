#include "kinetofem/verification/kirsch_plate.hpp"

#include <cmath>

namespace kinetofem::verification {

Eigen::Matrix3d kirsch_stress_x(double x, double y, double a, double S) {
  const double r = std::hypot(x, y), t = std::atan2(y, x);
  const double q2 = a * a / (r * r), q4 = q2 * q2;
  Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
  s(0, 0) = S * (1 - q2 * (1.5 * std::cos(2 * t) + std::cos(4 * t)) + 1.5 * q4 * std::cos(4 * t));
  s(1, 1) = S * (-q2 * (0.5 * std::cos(2 * t) - std::cos(4 * t)) - 1.5 * q4 * std::cos(4 * t));
  s(0, 1) = s(1, 0) = S * (-q2 * (0.5 * std::sin(2 * t) + std::sin(4 * t)) + 1.5 * q4 * std::sin(4 * t));
  return s;
}

Eigen::Matrix3d kirsch_stress_y(const Eigen::Vector3d& p, double a, double S) {
  const Eigen::Matrix3d s = kirsch_stress_x(p[1], p[0], a, S);
  Eigen::Matrix3d swapped = Eigen::Matrix3d::Zero();
  swapped(0, 0) = s(1, 1);
  swapped(1, 1) = s(0, 0);
  swapped(0, 1) = swapped(1, 0) = s(0, 1);
  return swapped;
}

}  // namespace kinetofem::verification
