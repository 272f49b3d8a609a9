#pragma once
// Q-manipulators: n-link primary chains whose links are coupled by
// constant-ratio control mechanisms (belts, chains, gears), SPEC §4; source
// seeds/002, ch. II, eqs. (II.5)-(II.8), (II.20)-(II.24).
//
// Links k = 1..n of lengths l_k; link k turns relative to link k-1 by
// phi_{k,k-1} (link 0 = frame, phi_{1,0} = P the lever angle). The CTMs give
// phi_{k+1,k} = -i_k phi_{k,k-1} (the source's sign convention: (II.23) carries
// (-1)^(j-1)), so the relative rotation of link j is
//   phi_{j,j-1} = (-1)^(j-1) (i_1 i_2 ... i_{j-1}) P,
// and the absolute angle of link k is
//   Theta_k(P) = alpha_k + K_k P,   K_k = sum_{j=1..k} (-1)^(j-1) prod_{m<j} i_m,
// alpha_k = sum of the initial relative angles alpha_{j,j-1} (j <= k). The
// characteristic point H (end of link n) is, as in (II.20)-(II.23),
//   H(P) = O + sum_k l_k e(Theta_k(P)),  e(t) = (cos t, sin t).
// n = 2: K = (1, 1 - i) gives SPEC's xH = l1 cos P + l2 cos(P(1 - i)) (roses /
// Grandi curves for i > 1); n = 3: K = (1, 1 - i21, 1 - i21 + i21 i32), (II.24).
// Frame: O at the base pivot; SI units (m, rad).
//
// Cusps: H'(P) = sum_k l_k K_k e'(Theta_k) = 0. For n = 2 with zero initial
// angles this needs l1 = |l2 (1 - i)| and, then, happens at
// P = (2j+1) pi / i when l2 (1 - i) = +l1 and at P = 2 j pi / i when l2 (1 - i) = -l1.
//
// Isokinematic equivalent of a 2-link Q-manipulator (SPEC §4, (II.8)):
// l1' = l2, l2' = l1, 1 - i' = 1/(1 - i), alpha1' = alpha2, alpha2' = alpha1
// (absolute initial angles). It traces the same point set with the lever angle
// reparametrised as P' = (1 - i) P: H'(P') = l2 e(alpha2 + P') +
// l1 e(alpha1 + P'/(1 - i)) = H(P). For 1 - i < 0 the curve is run backwards.
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/lever_chain.hpp"  // PointKinematics

namespace kinetofem::mech {

class QManipulator {
 public:
  // lengths_m: l_1..l_n (n >= 1, each > 0); ratios: i_1..i_{n-1};
  // initial_relative_angles_rad: alpha_{1,0}..alpha_{n,n-1} (empty = all zero).
  QManipulator(std::vector<double> lengths_m, std::vector<double> ratios,
               std::vector<double> initial_relative_angles_rad = {},
               Eigen::Vector2d origin_m = Eigen::Vector2d::Zero());

  std::size_t link_count() const { return lengths_.size(); }
  const std::vector<double>& lengths_m() const { return lengths_; }
  const std::vector<double>& ratios() const { return ratios_; }
  // K_k: d Theta_k / d P.
  const std::vector<double>& angle_rates() const { return rates_; }
  // Absolute initial angles alpha_k.
  const std::vector<double>& initial_absolute_angles_rad() const { return alpha_abs_; }

  // H and its first two derivatives w.r.t. the lever angle P.
  PointKinematics point_h(double lever_angle_rad) const;
  // Absolute angle of link k (1-based).
  double link_angle_rad(std::size_t k, double lever_angle_rad) const;

  // Lever angles in [p_lo, p_hi] where |H'| vanishes (cusps): local minima of
  // |H'|^2 found on n_samples and refined by golden-section search, kept when
  // |H'| <= rel_tol * sum_k |l_k K_k|.
  std::vector<double> find_cusps(double p_lo_rad, double p_hi_rad, std::size_t n_samples = 2000,
                                 double rel_tol = 1e-6) const;

 private:
  std::vector<double> lengths_;
  std::vector<double> ratios_;
  std::vector<double> rates_;
  std::vector<double> alpha_abs_;
  Eigen::Vector2d origin_;
};

// The two-link Q-manipulator of SPEC §4 (zero initial angles unless given).
QManipulator make_two_link_q_manipulator(double l1_m, double l2_m, double ratio,
                                         double alpha21_rad = 0.0);
// The three-link one of (II.24): ratios i21, i32.
QManipulator make_three_link_q_manipulator(double l1_m, double l2_m, double l3_m, double i21,
                                           double i32);

// True when the two-link chain's path has cusps: |l1 - |l2 (1 - i)|| <= rel_tol * l1.
bool two_link_has_cusps(double l1_m, double l2_m, double ratio, double rel_tol = 1e-12);

// Isokinematic equivalent of a two-link Q-manipulator (throws unless n = 2 and i != 1).
struct IsokinematicEquivalent {
  QManipulator manipulator;
  double lever_angle_scale;  // P' = lever_angle_scale * P, = 1 - i
};
IsokinematicEquivalent isokinematic_equivalent(const QManipulator& two_link);

}  // namespace kinetofem::mech
