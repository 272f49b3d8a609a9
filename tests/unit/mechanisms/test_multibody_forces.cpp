// Forces and reactions of the multibody core: the moment a fixed joint
// carries and the body-frame components of a reaction (hand statics), and the
// force-drive laws (constant, DC motor, PD servo) with their work in the
// energy balance.
#include <cmath>
#include <memory>
#include <numbers>

#include <gtest/gtest.h>

#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kG = 9.81;

MultibodyModel one_body(double angle) {
  MultibodyModel m;
  m.name = "one body";
  m.gravity = {0.0, -kG};
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body bar;
  bar.name = "bar";
  bar.mass_kg = 2.0;
  bar.inertia_kgm2 = 2.0 / 12.0;
  bar.com_body = {0.5, 0.0};
  bar.pose = {0.0, 0.0, angle};
  m.bodies = {ground, bar};
  return m;
}

TEST(MultibodyForces, FixedJointCarriesTheMomentOfTheWeight) {
  const double angle = std::numbers::pi / 6;
  MultibodyModel m = one_body(angle);
  m.bodies[1].point_masses.push_back({"tool", 1.0, {1.0, 0.0}});
  m.joints.push_back(make_fixed("clamp", "ground", "origin", "bar", "origin"));
  const Frame f = run_kinematics(MultibodySystem(m), {0.0}).frames.front();
  const JointFrame& j = f.joints.front();
  // Hand statics: the clamp holds the weight 3 g and its moment about the
  // clamp, g cos(30 deg) (2*0.5 + 1*1.0), counter-clockwise.
  EXPECT_NEAR(j.on_j.force_world.x(), 0.0, 1e-12);
  EXPECT_NEAR(j.on_j.force_world.y(), 3.0 * kG, 1e-12);
  EXPECT_NEAR(j.on_j.moment_Nm, kG * std::cos(angle) * 2.0, 1e-12);
  // The same force in the bar's frame: rotated by -30 deg.
  EXPECT_NEAR(j.on_j.force_body.x(), 3.0 * kG * std::sin(angle), 1e-12);
  EXPECT_NEAR(j.on_j.force_body.y(), 3.0 * kG * std::cos(angle), 1e-12);
  // Action and reaction on the ground.
  EXPECT_NEAR((j.on_i.force_world + j.on_j.force_world).norm(), 0.0, 1e-12);
  EXPECT_NEAR(j.on_i.moment_Nm + j.on_j.moment_Nm, 0.0, 1e-12);
  EXPECT_LT(f.equilibrium_residual, 1e-15);
}

TEST(MultibodyForces, ForceDriveLawsAndTheirWork) {
  const auto reference = std::make_shared<CycloidalLaw>(0.8, 1.0);
  for (ForceLaw law : {ForceLaw::Constant, ForceLaw::DcMotor, ForceLaw::PdServo}) {
    MultibodyModel m = one_body(-0.5 * std::numbers::pi);
    m.joints.push_back(make_revolute("pivot", "ground", "origin", "bar", "origin"));
    ForceDrive drive;
    drive.name = "motor";
    drive.coordinate = {CoordinateType::Angle, "ground", "origin", "bar", "origin", {1, 0}};
    drive.law_type = law;
    drive.value = 6.0;
    drive.stall = 15.0;
    drive.no_load_speed = 4.0;
    drive.kp = 400.0;
    drive.kd = 30.0;
    drive.law = reference;
    m.force_drives.push_back(drive);
    const MultibodySystem sys(m);
    std::vector<double> times;
    for (int k = 0; k <= 12; ++k) times.push_back(0.1 * k);
    const Results res = simulate_ggl(sys, times);
    const Frame& f = res.frames.back();
    const DriveFrame& d = f.drives.front();
    // Each law's definition (model.hpp), evaluated on the frame's own state.
    double expected = drive.value;
    if (law == ForceLaw::DcMotor) expected = drive.stall * (1.0 - d.s_dot / drive.no_load_speed);
    if (law == ForceLaw::PdServo) {
      const MotionState r = reference->at(f.t);
      expected = drive.kp * (-0.5 * std::numbers::pi + r.s - d.s) + drive.kd * (r.s_dot - d.s_dot);
    }
    EXPECT_NEAR(d.effort, expected, 1e-12 * std::max(1.0, std::abs(expected)));
    EXPECT_NEAR(d.power_W, d.effort * d.s_dot, 1e-12 * std::max(1.0, std::abs(d.power_W)));
    // Energy balance: the motor's work is the change of kinetic + potential energy.
    EXPECT_NE(f.work_drives_J, 0.0);
    EXPECT_LT(res.summary.energy_balance_error, 1e-7) << res.format_checks();
  }
}

}  // namespace
}  // namespace kinetofem::mech
