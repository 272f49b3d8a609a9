#include "kinetofem/verification/lever_chain_multibody.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"

namespace kinetofem::verification {

mech::MultibodyModel lever_chain_example_model(std::shared_ptr<const mech::MotionLaw> law, double arm_mass_kg,
                                               const Eigen::Vector2d& gravity_m_s2) {
  const mech::LeverChainGeometry g = spec1::example_geometry();
  mech::ManipulatorDefinition d;
  d.type = mech::ManipulatorType::LeverChain;
  d.geometry = g;
  d.lever = {8.0, {0.0, 0.5 * g.a_m}, 8.0 * g.a_m * g.a_m / 12.0};
  d.arm = {arm_mass_kg, {-0.5 * g.c_m, 0.0}, arm_mass_kg * g.c_m * g.c_m / 12.0};
  d.gripper_mass_kg = 0.0;
  d.casting_mass_kg = 2.0;
  d.gravity_m_s2 = gravity_m_s2;
  d.lever_motion = std::move(law);
  return mech::make_manipulator_model(d);
}

ClosedFormAgreement lever_chain_multibody_vs_closed_form() {
  const mech::LeverChainGeometry g = spec1::example_geometry();
  const mech::LeverChain closed_form(g);
  ClosedFormAgreement agreement;
  for (double stroke_deg : {85.0, -72.0}) {
    const mech::MultibodySystem system(
        lever_chain_example_model(std::make_shared<mech::Polynomial345Law>(stroke_deg * units::kDeg, 1.0)));
    mech::KinematicOptions options;
    options.slack_is_error = false;  // positions only
    std::vector<double> times;
    for (int k = 0; k <= 60; ++k) times.push_back(k / 60.0);
    const mech::Results res = mech::run_kinematics(system, times, options);
    for (const mech::Frame& f : res.frames) {
      const double dphi = f.bodies.at(1).q.z();
      const mech::LeverChainPose ref = closed_form.pose(dphi);
      agreement.worst_angle_rad =
          std::max(agreement.worst_angle_rad, std::abs(f.bodies.at(2).q.z() - dphi - ref.ctm.dpsi_rad));
      const Eigen::Vector3d arm = f.bodies.at(2).q;
      const Eigen::Rotation2Dd rot(arm.z());
      const Eigen::Vector2d c = arm.head<2>() + rot * Eigen::Vector2d(-g.c_m, 0.0);
      const Eigen::Vector2d h = arm.head<2>() + rot * Eigen::Vector2d(-g.c_m, g.h_m);
      agreement.worst_point_m = std::max({agreement.worst_point_m, (c - ref.c.p).norm(), (h - ref.h.p).norm()});
    }
    agreement.max_equilibrium_residual =
        std::max(agreement.max_equilibrium_residual, res.summary.max_equilibrium_residual);
  }
  return agreement;
}

}  // namespace kinetofem::verification
