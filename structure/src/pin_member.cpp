#include "kinetofem/structure/pin_member.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"

namespace kinetofem::structure {

using Eigen::Vector3d;

double PinSection::area_m2() const { return std::numbers::pi * diameter_m * diameter_m / 4.0; }
double PinSection::second_moment_m4() const { return std::numbers::pi * std::pow(diameter_m, 4) / 64.0; }
double PinSection::shear_modulus_pa() const { return youngs_modulus_pa / (2.0 * (1.0 + poisson_ratio)); }
double PinSection::shear_coefficient() const { return 6.0 * (1.0 + poisson_ratio) / (7.0 + 6.0 * poisson_ratio); }

void PinSection::validate(const std::string& who) const {
  require(std::isfinite(diameter_m) && diameter_m > 0, "{}: pin diameter {} m must be positive", who, diameter_m);
  require(std::isfinite(youngs_modulus_pa) && youngs_modulus_pa > 0, "{}: pin Young's modulus {} Pa must be positive",
          who, youngs_modulus_pa);
  require(std::isfinite(poisson_ratio) && poisson_ratio > -1.0 && poisson_ratio < 0.5,
          "{}: pin Poisson's ratio {} must lie in (-1, 0.5)", who, poisson_ratio);
}

Matrix12d PinMember::local_stiffness(double L, const PinSection& s) {
  const double E = s.youngs_modulus_pa, A = s.area_m2(), I = s.second_moment_m4();
  const double phi = 12.0 * E * I / (s.shear_coefficient() * s.shear_modulus_pa() * A * L * L);
  const double b = E * I / ((1.0 + phi) * L * L * L);
  Matrix12d K = Matrix12d::Zero();
  // Axial (x'): dofs 0 and 6.
  const double a = E * A / L;
  K(0, 0) = K(6, 6) = a;
  K(0, 6) = K(6, 0) = -a;
  // Bending in x'y' (v = 1, 7; theta_z' = 5, 11) and x'z' (w = 2, 8; theta_y' = 4, 10).
  auto bend = [&](int v1, int r1, int v2, int r2, double sign) {
    const int d[4] = {v1, r1, v2, r2};
    const double m[4][4] = {{12, 6 * L, -12, 6 * L},
                            {6 * L, (4 + phi) * L * L, -6 * L, (2 - phi) * L * L},
                            {-12, -6 * L, 12, -6 * L},
                            {6 * L, (2 - phi) * L * L, -6 * L, (4 + phi) * L * L}};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        // The 6L terms couple a translation with a rotation: one index odd.
        const bool coupling = (r % 2) != (c % 2);
        K(d[r], d[c]) = b * m[r][c] * (coupling ? sign : 1.0);
      }
  };
  bend(1, 5, 7, 11, 1.0);
  bend(2, 4, 8, 10, -1.0);
  return K;
}

PinMember::PinMember(const Vector3d& end_i_m, const Vector3d& end_j_m, const PinSection& section,
                     const std::string& who)
    : end_i_(end_i_m), end_j_(end_j_m), section_(section) {
  section_.validate(who);
  const Vector3d d = end_j_ - end_i_;
  length_ = d.norm();
  require(length_ > 0 && std::isfinite(length_), "{}: the pin's ends coincide (length {} m)", who, length_);
  axis_ = d / length_;
  // Any transverse pair (the section is round).
  const Vector3d helper = std::abs(axis_.x()) < 0.9 ? Vector3d::UnitX() : Vector3d::UnitY();
  const Vector3d y = axis_.cross(helper).normalized();
  const Vector3d z = axis_.cross(y);
  to_local_.row(0) = axis_.transpose();
  to_local_.row(1) = y.transpose();
  to_local_.row(2) = z.transpose();
  Matrix12d T = Matrix12d::Zero();
  for (int b = 0; b < 4; ++b) T.block<3, 3>(3 * b, 3 * b) = to_local_;
  k_world_ = T.transpose() * local_stiffness(length_, section_) * T;
  k_world_ = 0.5 * (k_world_ + k_world_.transpose()).eval();
}

PinLoads PinMember::loads(const Vector12d& u) const {
  const Vector12d f = k_world_ * u;  // what the bodies apply on the pin's ends
  PinLoads out;
  out.force_on_i_n = -f.segment<3>(0);
  out.moment_on_i_nm = -f.segment<3>(3);
  out.force_on_j_n = -f.segment<3>(6);
  out.moment_on_j_nm = -f.segment<3>(9);
  const Eigen::Matrix3d transverse = Eigen::Matrix3d::Identity() - axis_ * axis_.transpose();
  // At end j the section carries the load on the pin's end j; tension: along +axis at j.
  out.axial_force_n = axis_.dot(f.segment<3>(6));
  out.shear_force_n = (transverse * f.segment<3>(6)).norm();
  out.bending_moment_i_nm = (transverse * f.segment<3>(3)).norm();
  out.bending_moment_j_nm = (transverse * f.segment<3>(9)).norm();
  const double d = section_.diameter_m;
  const double M = std::max(out.bending_moment_i_nm, out.bending_moment_j_nm);
  out.bending_stress_pa = 32.0 * M / (std::numbers::pi * d * d * d);
  out.shear_stress_pa = 16.0 * out.shear_force_n / (3.0 * std::numbers::pi * d * d);
  const Vector3d ui = u.segment<3>(0), ti = u.segment<3>(3), uj = u.segment<3>(6), tj = u.segment<3>(9);
  const Vector3d span = end_j_ - end_i_;
  const double at_j = (transverse * (uj - ui - ti.cross(span))).norm();
  const double at_i = (transverse * (ui - uj - tj.cross(-span))).norm();
  out.deflection_m = std::max(at_i, at_j);
  return out;
}

}  // namespace kinetofem::structure
