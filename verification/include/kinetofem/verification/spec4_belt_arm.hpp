#pragma once
// SPEC §4's two-link Q-manipulator built in the planar multibody core with a
// belt (mech::Transmission), and its references (docs/transmissions.md):
// links 1 and 2 (l1 = l2 = 0.2 m) on revolute joints O and A, a belt from the
// frame's pulley to link 2's 20 mm pulley carried by link 1 (ratio -4: the
// source's i = 4, phi_21 = -i phi_10), link 2's centre of mass off its axis,
// a 3 kg payload at H, link 1 driven through a full turn in 2 s by a 3-4-5
// law, gravity -y. Bodies ground, link1, link2; joints O, A; drive lever;
// transmission belt. Shared by tests/verification/mechanisms/
// test_transmission_q_manipulator.cpp and `kinetofem verify`.
//
// References:
//   H(P) = l1 e(P) + l2 e((1 - i) P)         (mech::QManipulator, SPEC §4)
//   M_out = J_2 theta_2'' + sum_k rho_k x m_k (a_A + theta_2'' rho_k^perp - theta_2'^2 rho_k - g)
// the hand kinetostatics of link 2 about its pin A with the known kinematics
// (theta_2 = (1 + ratio) P; P, P', P'' from the law; a_A = l1 (P'' e_perp(P) -
// P'^2 e(P))), summed over link 2's bare body (J_2 about its centre) and the
// payload; the belt pull is M_out / r, the input's moment -ratio M_out. SI.
#include <memory>

#include <Eigen/Core>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"

namespace kinetofem::verification::spec4 {

inline constexpr double kBeltArmL1 = 0.2, kBeltArmL2 = 0.2;  // m, as cases/mechanisms/q_manipulator_rose
inline constexpr double kBeltArmSourceRatio = 4.0;           // the source's i (phi_21 = -i phi_10)
inline constexpr double kBeltArmRatio = -kBeltArmSourceRatio;  // ours (phi_21 = ratio phi_10)
inline constexpr double kBeltArmPulleyRadius = 0.02;         // m, link 2's pulley
inline constexpr double kBeltArmDuration = 2.0;              // s, the lever's full turn
// The constraints' residual and the index-1 solve's round-off only: 1e-9 (of
// l1 for H, of the peak moment for the belt).
inline constexpr double kBeltArmTolerance = 1e-9;

// The lever's law: 3-4-5 polynomial, 2 pi in kBeltArmDuration (mech::make_motion_law).
std::shared_ptr<const mech::MotionLaw> belt_arm_lever_law();
mech::MultibodyModel belt_arm_model();
// The belt's moment on link 2 (N m) at the lever's state, by hand (above).
double belt_arm_moment_on_link2(const mech::MotionState& lever);

// The worst differences of a run of belt_arm_model() from the references over
// its frames (m, N m, N, N m, rad), and the largest reference moment (N m).
struct BeltArmAgreement {
  double path_m = 0.0, moment_Nm = 0.0, force_N = 0.0, input_moment_Nm = 0.0, row_rad = 0.0;
  double moment_scale_Nm = 0.0;
};
BeltArmAgreement belt_arm_against_references(const mech::Results& results);

}  // namespace kinetofem::verification::spec4
