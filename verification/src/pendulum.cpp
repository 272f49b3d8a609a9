#include "kinetofem/verification/pendulum.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace kinetofem::verification {

mech::MultibodyModel compound_pendulum(const Rod& rod, double amplitude_rad) {
  mech::MultibodyModel m;
  m.name = "compound pendulum";
  m.characteristic_length_m = rod.length_m;
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body bar;
  bar.name = "rod";
  bar.mass_kg = rod.mass_kg;
  bar.inertia_kgm2 = rod.inertia_about_centre();
  bar.com_body = {0.5 * rod.length_m, 0.0};
  bar.pose = {0.0, 0.0, -0.5 * std::numbers::pi + amplitude_rad};
  m.bodies = {ground, bar};
  m.joints.push_back(mech::make_revolute("pivot", "ground", "origin", "rod", "origin"));
  m.gravity = {0.0, -kPendulumGravity};
  return m;
}

double compound_pendulum_period_s(const Rod& rod, double amplitude_rad) {
  const double d = 0.5 * rod.length_m, inertia_pivot = rod.inertia_about_centre() + rod.mass_kg * d * d;
  return 4.0 * std::sqrt(inertia_pivot / (rod.mass_kg * kPendulumGravity * d)) *
         std::comp_ellint_1(std::sin(0.5 * amplitude_rad));
}

double period_from_half_swing(const mech::Frame& half) {
  return 2.0 * (half.t - half.q_dot(2) / half.q_ddot(2));
}

PendulumRun run_compound_pendulum(const Rod& rod, double amplitude_rad) {
  const mech::MultibodySystem system(compound_pendulum(rod, amplitude_rad));
  PendulumRun run;
  run.exact_period_s = compound_pendulum_period_s(rod, amplitude_rad);
  const double t = run.exact_period_s;
  run.results = mech::simulate_ggl(system, {0.0, 0.25 * t, 0.5 * t, t});
  run.computed_period_s = period_from_half_swing(run.results.frames.at(2));
  return run;
}

PendulumAgreement idas_vs_cvodes(const Rod& rod, double amplitude_rad) {
  const mech::MultibodySystem system(compound_pendulum(rod, amplitude_rad));
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(0.1 * k);
  PendulumAgreement agreement;
  agreement.ggl = mech::simulate_ggl(system, times);
  agreement.minimal = mech::simulate_minimal(
      system, {mech::CoordinateType::Angle, "ground", "origin", "rod", "origin", {1, 0}}, times);
  const std::size_t n = std::min(agreement.ggl.frames.size(), agreement.minimal.frames.size());
  for (std::size_t k = 0; k < n; ++k) {
    const mech::Frame& a = agreement.ggl.frames[k];
    const mech::Frame& b = agreement.minimal.frames[k];
    agreement.angle = std::max(agreement.angle, std::abs(a.q(2) - b.q(2)) / amplitude_rad);
    agreement.force = std::max(
        agreement.force, (a.joints.at(0).on_j.force_world - b.joints.at(0).on_j.force_world).norm() / rod.weight_n());
  }
  return agreement;
}

}  // namespace kinetofem::verification
