#include "kinetofem/mechanisms/spatial/rotary_module.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech::spatial {

std::string rotary_joint_name(const RotaryModule& module) { return fmt::format("{}.joint", module.name); }
std::string rotary_drive_name(const RotaryModule& module) { return fmt::format("{}.drive", module.name); }

Model with_rotary_module(Model model, const RotaryModule& module) {
  const auto carrier = std::find_if(model.bodies.begin(), model.bodies.end(),
                                    [&](const Body& b) { return b.name == module.carrier; });
  require(carrier != model.bodies.end(), "rotary module '{}': the mechanism has no body '{}' to carry it", module.name,
          module.carrier);
  require(module.angle != nullptr, "rotary module '{}': no drive law for its turn (a rotary module needs a drive)",
          module.name);
  const double axis_length = module.axis_carrier.norm();
  require(axis_length > 0 && std::isfinite(axis_length), "rotary module '{}': its axis has zero length", module.name);
  const Eigen::Vector3d axis = module.axis_carrier / axis_length;
  Eigen::Vector3d mount = Eigen::Vector3d::Zero();
  if (module.mount_point != "origin") {
    const auto it = carrier->points.find(module.mount_point);
    require(it != carrier->points.end(), "rotary module '{}': body '{}' has no point '{}'", module.name, module.carrier,
            module.mount_point);
    mount = it->second;
  }
  require(module.mass_kg > 0 && std::isfinite(module.mass_kg),
          "rotary module '{}': the turning part's mass {} kg must be positive", module.name, module.mass_kg);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal(0.5 * (module.inertia_kgm2 + module.inertia_kgm2.transpose()));
  require(module.inertia_kgm2.allFinite() && principal.eigenvalues().minCoeff() > 0,
          "rotary module '{}': the turning part's inertia is not positive definite (principal values {}, {}, {} kg m^2)",
          module.name, principal.eigenvalues()[0], principal.eigenvalues()[1], principal.eigenvalues()[2]);

  // The module's frame: the carrier's axes at the initial pose, origin at the mount.
  const Eigen::Matrix3d carrier_rotation = rotation(carrier->euler_parameters.normalized());
  Body body;
  body.name = module.name;
  body.mass_kg = module.mass_kg;
  body.inertia_kgm2 = module.inertia_kgm2;
  body.position = carrier->position + carrier_rotation * mount;
  body.euler_parameters = carrier->euler_parameters.normalized();
  if (module.payload.mass_kg > 0) {
    body.point_masses.push_back(module.payload);
    body.points[module.payload.name] = module.payload.position_body;  // where the casting's centre is
  }
  const std::string carrier_name = carrier->name, mount_point = module.mount_point;
  model.bodies.push_back(std::move(body));
  model.joints.push_back(make_joint(rotary_joint_name(module), JointType::Revolute, carrier_name, mount_point,
                                    module.name, "origin", axis, axis));
  MotionDrive drive;
  drive.name = rotary_drive_name(module);
  drive.joint = rotary_joint_name(module);
  drive.coordinate = DriveCoordinate::Rotation;
  drive.law = module.angle;
  model.motion_drives.push_back(std::move(drive));
  return model;
}

}  // namespace kinetofem::mech::spatial
