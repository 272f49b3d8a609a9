#include "kinetofem/mechanisms/spatial/spherical_manipulator_model.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"

namespace kinetofem::mech::spatial {

using Eigen::Matrix3d;
using Eigen::Vector3d;
namespace names = spherical_names;

namespace {

// Joint axes and references in the bodies' frames, shared by the model and
// the map back from its frames (the header's table).
const Vector3d kBaseAxis = Vector3d::UnitZ();    // pair_10 on ground and column
const Vector3d kTiltAxis = -Vector3d::UnitY();   // pair_21 on column and sleeve: -e_phi
const Vector3d kSlideAxis = Vector3d::UnitX();   // pair_32 on sleeve and arm: e_r

struct Spherical {
  Vector3d r, theta, phi, h;  // e_r, e_theta, e_phi, e_h
};

Spherical unit_vectors(double phi10, double phi21) {
  const double c1 = std::cos(phi10), s1 = std::sin(phi10), c2 = std::cos(phi21), s2 = std::sin(phi21);
  return {{c2 * c1, c2 * s1, s2}, {-s2 * c1, -s2 * s1, c2}, {-s1, c1, 0.0}, {c1, s1, 0.0}};
}

Matrix3d columns(const Vector3d& x, const Vector3d& y, const Vector3d& z) {
  Matrix3d a;
  a << x, y, z;
  return a;
}

// Principal inertia of a body symmetric about its x axis (sleeve, arm).
Matrix3d about_x(double axial, double transverse) { return Vector3d(axial, transverse, transverse).asDiagonal(); }

const BodyState& body_named(const Frame& f, std::string_view name) {
  for (const BodyState& b : f.bodies)
    if (b.name == name) return b;
  fail("spherical manipulator frame at t = {} s: no body '{}'", f.t, name);
}
const JointState& joint_named(const Frame& f, std::string_view name) {
  for (const JointState& j : f.joints)
    if (j.name == name) return j;
  fail("spherical manipulator frame at t = {} s: no joint '{}'", f.t, name);
}
const DriveState& drive_named(const Frame& f, std::string_view name) {
  for (const DriveState& d : f.drives)
    if (d.name == name) return d;
  fail("spherical manipulator frame at t = {} s: no drive '{}'", f.t, name);
}

// The joint's constraint load on body_j as the reaction of a pair at `point`,
// plus the drive's load: a couple `drive_couple`, or a force `drive_force` at
// `drive_at`. The drive's component is then taken out as the closed form does.
PairLoad pair_load(const Reaction& joint, const Vector3d& point, double effort, const Vector3d& drive_couple,
                   const Vector3d& drive_force, const Vector3d& drive_at) {
  PairLoad p;
  p.point_world = point;
  p.drive = effort;
  p.reaction_force = joint.force_world;
  p.reaction_moment = joint.moment_world + (joint.point_world - point).cross(joint.force_world);
  p.force_world = p.reaction_force + drive_force;
  p.moment_world = p.reaction_moment + drive_couple + (drive_at - point).cross(drive_force);
  return p;
}

}  // namespace

// ---- the joint law --------------------------------------------------------------------------

SphericalJointLaw::SphericalJointLaw(const SphericalDesign& design, const StraightLineMotion& motion, int coordinate)
    : design_(design), motion_(motion), coordinate_(coordinate) {
  require(coordinate >= 0 && coordinate <= 2,
          "spherical joint law: coordinate {} is none of 0 (phi10), 1 (phi21), 2 (l_BM)", coordinate);
}

MotionState SphericalJointLaw::at(double t) const {
  const StraightLineMotion::Point p = motion_.at(t);
  const SphericalJointMotion j = spherical_joint_motion(design_, p.m, p.m_dot, p.m_ddot);
  return {j.q(coordinate_), j.qd(coordinate_), j.qdd(coordinate_)};
}

double SphericalJointLaw::stroke() const { return at(duration()).s - at(0.0).s; }

std::string SphericalJointLaw::describe() const {
  static constexpr const char* coordinate_names[] = {"phi10", "phi21", "l_BM"};
  return fmt::format("{} of the spherical manipulator {} along a straight line of {:.4g} m in {:.4g} s",
                     coordinate_names[coordinate_], design_.variant.name, motion_.length(), motion_.duration());
}

// ---- the model ------------------------------------------------------------------------------

SphericalDesign as_modelled(const SphericalDesign& design) {
  SphericalDesign d = design;
  if (d.arm_inertia_axial == 0.0) d.arm_inertia_axial = kSlenderAxialInertiaFraction * d.arm_inertia_transverse;
  if (d.sleeve_inertia_axial == 0.0)
    d.sleeve_inertia_axial = kSlenderAxialInertiaFraction * d.sleeve_inertia_transverse;
  return d;
}

Model spherical_manipulator_model(const SphericalDesign& given, const StraightLineMotion& motion) {
  const SphericalDesign design = as_modelled(given);
  const SphericalVariant& var = design.variant;
  const double z_a = var.height_a_m, z_b = var.height_b_m, arm_l = design.arm_length_m;
  require(arm_l > 0.0 && design.sleeve_length_m > 0.0,
          "spherical manipulator model: the design is not sized (arm {} m, sleeve {} m)", arm_l, design.sleeve_length_m);
  require(design.arm_inertia_transverse > 0.0 && design.sleeve_inertia_transverse > 0.0 &&
              design.column_inertia_z > 0.0 && design.arm_inertia_axial >= 0.0 && design.sleeve_inertia_axial >= 0.0,
          "spherical manipulator model: inertias must be positive (axial ones >= 0): arm {} / {}, sleeve {} / {}, "
          "column {} kg m^2",
          design.arm_inertia_transverse, design.arm_inertia_axial, design.sleeve_inertia_transverse,
          design.sleeve_inertia_axial, design.column_inertia_z);

  // The pose at t = 0 from the closed-form inverse kinematics, so that the
  // assembly starts on the solution.
  const StraightLineMotion::Point start = motion.at(0.0);
  const SphericalJointMotion j0 = spherical_joint_motion(design, start.m, start.m_dot, start.m_ddot);
  const Spherical e = unit_vectors(j0.q(0), j0.q(1));
  const Vector3d b_world(0.0, 0.0, z_b);
  const Vector3d w_column = j0.qd(0) * Vector3d::UnitZ();
  const Vector3d w_sleeve = w_column - j0.qd(1) * e.phi;

  Model m;
  m.name = fmt::format("spherical manipulator {} (SPEC §5)", var.name);
  m.gravity = Vector3d(0.0, 0.0, -design.gravity_mps2);
  m.characteristic_length_m = arm_l;

  Body ground;
  ground.name = names::ground;
  ground.fixed = true;
  ground.points[std::string(names::point_a)] = Vector3d(0.0, 0.0, z_a);

  Body column;
  column.name = names::column;
  column.mass_kg = var.m1_kg;
  column.com_body = Vector3d(0.0, 0.0, design.column_com_height_m);
  const double column_transverse = 0.1 * var.m1_kg * z_b * z_b;
  column.inertia_kgm2 = Vector3d(column_transverse, column_transverse, design.column_inertia_z).asDiagonal();
  column.points[std::string(names::point_a)] = Vector3d(0.0, 0.0, z_a);
  column.points[std::string(names::point_b)] = Vector3d(0.0, 0.0, z_b);
  column.position = Vector3d::Zero();
  set_rotation(column, columns(e.h, e.phi, Vector3d::UnitZ()));
  column.angular_velocity = w_column;

  Body sleeve;
  sleeve.name = names::sleeve;
  sleeve.mass_kg = var.m2_kg;
  sleeve.inertia_kgm2 = about_x(design.sleeve_inertia_axial, design.sleeve_inertia_transverse);
  sleeve.points[std::string(names::point_b)] = Vector3d::Zero();
  sleeve.position = b_world;
  set_rotation(sleeve, columns(e.r, e.phi, e.theta));
  sleeve.angular_velocity = w_sleeve;

  Body arm;
  arm.name = names::arm;
  arm.mass_kg = var.m3_kg;
  arm.com_body = Vector3d(0.5 * arm_l, 0.0, 0.0);
  arm.inertia_kgm2 = about_x(design.arm_inertia_axial, design.arm_inertia_transverse);
  arm.points[std::string(names::point_rear)] = Vector3d::Zero();
  arm.points[std::string(names::point_s3)] = Vector3d(0.5 * arm_l, 0.0, 0.0);
  arm.points[std::string(names::point_m)] = Vector3d(arm_l, 0.0, 0.0);
  if (design.payload_kg > 0.0)
    arm.point_masses.push_back({std::string(names::payload), design.payload_kg, Vector3d(arm_l, 0.0, 0.0),
                                Matrix3d::Zero()});
  const double rear = j0.q(2) - arm_l;  // the rear end's distance from B along e_r
  arm.position = b_world + rear * e.r;
  set_rotation(arm, columns(e.r, e.phi, e.theta));
  arm.angular_velocity = w_sleeve;
  arm.velocity = j0.qd(2) * e.r + w_sleeve.cross(rear * e.r);

  m.bodies = {ground, column, sleeve, arm};

  Joint p10 = make_joint(std::string(names::pair_10), JointType::Revolute, ground.name, std::string(names::point_a),
                         column.name, std::string(names::point_a), kBaseAxis, kBaseAxis);
  p10.reference_i = p10.reference_j = Vector3d::UnitX();
  Joint p21 = make_joint(std::string(names::pair_21), JointType::Revolute, column.name, std::string(names::point_b),
                         sleeve.name, std::string(names::point_b), kTiltAxis, kTiltAxis);
  p21.reference_i = p21.reference_j = Vector3d::UnitX();
  Joint p32 = make_joint(std::string(names::pair_32), JointType::Prismatic, sleeve.name, std::string(names::point_b),
                         arm.name, std::string(names::point_m), kSlideAxis, kSlideAxis);
  p32.reference_i = p32.reference_j = Vector3d::UnitY();
  p32.rotation_rad = 0.0;
  m.joints = {p10, p21, p32};

  const auto drive = [&](std::string_view name, std::string_view joint, DriveCoordinate coordinate, int k) {
    MotionDrive d;
    d.name = name;
    d.joint = joint;
    d.coordinate = coordinate;
    d.law = std::make_shared<SphericalJointLaw>(design, motion, k);
    d.initial = 0.0;
    return d;
  };
  m.motion_drives = {drive(names::drive_10, names::pair_10, DriveCoordinate::Rotation, 0),
                     drive(names::drive_21, names::pair_21, DriveCoordinate::Rotation, 1),
                     drive(names::drive_32, names::pair_32, DriveCoordinate::Translation, 2)};
  return m;
}

// ---- back to the closed form's quantities ------------------------------------------------------

SphericalDynamics spherical_dynamics(const Frame& f) {
  const BodyState& ground = body_named(f, names::ground);
  const BodyState& column = body_named(f, names::column);
  const BodyState& sleeve = body_named(f, names::sleeve);
  const JointState& j10 = joint_named(f, names::pair_10);
  const JointState& j21 = joint_named(f, names::pair_21);
  const JointState& j32 = joint_named(f, names::pair_32);
  const DriveState& d10 = drive_named(f, names::drive_10);
  const DriveState& d21 = drive_named(f, names::drive_21);
  const DriveState& d32 = drive_named(f, names::drive_32);

  SphericalDynamics out;
  out.t = f.t;
  out.joints.q = Vector3d(d10.s, d21.s, d32.s);
  out.joints.qd = Vector3d(d10.s_dot, d21.s_dot, d32.s_dot);
  out.joints.qdd = Vector3d(d10.s_ddot, d21.s_ddot, d32.s_ddot);

  // Drive axes in world: each drive acts about (along) its joint's h_i, on body_j.
  const Vector3d base_axis = ground.rotation * kBaseAxis;
  const Vector3d tilt_axis = column.rotation * kTiltAxis;
  const Vector3d slide_axis = sleeve.rotation * kSlideAxis;
  const Vector3d a = j10.on_j.point_world, b = j21.on_j.point_world, m = j32.on_j.point_world;
  const Vector3d zero = Vector3d::Zero();
  // A rotation drive loads body_j with a couple; the translation drive
  // h_i . (M - B) with a force along h_i at M.
  out.pair32 = pair_load(j32.on_j, b, d32.effort, zero, d32.effort * slide_axis, m);
  out.pair21 = pair_load(j21.on_j, b, d21.effort, d21.effort * tilt_axis, zero, b);
  out.pair10 = pair_load(j10.on_j, a, d10.effort, d10.effort * base_axis, zero, a);

  out.drive_power_W = Vector3d(d10.effort * d10.s_dot, d21.effort * d21.s_dot, d32.effort * d32.s_dot);
  out.total_power_W = out.drive_power_W.sum();
  return out;
}

ClosedFormComparison compare_with_closed_form(const SphericalDesign& design, const StraightLineMotion& motion,
                                              const Results& run) {
  require(!run.frames.empty(), "spherical manipulator comparison: the run has no frames");
  Vector3d drive_error = Vector3d::Zero(), drive_scale = Vector3d::Zero();
  double force_error = 0.0, force_scale = 0.0, moment_error = 0.0, moment_scale = 0.0;
  for (const Frame& f : run.frames) {
    const SphericalDynamics s = spherical_dynamics(f);
    const StraightLineMotion::Point p = motion.at(f.t);
    const SphericalDynamics c =
        spherical_inverse_dynamics(design, spherical_joint_motion(design, p.m, p.m_dot, p.m_ddot), f.t);
    const PairLoad* spatial_pairs[] = {&s.pair10, &s.pair21, &s.pair32};
    const PairLoad* closed_pairs[] = {&c.pair10, &c.pair21, &c.pair32};
    for (int k = 0; k < 3; ++k) {
      const PairLoad &sp = *spatial_pairs[k], &cp = *closed_pairs[k];
      drive_scale(k) = std::max(drive_scale(k), std::abs(cp.drive));
      drive_error(k) = std::max(drive_error(k), std::abs(sp.drive - cp.drive));
      force_scale = std::max(force_scale, cp.reaction_force.norm());
      moment_scale = std::max(moment_scale, cp.reaction_moment.norm());
      force_error = std::max(force_error, (sp.reaction_force - cp.reaction_force).cwiseAbs().maxCoeff());
      moment_error = std::max(moment_error, (sp.reaction_moment - cp.reaction_moment).cwiseAbs().maxCoeff());
    }
  }
  const double torque_scale = std::max({drive_scale(0), drive_scale(1), 1e-300});
  ClosedFormComparison out;
  out.drive = Vector3d(drive_error(0) / torque_scale, drive_error(1) / torque_scale,
                       drive_error(2) / std::max(drive_scale(2), 1e-300));
  out.reaction_force = force_error / std::max(force_scale, 1e-300);
  out.reaction_moment = moment_error / std::max(moment_scale, 1e-300);
  return out;
}

}  // namespace kinetofem::mech::spatial
