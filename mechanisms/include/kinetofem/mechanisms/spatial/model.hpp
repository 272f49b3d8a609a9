#pragma once
// spatial::Model — the plain-data description of a spatial linkage: rigid
// bodies with named points, joints with axes, motion drives on a joint's
// relative rotation or translation, force drives (motors) on them, point
// masses with rotary inertia, springs with dampers, point forces and gravity,
// all referred to by name.
// spatial::System (system.hpp) checks and compiles it; from_planar.hpp lifts a
// planar MultibodyModel into it.
//
// Frames and units (SI throughout):
//   world frame: right-handed x, y, z (m);
//   body frame: origin and orientation given by the body's pose (position of
//     the origin, world; rotation as Euler parameters or a rotation matrix);
//     points, centre of mass, axes and inertia tensors are in body axes.
//   A body's mass and centroidal inertia tensor (kg, kg m^2) are those of the
//   bare body; point masses are added with the parallel-axis rule.
//   The ground (fixed = true) keeps its pose and carries no coordinates.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/joint_traits.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"

namespace kinetofem::mech::spatial {

// A lumped mass at a body point (a gripper, a casting) with its own rotary
// inertia about its centre, body axes (zero: a point).
struct PointMass {
  std::string name;
  double mass_kg = 0.0;
  Eigen::Vector3d position_body = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Zero();
};

struct Body {
  std::string name;
  double mass_kg = 0.0;                                        // bare body
  Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Zero();      // about the bare body's centre of mass, body axes
  Eigen::Vector3d com_body = Eigen::Vector3d::Zero();          // bare body's centre of mass, body frame
  std::map<std::string, Eigen::Vector3d> points;               // named points, body frame; "origin" is implicit
  std::vector<PointMass> point_masses;
  // Pose of the body frame: the ground's pose, else the initial guess for assembly.
  Eigen::Vector3d position = Eigen::Vector3d::Zero();           // origin, world (m)
  Eigen::Vector4d euler_parameters{1.0, 0.0, 0.0, 0.0};         // (e0, e1, e2, e3), normalised on compile
  // Initial guess of the velocity, projected onto the constraints: the body
  // frame origin's velocity and the angular velocity, both world (m/s, rad/s).
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  bool fixed = false;  // ground
};

// Sets a body's rotation from a rotation matrix (body axes -> world).
inline void set_rotation(Body& body, const Eigen::Matrix3d& rotation) {
  body.euler_parameters = euler_parameters(rotation);
}

// Joint between point_i of body_i and point_j of body_j (joint_traits.hpp for
// the types and their frames). axis_i, axis_j: h_i, h_j in the bodies' frames
// (normalised on compile; a zero axis is an error); for the universal joint
// the two cross axes. reference_i / reference_j: f_i, f_j, the directions from
// which the relative rotation about h_i is measured (made perpendicular to the
// axis on compile); left empty, f_i is a vector perpendicular to h_i and f_j is
// f_i carried into body_j at the initial poses.
struct Joint {
  std::string name;
  JointType type = JointType::Revolute;
  std::string body_i, point_i = "origin";
  std::string body_j, point_j = "origin";
  Eigen::Vector3d axis_i = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d axis_j = Eigen::Vector3d::UnitZ();
  std::optional<Eigen::Vector3d> reference_i, reference_j;
  // Prismatic and fixed: the relative angle held about h_i (rad); left empty,
  // that of the initial poses.
  std::optional<double> rotation_rad;
  // Chain (SPEC §1; system.hpp for its equation): body_i carries the hinge
  // P_i, body_j the roller of radius radius_m (>= 0; 0 is a plain tie to P_j)
  // centred at P_j, both in the plane normal to h_i. wrap_ccw: followed from
  // the hinge onto the roller, the chain turns counter-clockwise about h_i.
  // length_m: free length + r * wrapped angle (m); left empty, that of the
  // initial poses.
  double radius_m = 0.0;
  bool wrap_ccw = true;
  std::optional<double> length_m;
};

inline Joint make_joint(std::string name, JointType type, std::string body_i, std::string point_i,
                        std::string body_j, std::string point_j, const Eigen::Vector3d& axis_i = Eigen::Vector3d::UnitZ(),
                        const Eigen::Vector3d& axis_j = Eigen::Vector3d::UnitZ()) {
  Joint j;
  j.name = std::move(name);
  j.type = type;
  j.body_i = std::move(body_i);
  j.point_i = std::move(point_i);
  j.body_j = std::move(body_j);
  j.point_j = std::move(point_j);
  j.axis_i = axis_i;
  j.axis_j = axis_j;
  return j;
}

// The relative coordinate of a joint that a motion drive acts on:
//   Rotation:    s = angle of f_j from f_i about h_i = atan2(g_i . f_j, f_i . f_j)  (rad)
//   Translation: s = h_i . (r_Pj - r_Pi)                                         (m)
enum class DriveCoordinate { Rotation, Translation };

// Prescribed motion as a constraint row: s(q) = s_0 + law(t). Its multiplier
// gives the drive effort (torque N m about h_i or force N along it) applied on
// body_j and reacted on body_i: effort = -lambda.
struct MotionDrive {
  std::string name;
  std::string joint;
  DriveCoordinate coordinate = DriveCoordinate::Rotation;
  std::shared_ptr<const MotionLaw> law;
  std::optional<double> initial;  // s_0; left empty, s(initial poses) - law(0)
};

// A motor on a joint's relative coordinate s (as a MotionDrive's) with an
// effort law, torque (N m) about h_i or force (N) along it, applied on body_j
// and reacted on body_i (the planar core's ForceDrive, multibody/model.hpp):
//   Constant:  effort = value
//   DcMotor:   effort = stall (1 - s' / no_load_speed)         (the speed-torque line)
//   PdServo:   effort = kp (s_0 + law(t) - s) + kd (law'(t) - s')
// Not a constraint: a load in Q (system.hpp), whose effort at a state
// System::force_drive_effort gives.
enum class EffortLaw { Constant, DcMotor, PdServo };

struct ForceDrive {
  std::string name;
  std::string joint;
  DriveCoordinate coordinate = DriveCoordinate::Rotation;
  EffortLaw law_type = EffortLaw::Constant;
  double value = 0.0;                    // Constant: N m (N)
  double stall = 0.0;                    // DcMotor: stall torque N m (force N)
  double no_load_speed = 0.0;            // DcMotor: rad/s (m/s), non-zero
  double kp = 0.0, kd = 0.0;             // PdServo: N m/rad, N m s/rad (N/m, N s/m)
  std::shared_ptr<const MotionLaw> law;  // PdServo reference
  std::optional<double> initial;         // PdServo s_0; left empty, s(initial poses) - law(0)
};

// Linear spring and damper between point_i of body_i and point_j of body_j,
// length L = |r_Pj - r_Pi| (m): tension N = stiffness (L - free_length) +
// damping L' (N, positive pulling the points together), acting along the line
// of the two points. L = 0 is an error (no direction).
struct Spring {
  std::string name;
  std::string body_i, point_i = "origin";
  std::string body_j, point_j = "origin";
  double stiffness_N_per_m = 0.0;
  double damping_Ns_per_m = 0.0;
  double free_length_m = 0.0;
};

// Constant force (world frame, N) at a body point.
struct PointForce {
  std::string name;
  std::string body, point = "origin";
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
};

struct Model {
  std::string name;
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<MotionDrive> motion_drives;
  std::vector<ForceDrive> force_drives;
  std::vector<Spring> springs;
  std::vector<PointForce> point_forces;
  Eigen::Vector3d gravity{0.0, 0.0, -9.80665};  // m/s^2, world frame
  double characteristic_length_m = 1.0;         // scales drift checks
};

}  // namespace kinetofem::mech::spatial
