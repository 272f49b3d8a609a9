#include "kinetofem/mechanisms/manipulator_models.hpp"

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"

namespace kinetofem::mech {

namespace {

Body make_body(const std::string& name, const LinkInertia& inertia, Eigen::Vector3d pose) {
  require(inertia.mass_kg > 0 && inertia.inertia_kgm2 > 0,
          "manipulator link '{}': mass {} kg and inertia {} kg m^2 must be positive", name,
          inertia.mass_kg, inertia.inertia_kgm2);
  Body body;
  body.name = name;
  body.mass_kg = inertia.mass_kg;
  body.inertia_kgm2 = inertia.inertia_kgm2;
  body.com_body = inertia.com_body;
  body.pose = pose;
  return body;
}

}  // namespace

MultibodyModel make_manipulator_model(const ManipulatorDefinition& d) {
  const LeverChainGeometry& g = d.geometry;
  require(d.lever_motion != nullptr, "manipulator: no motion law for the lever");
  require(d.gripper_mass_kg >= 0 && d.casting_mass_kg >= 0,
          "manipulator: gripper {} kg and casting {} kg must not be negative", d.gripper_mass_kg,
          d.casting_mass_kg);
  MultibodyModel m;
  m.name = d.type == ManipulatorType::LeverChain ? "lever-chain manipulator" : "lever manipulator";
  m.characteristic_length_m = g.a_m;
  m.gravity = d.gravity_m_s2;

  using namespace manipulator;  // the preset's names
  Body frame;
  frame.name = kFrame;
  frame.fixed = true;
  frame.points[kPointB0] = g.b0_point_m;
  Body lever = make_body(kLever, d.lever, {0, 0, 0});
  lever.points[kPointA] = {0.0, g.a_m};
  Body arm = make_body(kArm, d.arm, {0.0, g.a_m, 0.0});
  arm.points[kPointC] = {-g.c_m, 0.0};
  arm.points[kPointH] = {-g.c_m, g.h_m};
  if (d.gripper_mass_kg > 0) arm.point_masses.push_back({kGripperMass, d.gripper_mass_kg, {-g.c_m, g.h_m}});
  if (d.casting_mass_kg > 0) arm.point_masses.push_back({kCastingMass, d.casting_mass_kg, {-g.c_m, g.h_m}});
  m.joints.push_back({kJointA0, JointType::Revolute, kFrame, kOrigin, kLever, kOrigin});
  m.joints.push_back({kJointA, JointType::Revolute, kLever, kPointA, kArm, kOrigin});

  if (d.type == ManipulatorType::LeverChain) {
    m.bodies = {frame, lever, arm};
    Joint chain;
    chain.name = kChain;
    chain.type = JointType::Chain;
    chain.body_i = kFrame;
    chain.point_i = kPointB0;
    chain.body_j = kArm;
    chain.point_j = kOrigin;
    chain.radius_m = g.r_m;
    chain.wrap_ccw = true;  // from B0 up to the tangent point B = (r, a), then over the roller
    m.joints.push_back(chain);
  } else {
    arm.points[kPointB] = {g.r_m, 0.0};
    Body rocker = make_body(kRocker, d.rocker, {g.b0_point_m.x(), g.b0_point_m.y(), 0.0});
    rocker.points[kPointB] = {0.0, g.b0_m};
    m.bodies = {frame, lever, arm, rocker};
    m.joints.push_back({kJointB, JointType::Revolute, kArm, kPointB, kRocker, kPointB});
    m.joints.push_back({kJointB0, JointType::Revolute, kFrame, kPointB0, kRocker, kOrigin});
  }
  MotionDrive drive;
  drive.name = kLeverDrive;
  drive.coordinate = {CoordinateType::Angle, kFrame, kOrigin, kLever, kOrigin, {1, 0}};
  drive.law = d.lever_motion;
  drive.initial = 0.0;
  m.motion_drives.push_back(drive);
  return m;
}

}  // namespace kinetofem::mech
