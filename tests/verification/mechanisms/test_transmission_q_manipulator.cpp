// SPEC §4's two-link Q-manipulator built in the planar multibody core: links
// 1 and 2 (l1 = l2 = 0.2 m) on revolute joints O and A, a belt from the
// frame's pulley to link 2's pulley carried by link 1 (a Transmission with
// ratio -4: the source's i = 4, phi_21 = -i phi_10), a payload at H, link 1
// driven through a full turn by a polynomial 3-4-5 law, gravity -y.
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
#include <memory>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/motion_law_factory.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/q_manipulator.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kL1 = 0.2, kL2 = 0.2;        // m, SPEC §4 / cases/mechanisms/q_manipulator_rose
constexpr double kSourceRatio = 4.0;          // the source's i (phi_21 = -i phi_10)
constexpr double kRatio = -kSourceRatio;      // ours (phi_21 = ratio phi_10)
constexpr double kPulleyRadius = 0.02;        // m, link 2's pulley
constexpr double kM1 = 2.0, kM2 = 1.5, kPayload = 3.0;  // kg
const Eigen::Vector2d kCom2{0.1, 0.012};      // link 2's bare centre of mass (off its axis on purpose), m
const double kJ1 = kM1 * kL1 * kL1 / 12.0, kJ2 = kM2 * kL2 * kL2 / 12.0;  // kg m^2
const Eigen::Vector2d kGravity{0.0, -9.80665};
constexpr double kDuration = 2.0;             // s

std::shared_ptr<const MotionLaw> lever_law() {
  MotionLawSpec spec;
  spec.law = "polynomial345";
  spec.stroke = 2.0 * std::numbers::pi;
  spec.duration_s = kDuration;
  return make_motion_law(spec);
}

MultibodyModel belt_q_manipulator() {
  MultibodyModel m;
  m.name = "belt Q-manipulator";
  m.characteristic_length_m = kL1;
  m.gravity = kGravity;
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body link1;
  link1.name = "link1";
  link1.mass_kg = kM1;
  link1.inertia_kgm2 = kJ1;
  link1.com_body = {0.5 * kL1, 0.0};
  link1.points["A"] = {kL1, 0.0};
  Body link2;
  link2.name = "link2";
  link2.mass_kg = kM2;
  link2.inertia_kgm2 = kJ2;
  link2.com_body = kCom2;
  link2.points["H"] = {kL2, 0.0};
  link2.point_masses.push_back({"payload", kPayload, {kL2, 0.0}});
  link2.pose = {kL1, 0.0, 0.0};
  m.bodies = {ground, link1, link2};
  m.joints.push_back(make_revolute("O", "ground", "origin", "link1", "origin"));
  m.joints.push_back(make_revolute("A", "link1", "A", "link2", "origin"));
  MotionDrive lever;
  lever.name = "lever";
  lever.coordinate = {CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  lever.law = lever_law();
  m.motion_drives.push_back(lever);
  Transmission belt;
  belt.name = "belt";
  belt.input = {CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  belt.output = {CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  belt.ratio = kRatio;
  belt.radius_m = kPulleyRadius;
  m.transmissions.push_back(belt);
  return m;
}

std::vector<double> output_times(int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(kDuration * k / n);
  return t;
}

Eigen::Vector2d e(double angle) { return {std::cos(angle), std::sin(angle)}; }
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Hand kinetostatics of link 2 (docs/transmissions.md): the moment the belt
// applies to link 2 at lever angle P(t) with its rates, from link 2's moment
// equation about the pin A (its pin force has no moment there).
double belt_moment_on_link2(const MotionState& lever) {
  const double k2 = 1.0 + kRatio;  // theta_2 = (1 + ratio) P = (1 - i) P
  const double th1 = lever.s, w1 = lever.s_dot, a1 = lever.s_ddot;
  const double th2 = k2 * th1, w2 = k2 * w1, a2 = k2 * a1;
  const Eigen::Vector2d acc_a = kL1 * (a1 * perp(e(th1)) - w1 * w1 * e(th1));
  const Eigen::Matrix2d rot = Eigen::Rotation2Dd(th2).toRotationMatrix();
  double moment = kJ2 * a2;
  for (const auto& [mass, at_body] : {std::pair{kM2, kCom2}, std::pair{kPayload, Eigen::Vector2d(kL2, 0.0)}}) {
    const Eigen::Vector2d rho = rot * at_body;
    const Eigen::Vector2d acc = acc_a + a2 * perp(rho) - w2 * w2 * rho;
    moment += cross(rho, mass * (acc - kGravity));
  }
  return moment;
}

struct Errors {
  double path_m = 0.0, moment_nm = 0.0, force_n = 0.0, input_moment_nm = 0.0, row_rad = 0.0;
  double moment_scale_nm = 0.0;
};

Errors compare(const Results& results) {
  const QManipulator closed_form = make_two_link_q_manipulator(kL1, kL2, kSourceRatio);
  const auto law = lever_law();
  Errors err;
  for (const Frame& f : results.frames) {
    const double p = f.drives.at(0).s;
    const BodyFrame& link2 = f.bodies.at(2);
    const Eigen::Vector2d h = link2.q.head<2>() + Eigen::Rotation2Dd(link2.q.z()) * Eigen::Vector2d(kL2, 0.0);
    err.path_m = std::max(err.path_m, (h - closed_form.point_h(p).p).norm());
    const TransmissionFrame& belt = f.transmissions.at(0);
    const double reference = belt_moment_on_link2(law->at(f.t));
    err.moment_scale_nm = std::max(err.moment_scale_nm, std::abs(reference));
    err.moment_nm = std::max(err.moment_nm, std::abs(belt.moment_output_Nm - reference));
    err.force_n = std::max(err.force_n, std::abs(belt.force_N - reference / kPulleyRadius));
    err.input_moment_nm = std::max(err.input_moment_nm, std::abs(belt.moment_input_Nm + kRatio * reference));
    err.row_rad = std::max(err.row_rad, std::abs(belt.s_out - kRatio * belt.s_in));
  }
  return err;
}

TEST(TransmissionQManipulator, PathOfHIsSpec4sRoseAndTheBeltMomentIsTheHandKinetostatics) {
  const MultibodySystem system(belt_q_manipulator());
  for (const bool integrated : {false, true}) {
    const Results results =
        integrated ? simulate_ggl(system, output_times(200)) : run_kinematics(system, output_times(200));
    const Errors err = compare(results);
    fmt::print("belt Q-manipulator ({}): |H - H_closed| {:.3e} m ({:.3e} l1); belt moment error {:.3e} N m of "
               "{:.4g} N m, pull error {:.3e} N; drift {:.3e} m ({:.3e} l1); equilibrium {:.3e}, energy {:.3e}\n",
               results.summary.method, err.path_m, err.path_m / kL1, err.moment_nm, err.moment_scale_nm, err.force_n,
               results.summary.max_drift_position_m, results.summary.max_drift_relative,
               results.summary.max_equilibrium_residual, results.summary.energy_balance_error);
    ASSERT_EQ(results.frames.size(), 201u);
    // (a) Reference: SPEC §4's H(P) (mech::QManipulator, i = 4) at the lever
    // angle of each frame; the multibody path differs by the constraints'
    // residual only: 1e-9 of l1.
    EXPECT_LT(err.path_m, 1e-9 * kL1);
    // (b) Reference: the hand kinetostatics of link 2 about A with the law's
    // P, P', P'' (belt_moment_on_link2): 1e-9 of the largest moment; the pull
    // is moment / r (1e-9 of the largest pull), the input's moment -i times
    // the output's.
    EXPECT_LT(err.moment_nm, 1e-9 * err.moment_scale_nm);
    EXPECT_LT(err.force_n, 1e-9 * err.moment_scale_nm / kPulleyRadius);
    EXPECT_LT(err.input_moment_nm, 1e-9 * std::abs(kRatio) * err.moment_scale_nm);
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
  MultibodyModel m = belt_q_manipulator();
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
  MultibodyModel m = belt_q_manipulator();
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
