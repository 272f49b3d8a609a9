// Dynamics verification on pendulums (dynamics.hpp, IDAS GGL and CVODES
// minimal-coordinate paths): period against the exact elliptic-integral value,
// agreement of the two paths, energy conservation, constraint drift and the
// d'Alembert equilibrium of each body.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <gtest/gtest.h>

#include "kinetofem/mechanisms/multibody/dynamics.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kG = 9.80665;

struct Rod {
  double mass = 2.0, length = 1.0;
  double inertia() const { return mass * length * length / 12.0; }
};

// A rod pinned at its body-frame origin to the ground origin, released from
// rest at amplitude `amplitude` from the downward vertical.
MultibodyModel compound_pendulum(const Rod& rod, double amplitude) {
  MultibodyModel m;
  m.name = "compound pendulum";
  m.characteristic_length_m = rod.length;
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body bar;
  bar.name = "rod";
  bar.mass_kg = rod.mass;
  bar.inertia_kgm2 = rod.inertia();
  bar.com_body = {0.5 * rod.length, 0.0};
  bar.pose = {0.0, 0.0, -0.5 * kPi + amplitude};
  m.bodies = {ground, bar};
  m.joints.push_back(make_revolute("pivot", "ground", "origin", "rod", "origin"));
  m.gravity = {0.0, -kG};
  return m;
}

TEST(DynamicsPendulum, PeriodMatchesEllipticIntegral) {
  const Rod rod;
  const double amplitude = 60.0 * kPi / 180.0;
  const MultibodySystem sys(compound_pendulum(rod, amplitude));
  // Reference: T = 4 sqrt(I_O / (m g d)) K(sin(amplitude/2)), d = l/2, I_O = m l^2/3.
  const double d = 0.5 * rod.length, inertia_pivot = rod.inertia() + rod.mass * d * d;
  const double period = 4.0 * std::sqrt(inertia_pivot / (rod.mass * kG * d)) * std::comp_ellint_1(std::sin(0.5 * amplitude));
  const Results res = simulate_ggl(sys, {0.0, 0.25 * period, 0.5 * period, period});
  const Frame& half = res.frames[2];
  // At T/2 the rod is at the other extreme: omega = 0. The zero crossing of omega
  // is at t* = T/2 - omega/alpha (one Newton step); 2 t* is the computed period.
  const double omega = half.q_dot(2), alpha = half.q_ddot(2);
  const double period_computed = 2.0 * (half.t - omega / alpha);
  std::printf("pendulum 60 deg: period %.12f s, exact (elliptic) %.12f s, rel. error %.2e\n%s", period_computed, period,
              period_computed / period - 1.0, res.format_checks().c_str());
  // Tolerance: IDAS relative tolerance 1e-10 -> period error ~1e-9 relative; 1e-7 allowed.
  EXPECT_NEAR(period_computed / period, 1.0, 1e-7) << res.format_checks();
  EXPECT_NEAR(half.q(2), -0.5 * kPi - amplitude, 1e-6);
  EXPECT_NEAR(res.frames.back().q(2), -0.5 * kPi + amplitude, 1e-6);
  // Issue 3 requirements: drift < 1e-8 of the characteristic length,
  // equilibrium < 1e-9, energy conserved (relative 1e-8 at tolerance 1e-10).
  EXPECT_LT(res.summary.max_drift_relative, 1e-8);
  EXPECT_LT(res.summary.max_equilibrium_residual, 1e-9);
  EXPECT_LT(res.summary.energy_balance_error, 1e-8) << res.format_checks();
  // Pivot reaction at the extreme (omega = 0): radial equilibrium gives
  // |F_radial| = m g cos(amplitude) along the rod (exact for omega = 0).
  const Reaction& on_rod = half.joints[0].on_j;
  EXPECT_NEAR(on_rod.force_body.x(), -rod.mass * kG * std::cos(amplitude), 1e-5);
  EXPECT_NEAR(on_rod.moment_Nm, 0.0, 1e-9);
}

TEST(DynamicsPendulum, IdasAndCvodesPathsAgree) {
  const Rod rod;
  const MultibodySystem sys(compound_pendulum(rod, 1.2));
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(0.1 * k);
  const Results ggl = simulate_ggl(sys, times);
  const Results minimal = simulate_minimal(sys, {CoordinateType::Angle, "ground", "origin", "rod", "origin", {1, 0}}, times);
  ASSERT_EQ(ggl.frames.size(), minimal.frames.size());
  double worst_angle = 0.0, worst_force = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    worst_angle = std::max(worst_angle, std::abs(ggl.frames[k].q(2) - minimal.frames[k].q(2)));
    const Eigen::Vector2d f1 = ggl.frames[k].joints[0].on_j.force_world, f2 = minimal.frames[k].joints[0].on_j.force_world;
    worst_force = std::max(worst_force, (f1 - f2).norm() / (rod.mass * kG));
  }
  std::printf("pendulum IDAS vs CVODES: angle %.2e rel, pivot force %.2e rel\n", worst_angle / 1.2, worst_force);
  // Issue 3: both paths agree to 1e-6 relative (amplitude 1.2 rad, weight m g).
  EXPECT_LT(worst_angle / 1.2, 1e-6) << ggl.format_checks() << minimal.format_checks();
  EXPECT_LT(worst_force, 1e-6);
  EXPECT_LT(minimal.summary.energy_balance_error, 1e-8);
}

// Double pendulum with a spring from a ground point to the second link's tip
// and (second case) a damper: conservative energy is constant; with damping the
// energy lost equals the damper's work.
MultibodyModel sprung_double_pendulum(double damping) {
  MultibodyModel m;
  m.name = "sprung double pendulum";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["anchor"] = {0.8, 0.3};
  Body l1;
  l1.name = "l1";
  l1.mass_kg = 1.5;
  l1.inertia_kgm2 = 1.5 / 12.0;
  l1.com_body = {0.5, 0.0};
  l1.points["tip"] = {1.0, 0.0};
  l1.pose = {0, 0, -1.2};
  Body l2 = l1;
  l2.name = "l2";
  l2.mass_kg = 1.0;
  l2.inertia_kgm2 = 1.0 / 12.0;
  l2.point_masses.push_back({"payload", 0.5, {1.0, 0.0}});
  l2.pose = {std::cos(-1.2), std::sin(-1.2), -0.4};
  l2.velocity = {0, 0, 1.0};
  m.bodies = {ground, l1, l2};
  m.joints.push_back(make_revolute("O", "ground", "origin", "l1", "origin"));
  m.joints.push_back(make_revolute("A", "l1", "tip", "l2", "origin"));
  m.springs.push_back({"spring", "ground", "anchor", "l2", "tip", 40.0, damping, 0.6});
  return m;
}

TEST(DynamicsPendulum, EnergyConservedAndDamperWorkBalances) {
  std::vector<double> times;
  for (int k = 0; k <= 15; ++k) times.push_back(0.1 * k);
  for (double damping : {0.0, 3.0}) {
    const MultibodySystem sys(sprung_double_pendulum(damping));
    const Results res = simulate_ggl(sys, times);
    // Reference: dT + dV = W_other (damper work, zero when conservative);
    // relative to the energy scale, at IDAS tolerance 1e-10.
    EXPECT_LT(res.summary.energy_balance_error, 1e-7) << "damping " << damping << "\n" << res.format_checks();
    EXPECT_LT(res.summary.max_drift_relative, 1e-8);
    EXPECT_LT(res.summary.max_equilibrium_residual, 1e-9);
    if (damping > 0.0) EXPECT_LT(res.frames.back().work_other_J, -1e-3);
    else EXPECT_EQ(res.frames.back().work_other_J, 0.0);
  }
}

}  // namespace
}  // namespace kinetofem::mech
