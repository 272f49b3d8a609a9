#pragma once
// Geometry of a chain (belt, rope) from its hinge to the roller it wraps on
// (SPEC §1: the flexible link 3 hinged at B0, wrapped on roller 2' of radius
// r centred at A): the one place where the free length and the tangent point
// are computed (the chain constraint, its output frames, the load transfer).
//
// With e = P_hinge - C (C the roller centre), d = |e| > r and sigma = +1 when
// the chain, followed from the hinge onto the roller, turns counter-clockwise
// about C (-1 clockwise):
//   free length     b   = sqrt(d^2 - r^2)
//   tangent angle   tau = atan2(e_y, e_x) + sigma acos(r / d)
//   tangent point   T   = C + r (cos tau, sin tau)
// The chain pulls the roller at T along (P_hinge - T) / b.
#include <cmath>

#include <Eigen/Core>

namespace kinetofem::mech {

struct ChainTangent {
  double free_length_m = 0.0;      // b
  double tangent_angle_rad = 0.0;  // tau, world
  Eigen::Vector2d tangent_point_m = Eigen::Vector2d::Zero();
};

// `hinge` and `centre` in the same (world) frame, m; requires |hinge - centre| > r.
inline ChainTangent chain_tangent(const Eigen::Vector2d& hinge, const Eigen::Vector2d& centre, double radius_m,
                                  double sigma) {
  const Eigen::Vector2d e = hinge - centre;
  const double d = e.norm();
  ChainTangent t;
  t.free_length_m = std::sqrt(d * d - radius_m * radius_m);
  t.tangent_angle_rad = std::atan2(e.y(), e.x()) + sigma * std::acos(radius_m / d);
  t.tangent_point_m = centre + radius_m * Eigen::Vector2d(std::cos(t.tangent_angle_rad), std::sin(t.tangent_angle_rad));
  return t;
}

}  // namespace kinetofem::mech
