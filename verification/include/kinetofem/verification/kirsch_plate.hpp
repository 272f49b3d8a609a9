#pragma once
// Plate with a circular hole under remote tension: the stress concentration.
//
// Reference (Kirsch 1898; Timoshenko & Goodier, Theory of Elasticity,
// sec. 35): an infinite plate with a hole of radius a under remote tension S
// along x has, in polar coordinates (r, theta from the x axis),
//   sigma_xx = S [1 - a^2/r^2 (3/2 cos 2t + cos 4t) + 3/2 a^4/r^4 cos 4t]
//   sigma_yy = S [ - a^2/r^2 (1/2 cos 2t - cos 4t) - 3/2 a^4/r^4 cos 4t]
//   sigma_xy = S [ - a^2/r^2 (1/2 sin 2t + sin 4t) + 3/2 a^4/r^4 sin 4t]
// (plane stress and plane strain alike), 3 S at the hole's edge across the
// load.
#include <Eigen/Core>

namespace kinetofem::verification {

inline constexpr double kKirschConcentration = 3.0;  // sigma(a, 90 deg from the load) / S

// The Kirsch stress (3 x 3, in-plane components) at (x, y), tension S along x.
Eigen::Matrix3d kirsch_stress_x(double x, double y, double hole_radius_m, double tension_pa);
// The same for tension along y (x and y swapped, a reflection).
Eigen::Matrix3d kirsch_stress_y(const Eigen::Vector3d& point, double hole_radius_m, double tension_pa);

}  // namespace kinetofem::verification
