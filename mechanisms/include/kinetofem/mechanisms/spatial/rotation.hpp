#pragma once
// Euler-parameter algebra of the spatial multibody core (Haug, Computer-Aided
// Kinematics and Dynamics of Mechanical Systems, 1989, ch. 6; Nikravesh 1988).
//
// p = (e0, e) with e = (e1, e2, e3): the Euler parameters (unit quaternion) of
// a body frame; a vector a' given in body axes is a = A(p) a' in world axes.
//   E(p) = [-e, e~ + e0 I],  G(p) = [-e, -e~ + e0 I]   (3 x 4)
//   A(p) = E(p) G(p)^T = (e0^2 - e.e) I + 2 e e^T + 2 e0 e~
// A is written as this homogeneous quadratic in p (equal to the rotation matrix
// when p.p = 1, which the norm constraint keeps), so its derivative is exact:
//   d(A(p) a')/dp = B(p, a') = 2 [(e0 I + e~) a',  e a'^T - (e0 I + e~) a'~]   (3 x 4)
// Angular velocity in body axes omega' = 2 G(p) p', and for a unit p
// p' = (1/2) G(p)^T omega'. The time derivative of a body vector is
// A (omega' x a') = -A a'~ omega'.
#include <cmath>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace kinetofem::mech::spatial {

// a~ such that a~ b = a x b.
inline Eigen::Matrix3d skew(const Eigen::Vector3d& a) {
  Eigen::Matrix3d s;
  s << 0.0, -a.z(), a.y(), a.z(), 0.0, -a.x(), -a.y(), a.x(), 0.0;
  return s;
}

inline Eigen::Matrix3d rotation(const Eigen::Vector4d& p) {
  const double e0 = p(0);
  const Eigen::Vector3d e = p.tail<3>();
  return (e0 * e0 - e.dot(e)) * Eigen::Matrix3d::Identity() + 2.0 * e * e.transpose() + 2.0 * e0 * skew(e);
}

inline Eigen::Matrix<double, 3, 4> g_matrix(const Eigen::Vector4d& p) {
  Eigen::Matrix<double, 3, 4> g;
  g.col(0) = -p.tail<3>();
  g.rightCols<3>() = -skew(p.tail<3>()) + p(0) * Eigen::Matrix3d::Identity();
  return g;
}

inline Eigen::Matrix<double, 3, 4> b_matrix(const Eigen::Vector4d& p, const Eigen::Vector3d& a_body) {
  const Eigen::Matrix3d c = p(0) * Eigen::Matrix3d::Identity() + skew(p.tail<3>());
  Eigen::Matrix<double, 3, 4> b;
  b.col(0) = 2.0 * c * a_body;
  b.rightCols<3>() = 2.0 * (p.tail<3>() * a_body.transpose() - c * skew(a_body));
  return b;
}

// Euler parameters of a rotation matrix (Shepperd's method: the largest of the
// four squares is taken first so that no division is by a small number); e0 >= 0.
inline Eigen::Vector4d euler_parameters(const Eigen::Matrix3d& a) {
  const Eigen::Quaterniond quat(a);
  Eigen::Vector4d p(quat.w(), quat.x(), quat.y(), quat.z());
  p.normalize();
  return p(0) < 0.0 ? Eigen::Vector4d(-p) : p;
}

// Euler parameters of a rotation by angle_rad about the unit axis u.
inline Eigen::Vector4d axis_angle(const Eigen::Vector3d& u, double angle_rad) {
  Eigen::Vector4d p;
  p << std::cos(0.5 * angle_rad), std::sin(0.5 * angle_rad) * u.normalized();
  return p;
}

// A unit vector perpendicular to the unit vector h: the world axis least
// aligned with h, with its component along h removed.
inline Eigen::Vector3d perpendicular(const Eigen::Vector3d& h) {
  Eigen::Index k = 0;
  h.cwiseAbs().minCoeff(&k);
  Eigen::Vector3d f = Eigen::Vector3d::Unit(k);
  f -= f.dot(h) * h;
  return f.normalized();
}

}  // namespace kinetofem::mech::spatial
