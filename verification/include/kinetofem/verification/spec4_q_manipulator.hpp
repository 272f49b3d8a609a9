#pragma once
// SPEC §4 (seeds/002, ch. II): isokinematic Q-manipulators. A two-link
// Q-manipulator (l1, l2, ratio i) and its equivalent l1' = l2, l2' = l1,
// 1 - i' = 1/(1 - i) trace the same point set; point by point
// H(P) = H'((1 - i) P).
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/q_manipulator.hpp"

namespace kinetofem::verification::spec4 {

// The example both check: a rose, l1 = 0.5 m, l2 = 0.2 m, i = 4 (1 - i = -3),
// so i' = 1 + 1/3.
mech::QManipulator rose();
inline constexpr double kRoseEquivalentRatio = 1.0 + 1.0 / 3.0;

// max over P = k step, k = 0 .. count-1, of |H(P) - H'((1 - i) P)| (m).
double pointwise_distance(const mech::QManipulator& q, const mech::IsokinematicEquivalent& equivalent, int count,
                          double step_rad);

// Hausdorff distance of two point sets (m): the larger of the two directed
// distances max_a min_b |a - b|.
double hausdorff_distance(const std::vector<Eigen::Vector2d>& a, const std::vector<Eigen::Vector2d>& b);

// The rose and its equivalent as point sets: each closed curve sampled over
// its period (2 pi with n points, 6 pi with 3 n), their Hausdorff distance (m).
double rose_pair_hausdorff(const mech::QManipulator& rose, const mech::IsokinematicEquivalent& equivalent, int n);

// The sampling chord of n points over 2 pi: |H'| <= l1 + 3 l2 = 1.1 m/rad
// times the step 2 pi / n (m).
double rose_sampling_chord(int n);

}  // namespace kinetofem::verification::spec4
