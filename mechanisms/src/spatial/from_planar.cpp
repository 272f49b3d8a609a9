#include "kinetofem/mechanisms/spatial/from_planar.hpp"

#include <cmath>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"

namespace kinetofem::mech::spatial {

using Eigen::Vector2d;
using Eigen::Vector3d;

namespace {

Vector3d lift(const Vector2d& a) { return {a.x(), a.y(), 0.0}; }

// The planar core reads an empty point name as the body origin.
std::string point_name(const std::string& planar) { return planar.empty() ? "origin" : planar; }

Body lift_body(const mech::Body& b) {
  Body out;
  out.name = b.name;
  out.fixed = b.fixed;
  out.mass_kg = b.mass_kg;
  out.com_body = lift(b.com_body);
  // The polar rule of a lamina for the out-of-plane moments (from_planar.hpp: why harmless).
  out.inertia_kgm2 = Vector3d(0.5 * b.inertia_kgm2, 0.5 * b.inertia_kgm2, b.inertia_kgm2).asDiagonal();
  for (const auto& [name, p] : b.points) out.points[name] = lift(p);
  for (const mech::PointMass& pm : b.point_masses) out.point_masses.push_back({pm.name, pm.mass_kg, lift(pm.position_body), Eigen::Matrix3d::Zero()});
  out.position = {b.pose.x(), b.pose.y(), 0.0};
  out.euler_parameters = axis_angle(Vector3d::UnitZ(), b.pose.z());
  out.velocity = {b.velocity.x(), b.velocity.y(), 0.0};
  out.angular_velocity = {0.0, 0.0, b.velocity.z()};
  return out;
}

const mech::Body& planar_body(const MultibodyModel& m, const std::string& name, const std::string& owner) {
  for (const mech::Body& b : m.bodies)
    if (b.name == name) return b;
  fail("from_planar of '{}': {} names body '{}', which the model does not have", m.name, owner, name);
}

Joint lift_joint(const MultibodyModel& m, const mech::Joint& j) {
  Joint out = make_joint(j.name, JointType::Revolute, j.body_i, point_name(j.point_i), j.body_j, point_name(j.point_j),
                         Vector3d::UnitZ(), Vector3d::UnitZ());
  // Relative angles about z measured between the bodies' x axes: theta_j - theta_i, as in the planar core.
  out.reference_i = Vector3d::UnitX();
  out.reference_j = Vector3d::UnitX();
  switch (j.type) {
    case mech::JointType::Revolute:
      break;
    case mech::JointType::Fixed:
      out.type = JointType::Fixed;
      out.rotation_rad = j.reference;
      break;
    case mech::JointType::Prismatic: {
      require(j.axis_i.norm() > 0.0, "from_planar of '{}': prismatic joint '{}' has a zero axis", m.name, j.name);
      const double held = j.reference.value_or(planar_body(m, j.body_j, "joint '" + j.name + "'").pose.z() -
                                               planar_body(m, j.body_i, "joint '" + j.name + "'").pose.z());
      out.type = JointType::Prismatic;
      out.axis_i = lift(j.axis_i.normalized());
      // h_j is h_i seen from body_j at the held relative angle, so that the two
      // axis rows hold theta_j - theta_i there; the roll about the slide (f_i = f_j = z) is 0.
      out.axis_j = Eigen::AngleAxisd(-held, Vector3d::UnitZ()) * out.axis_i;
      out.reference_i = Vector3d::UnitZ();
      out.reference_j = Vector3d::UnitZ();
      out.rotation_rad = 0.0;
      break;
    }
    case mech::JointType::Chain:
      out.type = JointType::Chain;
      out.radius_m = j.radius_m;
      out.wrap_ccw = j.wrap_ccw;
      out.length_m = j.reference;
      break;
  }
  return out;
}

// The lifted joint and coordinate that carry a planar drive's relative coordinate.
struct DrivenCoordinate {
  std::string joint;
  DriveCoordinate coordinate = DriveCoordinate::Rotation;
};

DrivenCoordinate driven_coordinate(const MultibodyModel& m, const std::string& drive, const RelativeCoordinate& c) {
  DrivenCoordinate out;
  for (const mech::Joint& j : m.joints) {
    if (j.body_i != c.body_i || j.body_j != c.body_j) continue;
    switch (c.type) {
      case CoordinateType::Angle:
        if (j.type != mech::JointType::Revolute) continue;
        out.joint = j.name;
        out.coordinate = DriveCoordinate::Rotation;
        return out;
      case CoordinateType::Displacement: {
        // h_i . (P_j - P_i) is the planar u_i . d only with the same points and axis.
        const bool same = j.type == mech::JointType::Prismatic && point_name(j.point_i) == point_name(c.point_i) &&
                          point_name(j.point_j) == point_name(c.point_j) && j.axis_i.norm() > 0.0 &&
                          c.axis_i.norm() > 0.0 &&
                          (j.axis_i.normalized() - c.axis_i.normalized()).norm() <= 1e-12;
        if (!same) continue;
        out.joint = j.name;
        out.coordinate = DriveCoordinate::Translation;
        return out;
      }
    }
  }
  fail("from_planar of '{}': drive '{}' ({} of '{}' against '{}') is not the coordinate of a {} joint from "
       "'{}' to '{}'{}; the spatial core drives a joint's own coordinate",
       m.name, drive, c.type == CoordinateType::Angle ? "angle" : "displacement", c.body_j, c.body_i,
       c.type == CoordinateType::Angle ? "revolute" : "prismatic", c.body_i, c.body_j,
       c.type == CoordinateType::Angle ? "" : " with the same points and axis");
}

MotionDrive lift_drive(const MultibodyModel& m, const mech::MotionDrive& d) {
  const DrivenCoordinate c = driven_coordinate(m, d.name, d.coordinate);
  MotionDrive out;
  out.name = d.name;
  out.joint = c.joint;
  out.coordinate = c.coordinate;
  out.law = d.law;
  out.initial = d.initial;
  return out;
}

ForceDrive lift_force_drive(const MultibodyModel& m, const mech::ForceDrive& d) {
  const DrivenCoordinate c = driven_coordinate(m, d.name, d.coordinate);
  ForceDrive out;
  out.name = d.name;
  out.joint = c.joint;
  out.coordinate = c.coordinate;
  switch (d.law_type) {
    case ForceLaw::Constant: out.law_type = EffortLaw::Constant; break;
    case ForceLaw::DcMotor: out.law_type = EffortLaw::DcMotor; break;
    case ForceLaw::PdServo: out.law_type = EffortLaw::PdServo; break;
  }
  out.value = d.value;
  out.stall = d.stall;
  out.no_load_speed = d.no_load_speed;
  out.kp = d.kp;
  out.kd = d.kd;
  out.law = d.law;
  out.initial = d.initial;
  return out;
}

}  // namespace

Model from_planar(const MultibodyModel& planar) {
  require(planar.transmissions.empty(),
          "from_planar of '{}': {} transmission(s), first '{}': the spatial core has no transmission (its periodic "
          "relative angles carry no winding count; from_planar.hpp)",
          planar.name,
          planar.transmissions.size(), planar.transmissions.empty() ? "" : planar.transmissions.front().name);
  Model out;
  out.name = planar.name;
  out.characteristic_length_m = planar.characteristic_length_m;
  out.gravity = lift(planar.gravity);
  for (const mech::Body& b : planar.bodies) out.bodies.push_back(lift_body(b));
  for (const mech::Joint& j : planar.joints) out.joints.push_back(lift_joint(planar, j));
  for (const mech::MotionDrive& d : planar.motion_drives) out.motion_drives.push_back(lift_drive(planar, d));
  for (const mech::ForceDrive& d : planar.force_drives) out.force_drives.push_back(lift_force_drive(planar, d));
  for (const mech::Spring& s : planar.springs)
    out.springs.push_back({s.name, s.body_i, point_name(s.point_i), s.body_j, point_name(s.point_j), s.stiffness_N_per_m,
                           s.damping_Ns_per_m, s.free_length_m});
  for (const mech::PointForce& f : planar.point_forces)
    out.point_forces.push_back({f.name, f.body, point_name(f.point), lift(f.force_world)});
  return out;
}

}  // namespace kinetofem::mech::spatial
