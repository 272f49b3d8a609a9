// The extractor's rotary gripper module on the SPEC §1 lever-chain
// manipulator (spatial/rotary_module.hpp): the manipulator of the bundled case
// lifted into the spatial core (from_planar), the gripper (20 kg) on a
// revolute about the arm's axis at H, the casting (15 kg) held 120 mm below
// the axis; the lever turns 80 deg in 2 s, then the gripper turns the casting
// 90 deg about the arm in 1 s (a cycloidal law), out of the mechanism's plane.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/from_planar.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/rotary_module.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"

namespace kinetofem::mech {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kGripperKg = 20.0, kCastingKg = 15.0, kStroke = 2.0, kTurn = 1.0;

const Matrix3d kGripperInertia = Vector3d(0.30, 0.20, 0.25).asDiagonal();  // arm axes at the start, kg m^2
const Matrix3d kCastingInertia = Vector3d(0.05, 0.04, 0.06).asDiagonal();
const Vector3d kCastingOffset(0.0, -0.12, 0.0);  // from H, the module's (= the arm's) axes at the start, m

// The bundled lever-chain manipulator (rod links as in
// test_spatial_planar_equivalence.cpp) with `gripper_kg` and `casting_kg` at H
// and the arm's centroidal inertia raised by `extra_arm_inertia`.
MultibodyModel lever_chain(double gripper_kg, double casting_kg, double extra_arm_inertia) {
  const LeverChainGeometry g = verification::spec1::example_geometry();
  ManipulatorDefinition d;
  d.type = ManipulatorType::LeverChain;
  d.geometry = g;
  d.lever = {8.0, {0.0, 0.5 * g.a_m}, 8.0 * g.a_m * g.a_m / 12.0};
  d.arm = {5.0, {-0.5 * g.c_m, 0.0}, 5.0 * g.c_m * g.c_m / 12.0 + extra_arm_inertia};
  d.gripper_mass_kg = gripper_kg;
  d.casting_mass_kg = casting_kg;
  d.lever_motion = std::make_shared<Polynomial345Law>(80 * kDeg, kStroke);
  return make_manipulator_model(d);
}

spatial::RotaryModule rotary_module() {
  spatial::RotaryModule m;
  m.carrier = manipulator::kArm;
  m.mount_point = manipulator::kPointH;
  m.axis_carrier = -Vector3d::UnitX();  // the arm's axis, from A towards C
  m.mass_kg = kGripperKg;
  m.inertia_kgm2 = kGripperInertia;
  m.payload = {"casting", kCastingKg, kCastingOffset, kCastingInertia};
  m.angle = std::make_shared<DelayedLaw>(std::make_shared<CycloidalLaw>(90 * kDeg, kTurn), kStroke);
  return m;
}

std::vector<double> output_times() {
  std::vector<double> t;
  for (int k = 0; k <= 60; ++k) t.push_back((kStroke + kTurn) * k / 60);
  return t;
}

const spatial::Results& with_module() {
  static const spatial::Results run = [] {
    const spatial::Model model = spatial::with_rotary_module(spatial::from_planar(lever_chain(0.0, 0.0, 0.0)),
                                                             rotary_module());
    return spatial::run_kinematics(spatial::System(model), output_times());
  }();
  return run;
}

int index_of(const std::vector<spatial::DriveState>& drives, const std::string& name) {
  for (std::size_t k = 0; k < drives.size(); ++k)
    if (drives[k].name == name) return int(k);
  return -1;
}

TEST(SpatialRotaryModule, BeforeTheTurnTheManipulatorIsThePlanarOneWithARigidPayload) {
  // Reference: the planar core with the gripper at H and the casting at
  // H + offset as point masses and their rotary inertias about z added to the
  // arm's (they turn with it until the module turns): lever drive torque and
  // chain tension, 1e-9 of their largest values.
  MultibodyModel planar = lever_chain(0.0, 0.0, kGripperInertia(2, 2) + kCastingInertia(2, 2));
  for (Body& b : planar.bodies)
    if (b.name == manipulator::kArm) {
      const Eigen::Vector2d h = b.points.at(manipulator::kPointH);
      b.point_masses.push_back({"gripper", kGripperKg, h});
      b.point_masses.push_back({"casting", kCastingKg, h + kCastingOffset.head<2>()});
    }
  const Results reference = run_kinematics(MultibodySystem(planar), output_times());
  const spatial::Results& run = with_module();
  const int lever = index_of(run.frames.front().drives, manipulator::kLeverDrive);
  ASSERT_GE(lever, 0);
  double torque = 0, torque_scale = 0, tension = 0, tension_scale = 0;
  for (std::size_t k = 0; k < run.frames.size(); ++k) {
    if (run.frames[k].t > kStroke + 1e-12) break;
    const double planar_torque = reference.frames[k].drives.at(0).effort;
    torque = std::max(torque, std::abs(run.frames[k].drives[std::size_t(lever)].effort - planar_torque));
    torque_scale = std::max(torque_scale, std::abs(planar_torque));
    const double planar_tension = reference.frames[k].chains.at(0).tension_N;
    for (const spatial::JointState& j : run.frames[k].joints)
      if (j.name == manipulator::kChain) {
        const double spatial_tension = j.on_j.force_world.norm();
        tension = std::max(tension, std::abs(spatial_tension - planar_tension));
      }
    tension_scale = std::max(tension_scale, std::abs(planar_tension));
  }
  EXPECT_LT(torque / torque_scale, 1e-9);
  EXPECT_LT(tension / tension_scale, 1e-9);
}

TEST(SpatialRotaryModule, TheTurnsTorqueIsTheRigidRotationAboutAFixedAxis) {
  // During the turn the lever dwells (its 3-4-5 law ends at rest), so the
  // arm is still and the module turns about a fixed axis h through H:
  //   T = I_h theta'' - ((r_c - r_H) x m_c g) . h,
  //   I_h = h.J_g h + h.J_c h + m_c |(r_c - r_H) x h|^2,
  // J_g, J_c in world axes (the parts of h.J h about the axis do not change
  // as they turn about it). Reference: this closed form, 1e-9 of the peak
  // torque. The arm takes -T about its axis from the drive and nothing about
  // it from the joint: its torsion.
  const spatial::Results& run = with_module();
  const spatial::RotaryModule module = rotary_module();
  const int drive = index_of(run.frames.front().drives, spatial::rotary_drive_name(module));
  ASSERT_GE(drive, 0);
  const Vector3d g(0.0, -9.80665, 0.0);
  double worst = 0, peak = 0, torsion = 0, joint_about_axis = 0;
  int frames_in_turn = 0;
  for (const spatial::Frame& f : run.frames) {
    if (f.t <= kStroke + 1e-12) continue;
    ++frames_in_turn;
    const spatial::BodyState& arm = *std::find_if(f.bodies.begin(), f.bodies.end(),
                                                  [](const auto& b) { return b.name == manipulator::kArm; });
    const spatial::BodyState& gripper = *std::find_if(f.bodies.begin(), f.bodies.end(),
                                                      [&](const auto& b) { return b.name == module.name; });
    ASSERT_LT(arm.angular_velocity.norm() + arm.angular_acceleration.norm(), 1e-9);  // at rest, to round-off
    const Vector3d h = arm.rotation * module.axis_carrier.normalized();
    const Vector3d r = gripper.rotation * kCastingOffset;  // casting from H (the module's origin)
    const Matrix3d Jg = gripper.rotation * kGripperInertia * gripper.rotation.transpose();
    const Matrix3d Jc = gripper.rotation * kCastingInertia * gripper.rotation.transpose();
    const double inertia = h.dot(Jg * h) + h.dot(Jc * h) + kCastingKg * r.cross(h).squaredNorm();
    const double theta_ddot = module.angle->at(f.t).s_ddot;
    const double closed_form = inertia * theta_ddot - r.cross(kCastingKg * g).dot(h);
    const spatial::DriveState& d = f.drives[std::size_t(drive)];
    worst = std::max(worst, std::abs(d.effort - closed_form));
    peak = std::max(peak, std::abs(closed_form));
    torsion = std::max(torsion, std::abs(d.on_i.moment_world.dot(h) + d.effort));
    for (const spatial::JointState& j : f.joints)
      if (j.name == spatial::rotary_joint_name(module))
        joint_about_axis = std::max(joint_about_axis, std::abs(j.on_i.moment_world.dot(h)));
  }
  EXPECT_GE(frames_in_turn, 15);
  EXPECT_GT(peak, 1.0);
  EXPECT_LT(worst / peak, 1e-9);
  EXPECT_LT(torsion / peak, 1e-9);
  EXPECT_LT(joint_about_axis / peak, 1e-9);
  // The casting ends 90 deg round the arm: out of the mechanism's plane.
  const spatial::Frame& last = run.frames.back();
  const auto gripper = std::find_if(last.bodies.begin(), last.bodies.end(),
                                    [&](const auto& b) { return b.name == module.name; });
  EXPECT_NEAR(std::abs((gripper->rotation * kCastingOffset).z()), 0.12, 1e-9);
}

TEST(SpatialRotaryModule, AModuleWithoutADriveOrCarrierIsAnErrorNamingIt) {
  const spatial::Model base = spatial::from_planar(lever_chain(0.0, 0.0, 0.0));
  spatial::RotaryModule no_drive = rotary_module();
  no_drive.angle = nullptr;
  spatial::RotaryModule no_carrier = rotary_module();
  no_carrier.carrier = "boom";
  spatial::RotaryModule zero_axis = rotary_module();
  zero_axis.axis_carrier = Vector3d::Zero();
  for (const auto& [module, text] : {std::pair{no_drive, "needs a drive"}, std::pair{no_carrier, "no body 'boom'"},
                                     std::pair{zero_axis, "axis has zero length"}}) {
    try {
      spatial::with_rotary_module(base, module);
      FAIL() << "expected an Error: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("rotary module 'rotary_module'"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace kinetofem::mech
