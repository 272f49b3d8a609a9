#include "kinetofem/verification/spec5_spherical.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace kinetofem::verification::spec5 {

double drive_work_J(const mech::SphericalDesign& d, const mech::StraightLineMotion& motion) {
  const std::vector<double> br = motion.breakpoints();
  double work = 0.0;
  for (std::size_t s = 0; s + 1 < br.size(); ++s) {
    const int n = 200;
    const double t0 = br[s], t1 = br[s + 1], h = (t1 - t0) / n;
    auto power = [&](double t) {
      // inside the segment, away from the jump
      const double tt = std::clamp(t, t0 + 1e-12 * (t1 - t0), t1 - 1e-12 * (t1 - t0));
      const mech::StraightLineMotion::Point p = motion.at(tt);
      return mech::spherical_inverse_dynamics(d, mech::spherical_joint_motion(d, p.m, p.m_dot, p.m_ddot))
          .total_power_W;
    };
    double sum = power(t0) + power(t1);
    for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * power(t0 + k * h);
    work += sum * h / 3.0;
  }
  return work;
}

double potential_energy_gain_J(const mech::SphericalDesign& d, double payload_kg, const Eigen::Vector3d& a,
                               const Eigen::Vector3d& b) {
  const Eigen::Vector3d qa = mech::spherical_inverse_kinematics(d, a), qb = mech::spherical_inverse_kinematics(d, b);
  auto z_s3 = [&](const Eigen::Vector3d& q) { return (q(2) - 0.5 * d.arm_length_m) * std::sin(q(1)); };
  return d.gravity_mps2 * (d.variant.m3_kg * (z_s3(qb) - z_s3(qa)) + payload_kg * (b.z() - a.z()));
}

WorkEnergyBalance work_energy_balance(char variant) {
  const mech::SphericalDesign d =
      mech::size_spherical_manipulator(mech::spherical_variant(variant), kWorkEnergyPayload_kg);
  const Eigen::Vector3d a(1.4, -0.7, 0.5), b(1.2, 0.8, 0.9);
  const mech::StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
  WorkEnergyBalance balance;
  balance.run = mech::analyse_straight_line(d, motion, 60);
  balance.duration_s = motion.duration();
  balance.work_J = drive_work_J(d, motion);
  balance.potential_gain_J = potential_energy_gain_J(d, kWorkEnergyPayload_kg, a, b);
  for (const auto& s : balance.run.samples) balance.scale_J = std::max(balance.scale_J, std::abs(s.total_power_W));
  balance.scale_J *= motion.duration();
  return balance;
}

}  // namespace kinetofem::verification::spec5
