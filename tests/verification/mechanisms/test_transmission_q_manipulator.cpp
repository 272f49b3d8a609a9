// SPEC §4's two-link Q-manipulator built in the planar multibody core: links
// 1 and 2 (l1 = l2 = 0.2 m) on revolute joints O and A, a belt from the
// frame's pulley to link 2's pulley carried by link 1 (a Transmission with
// ratio -4: the source's i = 4, phi_21 = -i phi_10), a payload at H, link 1
// driven through a full turn by a polynomial 3-4-5 law, gravity -y (the model
// and the references: kinetofem/verification/spec4_belt_arm.hpp, shared with
// `kinetofem verify`).
// References (docs/transmissions.md):
//   (a) H from mech::QManipulator's closed form, H(P) = l1 e(P) + l2 e((1 - i) P);
//   (b) the belt's moment on link 2 from the hand kinetostatics of link 2 about
//       A with the known kinematics, M = J2 alpha2 + sum_k rho_k x m_k (a_k - g),
//       and the belt pull M / r;
//   (c) the constraint drift of the integrated motion.
// And two more: the three-link chain of (II.24), two belts in series, against
// mech::make_three_link_q_manipulator; the two-link arm free under gravity
// (1 DoF, the belt's row in the forward dynamics), IDAS against CVODES and
// the energy balance.
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/q_manipulator.hpp"
#include "kinetofem/verification/spec4_belt_arm.hpp"

namespace kinetofem::mech {
namespace {

namespace s4 = verification::spec4;
constexpr double kL1 = s4::kBeltArmL1, kL2 = s4::kBeltArmL2;
constexpr double kSourceRatio = s4::kBeltArmSourceRatio, kRatio = s4::kBeltArmRatio;
constexpr double kPulleyRadius = s4::kBeltArmPulleyRadius;

std::vector<double> output_times(int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(s4::kBeltArmDuration * k / n);
  return t;
}

TEST(TransmissionQManipulator, PathOfHIsSpec4sRoseAndTheBeltMomentIsTheHandKinetostatics) {
  const MultibodySystem system(s4::belt_arm_model());
  for (const bool integrated : {false, true}) {
    const Results results =
        integrated ? simulate_ggl(system, output_times(200)) : run_kinematics(system, output_times(200));
    const s4::BeltArmAgreement err = s4::belt_arm_against_references(results);
    fmt::print("belt Q-manipulator ({}): |H - H_closed| {:.3e} m ({:.3e} l1); belt moment error {:.3e} N m of "
               "{:.4g} N m, pull error {:.3e} N; drift {:.3e} m ({:.3e} l1); equilibrium {:.3e}, energy {:.3e}\n",
               results.summary.method, err.path_m, err.path_m / kL1, err.moment_Nm, err.moment_scale_Nm, err.force_N,
               results.summary.max_drift_position_m, results.summary.max_drift_relative,
               results.summary.max_equilibrium_residual, results.summary.energy_balance_error);
    ASSERT_EQ(results.frames.size(), 201u);
    // (a) Reference: SPEC §4's H(P) (mech::QManipulator, i = 4) at the lever
    // angle of each frame; the multibody path differs by the constraints'
    // residual only: 1e-9 of l1 (s4::kBeltArmTolerance).
    EXPECT_LT(err.path_m, s4::kBeltArmTolerance * kL1);
    // (b) Reference: the hand kinetostatics of link 2 about A with the law's
    // P, P', P'' (s4::belt_arm_moment_on_link2): 1e-9 of the largest moment;
    // the pull is moment / r (1e-9 of the largest pull), the input's moment
    // -ratio times the output's.
    EXPECT_LT(err.moment_Nm, s4::kBeltArmTolerance * err.moment_scale_Nm);
    EXPECT_LT(err.force_N, s4::kBeltArmTolerance * err.moment_scale_Nm / kPulleyRadius);
    EXPECT_LT(err.input_moment_Nm, s4::kBeltArmTolerance * std::abs(kRatio) * err.moment_scale_Nm);
    // (c) Reference: the constraints hold, the belt's row (phi_21 = -4 phi_10)
    // among them: drift below 1e-8 of the link length.
    EXPECT_LT(results.summary.max_drift_position_m, 1e-8 * kL1);
    EXPECT_LT(err.row_rad * kL1, 1e-8 * kL1);
    // Reference: each body's d'Alembert balance with the belt's moments
    // (round-off of the index-1 solve, 1e-10 of the loads), and, integrated,
    // dT + dV = the motor's work alone (the belt does none), 1e-6 of the
    // energy as for the other driven runs (test_dynamics_slider_crank.cpp).
    EXPECT_LT(results.summary.max_equilibrium_residual, 1e-10);
    if (integrated) {
      EXPECT_LT(results.summary.energy_balance_error, 1e-6);
    }
  }
}

// The three-link chain of SPEC §4 (II.24): link 3 (l3) on link 2 at B, a
// second belt from link 1's pulley at A to link 3's at B carried by link 2.
// The source's i21 = 2, i32 = 1.5 are our ratios -2 and -1.5.
TEST(TransmissionQManipulator, ThreeLinksWithTwoBeltsTraceTheClosedFormOfII24) {
  const double l3 = 0.12, i21 = 2.0, i32 = 1.5;
  MultibodyModel m = s4::belt_arm_model();
  m.transmissions[0].ratio = -i21;
  m.bodies[2].point_masses.clear();
  m.bodies[2].points["B"] = {kL2, 0.0};
  Body link3;
  link3.name = "link3";
  link3.mass_kg = 0.5;
  link3.inertia_kgm2 = 0.5 * l3 * l3 / 12.0;
  link3.com_body = {0.5 * l3, 0.0};
  link3.pose = {kL1 + kL2, 0.0, 0.0};
  m.bodies.push_back(link3);
  m.joints.push_back(make_revolute("B", "link2", "B", "link3", "origin"));
  Transmission second;
  second.name = "belt2";
  second.input = {CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  second.output = {CoordinateType::Angle, "link2", "origin", "link3", "origin", {1, 0}};
  second.ratio = -i32;
  second.radius_m = 0.015;
  m.transmissions.push_back(second);
  const MultibodySystem system(m);
  const Results results = run_kinematics(system, output_times(100));
  const QManipulator closed_form = make_three_link_q_manipulator(kL1, kL2, l3, i21, i32);
  double worst = 0.0;
  for (const Frame& f : results.frames) {
    const BodyFrame& end = f.bodies.at(3);
    const Eigen::Vector2d h = end.q.head<2>() + Eigen::Rotation2Dd(end.q.z()) * Eigen::Vector2d(l3, 0.0);
    worst = std::max(worst, (h - closed_form.point_h(f.drives.at(0).s).p).norm());
  }
  fmt::print("three-link Q-manipulator (two belts): |H - H_closed(II.24)| {:.3e} m; drift {:.3e} of l1\n", worst,
             results.summary.max_drift_relative);
  // Reference: (II.24), H(P) = l1 e(P) + l2 e(P (1 - i21)) + l3 e(P (1 - i21 + i21 i32)), at each
  // frame's lever angle: 1e-9 of l1, as for two links.
  EXPECT_LT(worst, 1e-9 * kL1);
  EXPECT_LT(results.summary.max_drift_relative, 1e-8);
}

// The two-link arm without its motor, let go from rest stretched out along x:
// one DoF, the belt's row in the forward dynamics. Reference: the
// minimal-coordinate path (CVODES on link 1's angle) and the GGL path
// (IDAS) agree to 1e-6 (angles relative to the swing, belt moments relative
// to the peak), as the four-bar's free motion (test_dynamics_four_bar.cpp);
// H stays on SPEC §4's rose (1e-9 of l1) and the energy balances (a
// conservative run, the belt does no work: 1e-7 of the energy at the
// integrators' tolerances, as the slider-crank's, test_dynamics_slider_crank.cpp).
TEST(TransmissionQManipulator, FreeSwingUnderGravityAgreesOnBothPathsAndConservesEnergy) {
  MultibodyModel m = s4::belt_arm_model();
  m.motion_drives.clear();
  const MultibodySystem system(m);
  const std::vector<double> times = output_times(100);
  const Results ggl = simulate_ggl(system, times);
  const Results minimal =
      simulate_minimal(system, {CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}}, times);
  const QManipulator closed_form = make_two_link_q_manipulator(kL1, kL2, kSourceRatio);
  double swing = 0.0, angle_err = 0.0, moment_scale = 0.0, moment_err = 0.0, path = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const Frame &a = ggl.frames[k], &b = minimal.frames[k];
    swing = std::max(swing, std::abs(a.bodies[1].q.z()));
    for (int body = 1; body < 3; ++body) angle_err = std::max(angle_err, std::abs(a.bodies[body].q.z() - b.bodies[body].q.z()));
    moment_scale = std::max(moment_scale, std::abs(a.transmissions[0].moment_output_Nm));
    moment_err = std::max(moment_err, std::abs(a.transmissions[0].moment_output_Nm - b.transmissions[0].moment_output_Nm));
    for (const Frame* f : {&a, &b}) {
      const BodyFrame& link2 = f->bodies[2];
      const Eigen::Vector2d h = link2.q.head<2>() + Eigen::Rotation2Dd(link2.q.z()) * Eigen::Vector2d(kL2, 0.0);
      path = std::max(path, (h - closed_form.point_h(f->bodies[1].q.z()).p).norm());
    }
  }
  fmt::print("belt Q-manipulator free swing, IDAS vs CVODES: angles {:.2e} of the swing {:.3f} rad, belt moment "
             "{:.2e} of {:.4g} N m; |H - H_closed| {:.3e} m; energy {:.2e} / {:.2e}\n",
             angle_err / swing, swing, moment_err / moment_scale, moment_scale, path,
             ggl.summary.energy_balance_error, minimal.summary.energy_balance_error);
  EXPECT_GT(swing, 0.5);
  EXPECT_LT(angle_err / swing, 1e-6);
  EXPECT_LT(moment_err / moment_scale, 1e-6);
  EXPECT_LT(path, 1e-9 * kL1);
  EXPECT_LT(ggl.summary.max_drift_relative, 1e-8);
  EXPECT_LT(ggl.summary.energy_balance_error, 1e-7);
  EXPECT_LT(minimal.summary.energy_balance_error, 1e-7);
}

}  // namespace
}  // namespace kinetofem::mech
