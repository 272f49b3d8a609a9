#pragma once
// Planar vector helpers shared by the multibody sources (internal header).
// Angles in rad, counter-clockwise positive; vectors in any one frame.
#include <cmath>

#include <Eigen/Core>

namespace kinetofem::mech::planar {

// Rotation matrix of angle theta: body frame -> world frame.
inline Eigen::Matrix2d rotation(double theta) {
  Eigen::Matrix2d a;
  a << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  return a;
}
// v turned by +90 degrees (e_z x v).
inline Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
// z component of a x b.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace kinetofem::mech::planar
