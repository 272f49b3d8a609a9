// SPEC §5 spherical 3-DoF manipulator through the spatial multibody core
// (spatial/spherical_manipulator_model.hpp): absolute coordinates with Euler
// parameters, Lagrange multipliers, the index-1 solve, against the closed-form
// kinetostatics solved link by link from the gripper back to the base
// (mechanisms/src/spherical_manipulator.cpp). Two independent formulations of
// the same rigid-body problem: the drive efforts and all pair reactions (the
// 18 unknowns of SPEC §5) agree to round-off, and the drives' work is the
// energy the manipulator gains.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/spherical_manipulator_model.hpp"
#include "kinetofem/mechanisms/spherical_manipulator.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/verification/spec5_spherical.hpp"

namespace kinetofem::mech::spatial {
namespace {

using Eigen::Vector3d;

// Both sides are exact kinetostatics of the same motion: round-off (1e-9 of
// the largest value of each kind).
constexpr double kRoundOff = 1e-9;
// Constraint drift below 1e-8 of the arm length (the spatial core's stabilisation target, docs/multibody.md).
constexpr double kDrift = 1e-8;
constexpr double kPayload_kg = 20.0;

void print(const char* what, const ClosedFormComparison& c, const RunSummary& s, double arm_length) {
  std::printf("SPEC5 %s, spatial core vs closed form: M10d %.2e, M21d %.2e, F32d %.2e, reaction forces %.2e, "
              "reaction moments %.2e (tolerance %.0e); drift %.2e of the arm length %.4f m\n",
              what, c.drive(0), c.drive(1), c.drive(2), c.reaction_force, c.reaction_moment, kRoundOff,
              s.max_drift_relative, arm_length);
}

void expect_round_off(const ClosedFormComparison& c) {
  EXPECT_LT(c.drive(0), kRoundOff);
  EXPECT_LT(c.drive(1), kRoundOff);
  EXPECT_LT(c.drive(2), kRoundOff);
  EXPECT_LT(c.reaction_force, kRoundOff);
  EXPECT_LT(c.reaction_moment, kRoundOff);
}

// Rate of the mechanical energy from the bodies' motion alone (no
// multipliers): dE/dt = sum m v_c . (a_c - g) + w . (J_world alpha), the
// gyroscopic term w . (w x J w) being zero.
double energy_rate_W(const System& sys, const Frame& f) {
  double rate = 0.0;
  for (int b = 0; b < sys.n_bodies(); ++b) {
    if (sys.moving_index(b) < 0) continue;
    const EffectiveBody& e = sys.effective(b);
    const BodyState& s = f.bodies[b];
    const Eigen::Matrix3d j_world = s.rotation * e.inertia_kgm2 * s.rotation.transpose();
    rate += e.mass_kg * s.com_velocity.dot(s.com_acceleration - sys.model().gravity) +
            s.angular_velocity.dot(j_world * s.angular_acceleration);
  }
  return rate;
}

TEST(Spec5SpatialCore, VariantAEqualsTheClosedFormKinetostatics) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), kPayload_kg);
  // Rises 0.9 m, sweeps 55 deg of base rotation and 0.4 m of reach: every
  // drive works (inside A's zone, checked at every frame below).
  const Vector3d a(1.3, -1.0, 0.3), b(1.9, 0.6, 1.2);
  const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
  const System sys(spherical_manipulator_model(d, motion));
  ASSERT_EQ(sys.n_constraints(), 18);  // 5 + 5 + 5 joint rows and 3 drive rows: 6 x 3 coordinates
  const Results run = run_kinematics(sys, equally_spaced_times(motion.duration(), 101));

  const ClosedFormComparison c = compare_with_closed_form(d, motion, run);
  print("A, 20 kg, 101 frames", c, run.summary, d.arm_length_m);
  std::printf("%s", run.format_checks().c_str());
  expect_round_off(c);
  // The same against the closed form of the design as modelled (the slender
  // bars' axial inertia made positive): the formulations alone.
  const ClosedFormComparison same = compare_with_closed_form(as_modelled(d), motion, run);
  print("A, against the design as modelled", same, run.summary, d.arm_length_m);
  expect_round_off(same);
  EXPECT_LT(run.summary.max_drift_relative, kDrift);
  EXPECT_EQ(run.summary.redundant_rows, 0);

  // The drives hold the closed-form joint motion; M stays on the line.
  double joint_error = 0.0, path_error = 0.0, peak_power = 0.0, power_error = 0.0;
  for (const Frame& f : run.frames) {
    const StraightLineMotion::Point p = motion.at(f.t);
    const SphericalJointMotion cf = spherical_joint_motion(d, p.m, p.m_dot, p.m_ddot);
    check_service_zone(d, cf.q, f.t);
    const SphericalDynamics s = spherical_dynamics(f);
    joint_error = std::max({joint_error, (s.joints.q - cf.q).cwiseAbs().maxCoeff(),
                            (s.joints.qd - cf.qd).cwiseAbs().maxCoeff(), (s.joints.qdd - cf.qdd).cwiseAbs().maxCoeff()});
    path_error = std::max(path_error, (sys.point_world(sys.body_index("arm"), "M", f.q) - p.m).norm());
    // Exact energy balance at every frame: the drives' power (efforts from the
    // multipliers) is the rate of T + V (from the bodies' motion).
    peak_power = std::max(peak_power, std::abs(s.total_power_W));
    power_error = std::max(power_error, std::abs(s.total_power_W - energy_rate_W(sys, f)));
  }
  std::printf("SPEC5 A: joint motion vs closed form %.2e, |M - M_planned| %.2e m, power balance %.2e of the peak "
              "power %.1f W\n",
              joint_error, path_error, power_error / peak_power, peak_power);
  EXPECT_LT(joint_error, kRoundOff);
  EXPECT_LT(path_error, kDrift * d.arm_length_m);
  EXPECT_LT(power_error, verification::spec5::kWorkEnergyTolerance * peak_power);
}

// The drives' work over the whole motion (composite Simpson of the spatial
// core's drive power on each segment of the trapezoidal law, where it is
// smooth) is the energy gained: T = 0 at both ends (rest to rest), so the
// potential energy of the arm and payload (the closed form's
// potential_energy_gain_J). Tolerance as the closed-form test.
TEST(Spec5SpatialCore, VariantADriveWorkEqualsTheEnergyGained) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), kPayload_kg);
  const Vector3d a(1.3, -1.0, 0.3), b(1.9, 0.6, 1.2);
  const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
  const System sys(spherical_manipulator_model(d, motion));
  const std::vector<double> breaks = motion.breakpoints();
  const int n = 100;  // Simpson intervals per segment (even)
  std::vector<double> times;
  for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
    // Just inside the segment: the efforts jump at its ends.
    const double t0 = breaks[s], t1 = breaks[s + 1], inset = 1e-12 * (t1 - t0);
    for (int k = 0; k <= n; ++k) times.push_back(std::clamp(t0 + (t1 - t0) * k / n, t0 + inset, t1 - inset));
  }
  const Results run = run_kinematics(sys, times);
  double work = 0.0, peak_power = 0.0;
  for (std::size_t s = 0; s + 1 < breaks.size(); ++s) {
    const double h = (breaks[s + 1] - breaks[s]) / n;
    double sum = 0.0;
    for (int k = 0; k <= n; ++k) {
      const double p = spherical_dynamics(run.frames[s * (n + 1) + k]).total_power_W;
      peak_power = std::max(peak_power, std::abs(p));
      sum += (k == 0 || k == n ? 1.0 : (k % 2 ? 4.0 : 2.0)) * p;
    }
    work += sum * h / 3.0;
  }
  const Frame &first = run.frames.front(), &last = run.frames.back();
  const double gained = last.kinetic_energy_J + last.potential_energy_J - first.kinetic_energy_J -
                        first.potential_energy_J;
  const double potential = verification::spec5::potential_energy_gain_J(d, kPayload_kg, a, b);
  const double scale = peak_power * motion.duration();
  std::printf("SPEC5 A, spatial core: drive work %.9f J, T + V gained %.9f J, closed-form potential gain %.9f J; "
              "differences %.2e, %.2e of %.1f J (tolerance %.0e)\n",
              work, gained, potential, std::abs(work - gained) / scale, std::abs(work - potential) / scale, scale,
              verification::spec5::kWorkEnergyTolerance);
  EXPECT_NEAR(work, gained, verification::spec5::kWorkEnergyTolerance * scale);
  EXPECT_NEAR(work, potential, verification::spec5::kWorkEnergyTolerance * scale);
  EXPECT_LT(run.summary.max_drift_relative, kDrift);
}

TEST(Spec5SpatialCore, VariantsBToEEqualTheClosedFormKinetostatics) {
  // The line of the closed-form work-energy check, inside every variant's zone.
  const Vector3d a(1.4, -0.7, 0.5), b(1.2, 0.8, 0.9);
  for (char name : {'B', 'C', 'D', 'E'}) {
    const SphericalDesign d = size_spherical_manipulator(spherical_variant(name), kPayload_kg);
    const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
    (void)analyse_straight_line(d, motion, 40);  // throws if the line leaves the zone
    const System sys(spherical_manipulator_model(d, motion));
    const Results run = run_kinematics(sys, equally_spaced_times(motion.duration(), 41));
    const ClosedFormComparison c = compare_with_closed_form(d, motion, run);
    const char what[] = {name, '\0'};
    print(what, c, run.summary, d.arm_length_m);
    SCOPED_TRACE(what);
    expect_round_off(c);
    EXPECT_LT(run.summary.max_drift_relative, kDrift);
  }
}

// From no payload to one heavier than the arm: the slender bars' axial
// inertia stays a small fraction of the payload-laden transverse one.
TEST(Spec5SpatialCore, PayloadsFromNoneToHeavy) {
  const Vector3d a(1.3, -1.0, 0.3), b(1.9, 0.6, 1.2);
  for (double payload : {0.0, 100.0, 500.0, 2000.0}) {
    const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), payload);
    const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
    const Results run = run_kinematics(System(spherical_manipulator_model(d, motion)),
                                       equally_spaced_times(motion.duration(), 41));
    const ClosedFormComparison c = compare_with_closed_form(d, motion, run);
    const std::string what = fmt::format("A, payload {} kg", payload);
    print(what.c_str(), c, run.summary, d.arm_length_m);
    SCOPED_TRACE(what);
    expect_round_off(c);
  }
}

// With axial inertias of sleeve and arm (the closed form takes them too), the
// axial and gyroscopic terms of both formulations are in play: the arm turns
// about its own axis at phi10' sin(phi21).
TEST(Spec5SpatialCore, AxialInertiasEnterBothFormulationsAlike) {
  SphericalDesign d = size_spherical_manipulator(spherical_variant('C'), 5.0);
  d.arm_inertia_axial = 0.5 * d.variant.m3_kg * std::pow(0.25 * d.sleeve_diameter_m, 2);   // a bar of d2 / 2
  d.sleeve_inertia_axial = d.variant.m2_kg * std::pow(0.5 * d.sleeve_diameter_m, 2);      // a thin tube of d2
  const Vector3d a(1.0, -1.1, 0.4), b(1.5, 0.7, 1.1);
  const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
  (void)analyse_straight_line(d, motion, 40);
  const Results run = run_kinematics(System(spherical_manipulator_model(d, motion)),
                                     equally_spaced_times(motion.duration(), 61));
  const ClosedFormComparison c = compare_with_closed_form(d, motion, run);
  print("C with axial inertias", c, run.summary, d.arm_length_m);
  expect_round_off(c);
  // And the axial inertias matter at this tolerance: the closed form without
  // them differs (the comparison can fail).
  SphericalDesign slender = d;
  slender.arm_inertia_axial = slender.sleeve_inertia_axial = 0.0;
  const ClosedFormComparison without = compare_with_closed_form(slender, motion, run);
  std::printf("SPEC5 C: against the closed form without axial inertias: largest difference %.2e\n", without.largest());
  EXPECT_GT(without.largest(), 1e3 * kRoundOff);
}

// The comparison is sharp: a closed form with 1 % more payload than the model
// is told apart by orders of magnitude.
TEST(Spec5SpatialCore, ComparisonTellsADifferentPayloadApart) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), kPayload_kg);
  const StraightLineMotion motion({1.3, -1.0, 0.3}, {1.9, 0.6, 1.2}, d.variant.speed_mps, d.variant.k_accel,
                                  d.variant.k_decel);
  const Results run = run_kinematics(System(spherical_manipulator_model(d, motion)),
                                     equally_spaced_times(motion.duration(), 21));
  const SphericalDesign heavier = size_spherical_manipulator(spherical_variant('A'), 1.01 * kPayload_kg);
  const ClosedFormComparison c = compare_with_closed_form(heavier, motion, run);
  std::printf("SPEC5 A: against a closed form with 1%% more payload: largest difference %.2e\n", c.largest());
  EXPECT_GT(c.largest(), 1e-4);
}

// The model's names and frames, which a later stage attaches FE parts to.
TEST(Spec5SpatialCore, ModelNamesAndBodyFrames) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), kPayload_kg);
  const Vector3d a(1.3, -1.0, 0.3);
  const StraightLineMotion motion(a, {1.9, 0.6, 1.2}, 1.0, 0.25, 0.25);
  const System sys(spherical_manipulator_model(d, motion));
  const Results run = run_kinematics(sys, {0.0});
  const Frame& f = run.frames.front();
  const Vector3d q = spherical_inverse_kinematics(d, a);
  const double c1 = std::cos(q(0)), s1 = std::sin(q(0)), c2 = std::cos(q(1)), s2 = std::sin(q(1));
  const Vector3d e_r(c2 * c1, c2 * s1, s2), e_phi(-s1, c1, 0.0), zb(0.0, 0.0, d.variant.height_b_m);
  const BodyState& column = f.bodies[sys.body_index("column")];
  const BodyState& sleeve = f.bodies[sys.body_index("sleeve")];
  const BodyState& arm = f.bodies[sys.body_index("arm")];
  EXPECT_LT(column.origin.norm(), 1e-12);
  EXPECT_LT((column.rotation.col(2) - Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_LT((column.rotation.col(0) - Vector3d(c1, s1, 0.0)).norm(), 1e-12);
  EXPECT_LT((sleeve.origin - zb).norm(), 1e-12);
  EXPECT_LT((sleeve.rotation.col(0) - e_r).norm(), 1e-12);
  EXPECT_LT((sleeve.rotation.col(1) - e_phi).norm(), 1e-12);
  EXPECT_LT((arm.origin - (zb + (q(2) - d.arm_length_m) * e_r)).norm(), 1e-12);
  EXPECT_LT((arm.rotation - sleeve.rotation).norm(), 1e-12);
  EXPECT_LT((sys.point_world(sys.body_index("arm"), "M", f.q) - a).norm(), 1e-12);
  EXPECT_LT((sys.point_world(sys.body_index("arm"), "S3", f.q) - (zb + (q(2) - 0.5 * d.arm_length_m) * e_r)).norm(),
            1e-12);
  EXPECT_NEAR(sys.effective(sys.body_index("arm")).mass_kg, d.variant.m3_kg + kPayload_kg, 1e-12);
  for (const char* name : {"pair_10", "pair_21", "pair_32", "M10d", "M21d", "F32d"}) EXPECT_NO_THROW(sys.block(name));
  EXPECT_NEAR(f.drives[0].s, q(0), 1e-12);
  EXPECT_NEAR(f.drives[1].s, q(1), 1e-12);
  EXPECT_NEAR(f.drives[2].s, q(2), 1e-12);
}

}  // namespace
}  // namespace kinetofem::mech::spatial
