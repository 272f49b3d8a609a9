#pragma once
// The rotary gripper module of a casting extractor (seed 002, l. 1045-1050:
// the gripper turns the casting through 90 degrees about the arm): a body on a
// revolute joint about an axis fixed in its carrier (the arm), at a mount
// point on that axis, turned by a motion drive, carrying the casting as a
// point mass with rotary inertia off the axis. Added to a spatial::Model (a
// planar manipulator lifted by from_planar, or any other), so the turn is a
// motion out of the mechanism's plane: the arm takes the drive's torque about
// its axis (torsion) and the casting's weight moves across the plane.
//
// Frames and units (SI): the module's body frame has its origin at the mount
// point and the carrier's axes at the initial pose, so the axis is
// axis_carrier in both frames at the start; the casting's position and both
// inertias are in these axes.
//
// Names: the body `name`, its joint `name + ".joint"` (carrier - module, the
// carrier body_i) and its drive `name + ".drive"` (the relative angle about
// the axis, from the initial pose; effort = the torque on the module about
// the axis, reacted on the carrier), the casting point mass `payload.name`.
#include <memory>
#include <string>

#include <Eigen/Core>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"

namespace kinetofem::mech::spatial {

struct RotaryModule {
  std::string name = "rotary_module";
  std::string carrier = "arm";
  std::string mount_point = "H";                          // a named point of the carrier, on the axis
  Eigen::Vector3d axis_carrier = Eigen::Vector3d::UnitX();  // the turning axis, carrier frame (normalised)
  // The turning part (the gripper with its jaws), its centre of mass at the
  // mount point; its inertia about that centre must be positive definite
  // (the spatial core works in the mass metric).
  double mass_kg = 0.0;
  Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Zero();
  PointMass payload;                        // the casting: position in the module's frame
  std::shared_ptr<const MotionLaw> angle;   // the turn about the axis (rad)
};

// `model` with the module added (the carrier keeps everything it had).
// Throws Error naming the module when the carrier or its mount point is
// missing, the axis has zero length, the turning part has no positive
// definite inertia, or the turn has no law (a rotary module without a drive).
Model with_rotary_module(Model model, const RotaryModule& module);

// The names of the module's joint and drive.
std::string rotary_joint_name(const RotaryModule& module);
std::string rotary_drive_name(const RotaryModule& module);

}  // namespace kinetofem::mech::spatial
