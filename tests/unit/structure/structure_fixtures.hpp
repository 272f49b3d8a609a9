#pragma once
// Small models shared by the elastic-assembly tests (tests/unit/structure/,
// tests/verification/structure/). Structured box meshes (tests/support
// box_mesh), no Gmsh. SI units.
//
//   bar_mesh       a straight bar L x H x T (HEX20) in the body frame of a
//                  link whose joints lie on its axis: x in [0, L], y in
//                  [-H/2, H/2], z in [-T/2, T/2] (symmetric about the
//                  mechanism plane): face x0's centroid is the body origin,
//                  x1's is (L, 0). Face sets x0, x1, y0, y1, z0, z1.
//   bar_part       that mesh as a pipeline::Part of a body, with its mass.
//   two_link_arm   frame - "link1" - "link2": pins "J1" (frame origin, link1
//                  origin) and "J2" (link1 "tip" = (L1, 0), link2 origin);
//                  motion drives "d1" (frame-link1) and "d2" (link1-link2,
//                  relative angle), 3-4-5 rises; a point mass "payload" at
//                  link2's "tip" = (L2, 0); gravity -y.
//   two_link_parts the two bars with their attachments: link1 J1 + d1 on x0,
//                  J2 + d2 on x1; link2 J2 + d2 on x0, payload on x1.
//   lever_chain    the SPEC §1 lever-chain manipulator (a = 500, c = 350,
//                  h = 100, r = 75 mm; mech::make_manipulator_model) with box
//                  parts: lever x in [-w/2, w/2], y in [0, a] (A0 = centroid of
//                  y0, A = centroid of y1); arm x in [-c, 0] (A = centroid of
//                  x1, which also carries the chain; gripper and casting at
//                  H = (-c, h) through x0).
#include <array>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/testing/box_mesh.hpp"

namespace kinetofem::structure::test {

inline constexpr double kDeg = std::numbers::pi / 180.0;

struct BarSize {
  double length_m = 0.30, height_m = 0.04, thickness_m = 0.02;
  std::array<int, 3> cells = {10, 2, 1};
  fem::ElementType type = fem::ElementType::Hex20;
};

inline fem::Mesh bar_mesh(const BarSize& size = {}) {
  testing::BoxMeshOptions box;
  box.length_m = {size.length_m, size.height_m, size.thickness_m};
  box.divisions = size.cells;
  box.type = size.type;
  fem::Mesh mesh = testing::box_mesh(box);
  mesh.nodes.col(1).array() -= 0.5 * size.height_m;
  mesh.nodes.col(2).array() -= 0.5 * size.thickness_m;
  return mesh;
}

inline fem::IsotropicMaterial steel(double stiffness_factor = 1.0) {
  fem::IsotropicMaterial m;  // E 210 GPa, nu 0.3, 7850 kg/m^3
  m.youngs_modulus_pa *= stiffness_factor;
  return m;
}

inline pipeline::Part mesh_part(const std::string& body, loads::LinkDefinition attachments, fem::Mesh mesh,
                                const fem::IsotropicMaterial& material) {
  pipeline::Part part;
  attachments.body = body;
  attachments.model = nullptr;
  part.attachments = std::move(attachments);
  part.label = "part '" + body + "' (test bar)";
  part.model.mesh = std::move(mesh);
  part.model.material = material;
  part.mass = fem::mass_properties(part.model.mesh, part.model.material);
  return part;
}

inline pipeline::Part bar_part(const std::string& body, loads::LinkDefinition attachments, const BarSize& size = {},
                               const fem::IsotropicMaterial& material = steel()) {
  return mesh_part(body, std::move(attachments), bar_mesh(size), material);
}

struct TwoLinkArm {
  double l1_m = 0.30, l2_m = 0.30;
  double theta1_rad = 20 * kDeg, theta2_rad = 30 * kDeg;  // link1 absolute, link2 relative to link1 at t = 0
  double stroke1_rad = 40 * kDeg, stroke2_rad = -50 * kDeg, duration_s = 0.5;
  double payload_kg = 3.0;
};

inline mech::MultibodyModel two_link_arm(const TwoLinkArm& a = {}) {
  mech::MultibodyModel m;
  m.name = "two-link arm";
  m.characteristic_length_m = a.l1_m;
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body link1;
  link1.name = "link1";
  link1.mass_kg = 1.0;  // placeholders: the parts' mass properties replace them
  link1.inertia_kgm2 = 0.01;
  link1.points["tip"] = {a.l1_m, 0.0};
  link1.pose = {0.0, 0.0, a.theta1_rad};
  mech::Body link2 = link1;
  link2.name = "link2";
  link2.points["tip"] = {a.l2_m, 0.0};
  link2.pose = {a.l1_m * std::cos(a.theta1_rad), a.l1_m * std::sin(a.theta1_rad), a.theta1_rad + a.theta2_rad};
  if (a.payload_kg > 0) link2.point_masses.push_back({"payload", a.payload_kg, {a.l2_m, 0.0}});
  m.bodies = {frame, link1, link2};
  m.joints.push_back(mech::make_revolute("J1", "frame", "origin", "link1", "origin"));
  m.joints.push_back(mech::make_revolute("J2", "link1", "tip", "link2", "origin"));
  mech::MotionDrive d1;
  d1.name = "d1";
  d1.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "link1", "origin", {1, 0}};
  d1.law = std::make_shared<mech::Polynomial345Law>(a.stroke1_rad, a.duration_s);
  mech::MotionDrive d2 = d1;
  d2.name = "d2";
  d2.coordinate = {mech::CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  d2.law = std::make_shared<mech::Polynomial345Law>(a.stroke2_rad, a.duration_s);
  m.motion_drives = {d1, d2};
  return m;
}

inline std::vector<pipeline::Part> two_link_parts(const TwoLinkArm& a = {},
                                                  const fem::IsotropicMaterial& material = steel()) {
  BarSize s1, s2;
  s1.length_m = a.l1_m;
  s2.length_m = a.l2_m;
  loads::LinkDefinition link1{"link1", nullptr, {{"J1", "x0"}, {"J2", "x1"}}, {}, {{"d1", "x0"}, {"d2", "x1"}}};
  loads::LinkDefinition link2{"link2", nullptr, {{"J2", "x0"}}, {}, {{"d2", "x0"}}};
  if (a.payload_kg > 0) link2.point_masses.push_back({"payload", "x1"});
  return {bar_part("link1", link1, s1, material), bar_part("link2", link2, s2, material)};
}

// SPEC §1 lever-chain manipulator with box parts.
struct LeverChain {
  mech::ManipulatorDefinition definition;
  std::vector<pipeline::Part> parts;
};

inline mech::ManipulatorDefinition lever_chain_definition() {
  mech::ManipulatorDefinition def;
  def.type = mech::ManipulatorType::LeverChain;
  def.geometry = mech::make_lever_chain_geometry(0.500, 0.350, 0.100, 0.075);
  def.lever = {12.0, {0.0, 0.25}, 0.3};  // replaced by the parts' when there are parts
  def.arm = {8.0, {-0.15, 0.0}, 0.1};
  def.gripper_mass_kg = 20.0;
  def.casting_mass_kg = 15.0;
  def.lever_motion = std::make_shared<mech::Polynomial345Law>(80 * kDeg, 2.0);
  return def;
}

inline std::vector<pipeline::Part> lever_chain_parts(const mech::ManipulatorDefinition& def,
                                                     const fem::IsotropicMaterial& material) {
  const double a = def.geometry.a_m, c = def.geometry.c_m;
  const double w = 0.04, t = 0.03;
  testing::BoxMeshOptions box;
  box.type = fem::ElementType::Hex20;
  box.length_m = {w, a, t};
  box.divisions = {2, 12, 1};
  fem::Mesh lever = testing::box_mesh(box);
  lever.nodes.col(0).array() -= 0.5 * w;
  lever.nodes.col(2).array() -= 0.5 * t;
  box.length_m = {c, w, t};
  box.divisions = {9, 2, 1};
  fem::Mesh arm = testing::box_mesh(box);
  arm.nodes.col(0).array() -= c;
  arm.nodes.col(1).array() -= 0.5 * w;
  arm.nodes.col(2).array() -= 0.5 * t;
  loads::LinkDefinition lever_def{"lever", nullptr, {{"A0", "y0"}, {"A", "y1"}}, {}, {{"lever_drive", "y0"}}};
  loads::LinkDefinition arm_def{"arm", nullptr, {{"A", "x1"}, {"chain", "x1"}}, {{"gripper", "x0"}, {"casting", "x0"}}};
  return {mesh_part("lever", lever_def, lever, material), mesh_part("arm", arm_def, arm, material)};
}

template <typename F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A column frame along +y from y = y_foot: x in [-h/2, h/2], z in [-t/2, t/2]
// (HEX20, `cells` along x, y, z), held on its foot face y0 (the ground's
// part); its top face y1 (centroid (0, y_foot + L, 0)) carries the ground's
// joints named in `attachments`. SI units.
inline pipeline::Part held_column_part(loads::LinkDefinition attachments, double L, double h, double t,
                                       std::array<int, 3> cells, double y_foot) {
  testing::BoxMeshOptions box;
  box.type = fem::ElementType::Hex20;
  box.length_m = {h, L, t};
  box.divisions = cells;
  fem::Mesh mesh = testing::box_mesh(box);
  mesh.nodes.col(0).array() -= 0.5 * h;
  mesh.nodes.col(1).array() += y_foot;
  mesh.nodes.col(2).array() -= 0.5 * t;
  pipeline::Part part = mesh_part("frame", std::move(attachments), std::move(mesh), steel());
  part.held_face = "y0";
  return part;
}

}  // namespace kinetofem::structure::test
