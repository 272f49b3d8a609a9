#pragma once
// MultibodyModel — the plain-data description of a planar linkage: bodies with
// named points, joints, prescribed-motion drives, constant-ratio transmissions,
// force drives, springs, point masses, point forces and gravity, all referred
// to by name. A case reader
// fills it; MultibodySystem (system.hpp) checks and compiles it.
//
// Frames and units (SI throughout):
//   world frame: x, y in the plane, angles counter-clockwise positive (rad);
//   body frame: origin and orientation given by the body's pose (x, y, theta);
//     local points, centre of mass and axes are given in the body frame (m).
//   A body's mass and centroidal inertia (kg, kg m^2) are those of the bare
//   body; point masses (gripper, casting) are added with the parallel-axis rule.
//   The ground body (fixed = true) keeps its pose and carries no coordinates.
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/joint_traits.hpp"

namespace kinetofem::mech {

// A lumped mass at a body point (a gripper, a casting): adds mass_kg at
// position_body to the body's mass, centre of mass and inertia.
struct PointMass {
  std::string name;
  double mass_kg = 0.0;
  Eigen::Vector2d position_body = Eigen::Vector2d::Zero();
};

struct Body {
  std::string name;
  double mass_kg = 0.0;                                   // bare body
  double inertia_kgm2 = 0.0;                              // about the bare body's centre of mass
  Eigen::Vector2d com_body = Eigen::Vector2d::Zero();     // bare body's centre of mass, body frame
  std::map<std::string, Eigen::Vector2d> points;          // named points, body frame; "origin" is implicit
  std::vector<PointMass> point_masses;
  Eigen::Vector3d pose{0.0, 0.0, 0.0};  // (x, y, theta) of the body frame: the ground's pose, else the
                                        // initial guess for assembly
  Eigen::Vector3d velocity{0.0, 0.0, 0.0};  // initial guess of (x', y', theta') (projected onto the constraints)
  bool fixed = false;                        // ground
};

// JointType and its facts: joint_traits.hpp.

struct Joint {
  std::string name;
  JointType type = JointType::Revolute;
  std::string body_i, point_i;
  std::string body_j, point_j;
  Eigen::Vector2d axis_i{1.0, 0.0};  // prismatic: sliding direction in body_i frame (normalised on compile)
  double radius_m = 0.0;             // chain: roller radius
  bool wrap_ccw = true;              // chain: going from point_i along the chain onto the roller, the
                                     // chain turns counter-clockwise about the roller centre
  // Fixed joint: relative angle theta_j - theta_i; chain: constant free length + r * wrap angle.
  // Left empty, the value is taken from the bodies' initial poses.
  std::optional<double> reference;
};

// Shorthands for the common joints (the struct stays plain data).
inline Joint make_revolute(std::string name, std::string body_i, std::string point_i, std::string body_j,
                           std::string point_j) {
  Joint j;
  j.name = std::move(name);
  j.type = JointType::Revolute;
  j.body_i = std::move(body_i);
  j.point_i = std::move(point_i);
  j.body_j = std::move(body_j);
  j.point_j = std::move(point_j);
  return j;
}
inline Joint make_prismatic(std::string name, std::string body_i, std::string point_i, std::string body_j,
                            std::string point_j, const Eigen::Vector2d& axis_i) {
  Joint j = make_revolute(std::move(name), std::move(body_i), std::move(point_i), std::move(body_j), std::move(point_j));
  j.type = JointType::Prismatic;
  j.axis_i = axis_i;
  return j;
}
inline Joint make_fixed(std::string name, std::string body_i, std::string point_i, std::string body_j,
                        std::string point_j) {
  Joint j = make_revolute(std::move(name), std::move(body_i), std::move(point_i), std::move(body_j), std::move(point_j));
  j.type = JointType::Fixed;
  return j;
}
// The relative coordinate a drive acts on (and the independent coordinate of the
// minimal-coordinate path):
//   Angle:        s = theta_j - theta_i                         (rad)
//   Displacement: s = u_i . (r_Pj - r_Pi), u_i = axis_i turned into world (m)
enum class CoordinateType { Angle, Displacement };

struct RelativeCoordinate {
  CoordinateType type = CoordinateType::Angle;
  std::string body_i, point_i = "origin";
  std::string body_j, point_j = "origin";
  Eigen::Vector2d axis_i{1.0, 0.0};  // Displacement: direction in body_i frame (normalised on compile)
};

// Prescribed motion as a constraint: s(q) = s_0 + law(t). Its multiplier gives
// the drive effort (torque N m or force N) that the drive applies on body_j
// (and, reversed, on body_i): effort = -lambda.
struct MotionDrive {
  std::string name;
  RelativeCoordinate coordinate;
  std::shared_ptr<const MotionLaw> law;
  std::optional<double> initial;  // s_0; left empty, s(q_initial poses) - law(0)
};

// A constant-ratio transmission between two relative angles (SPEC §4's control
// transmission mechanism: a belt, chain or gear train that ties one joint angle
// of a primary chain to another):
//     s_out = ratio * s_in + c,      s = theta_j - theta_i of each coordinate (rad),
// i.e. phi_{k+1,k} = i_k phi_{k,k-1} with s_in = phi_{k,k-1}, s_out = phi_{k+1,k}.
// The sign is that of the general statement of SPEC §4; the source's two-link
// formula writes phi_21 = -i phi_10, so its i is -ratio here: an open belt from a
// fixed pulley of radius r_0 to a pulley of radius r_2 on the next link gives
// ratio = -r_0 / r_2, a crossed belt or one gear pair +r_0 / r_2.
// An ideal, workless, massless transmission: one constraint row (system.hpp)
// whose multiplier gives the moment it transmits (results.hpp: TransmissionFrame).
enum class TransmissionKind { Belt, Gear };

// What a kind's force (output moment / radius) is, in words: "belt pull", "tooth force".
inline const char* transmission_force_name(TransmissionKind kind) {
  switch (kind) {
    case TransmissionKind::Belt:
      return "belt pull";
    case TransmissionKind::Gear:
      return "tooth force";
  }
  return "force";
}

struct Transmission {
  std::string name;
  RelativeCoordinate input, output;  // both CoordinateType::Angle
  double ratio = 1.0;                // i, finite and non-zero
  std::optional<double> reference;   // c (rad); left empty, s_out - i s_in at the initial poses
  TransmissionKind kind = TransmissionKind::Belt;
  // Radius of the output side's pulley (belt, chain) or pitch circle (gear), m:
  // the belt's effective pull or the tooth force is the output moment / radius.
  double radius_m = 0.0;
};

// A motor acting on the relative coordinate s with an effort (torque or force) law:
//   Constant:  effort = value
//   DcMotor:   effort = stall * (1 - s_dot / no_load_speed)  (the speed-torque line)
//   PdServo:   effort = kp * (s_0 + law(t) - s) + kd * (law'(t) - s_dot)
// The effort acts on body_j (+) and reacts on body_i (-).
enum class ForceLaw { Constant, DcMotor, PdServo };

struct ForceDrive {
  std::string name;
  RelativeCoordinate coordinate;
  ForceLaw law_type = ForceLaw::Constant;
  double value = 0.0;               // Constant: torque N m (force N)
  double stall = 0.0;               // DcMotor: stall torque (force)
  double no_load_speed = 0.0;       // DcMotor: rad/s (m/s)
  double kp = 0.0, kd = 0.0;        // PdServo gains (N m/rad, N m s/rad or N/m, N s/m)
  std::shared_ptr<const MotionLaw> law;  // PdServo reference
  std::optional<double> initial;    // PdServo s_0; left empty, s(q_initial poses) - law(0)
};

// Linear spring and damper between point_i of body_i and point_j of body_j,
// length L = |r_Pj - r_Pi|: tension N = stiffness*(L - free_length) + damping*L'.
struct Spring {
  std::string name;
  std::string body_i, point_i = "origin";
  std::string body_j, point_j = "origin";
  double stiffness_N_per_m = 0.0;
  double damping_Ns_per_m = 0.0;
  double free_length_m = 0.0;
};

// Constant force (world frame, N) at a body point, e.g. a process load.
struct PointForce {
  std::string name;
  std::string body, point = "origin";
  Eigen::Vector2d force_world = Eigen::Vector2d::Zero();
};

struct MultibodyModel {
  std::string name;
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<MotionDrive> motion_drives;
  std::vector<Transmission> transmissions;
  std::vector<ForceDrive> force_drives;
  std::vector<Spring> springs;
  std::vector<PointForce> point_forces;
  Eigen::Vector2d gravity{0.0, -9.80665};  // m/s^2, world frame (zero vector: no gravity)
  double characteristic_length_m = 1.0;   // scales drift and residual checks
};

}  // namespace kinetofem::mech
