#pragma once
// Mechanisms of two-bore links (tests/data/meshes/link_two_bores.geo: a link
// 300 x 60 x 20 mm, bores of diameter 30 mm at x = 0 and x = 0.24, TET10 of
// 10 mm) for the load-transfer and contact tests. The multibody bodies take
// the FE mesh's mass properties, so every link's loads are in equilibrium.
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::testing {

inline const fem::FeModel& two_bore_link_model() {
  static const fem::FeModel model = [] {
    fem::FeModel m;
    meshes::MeshOptions options;
    options.element_size_m = 0.01;
    options.order = 2;
    m.mesh = meshes::mesh_geometry("tests/data/meshes/link_two_bores.geo", options);
    return m;
  }();
  return model;
}

// The model with a 3-2-1 support on the nodes of no bore (contact nodes
// must stay free).
inline fem::FeModel supported_two_bore_link() {
  fem::FeModel fe = two_bore_link_model();
  std::vector<char> on_bore(size_t(fe.mesh.node_count()), 0);
  for (const char* bore : {"bore_1", "bore_2"})
    for (const fem::Index n : fem::nodes_of_faces(fe.mesh.face_set(bore))) on_bore[size_t(n)] = 1;
  std::vector<fem::Index> free;
  for (fem::Index i = 0; i < fe.mesh.node_count(); ++i)
    if (!on_bore[size_t(i)]) free.push_back(i);
  fe.supports = fem::three_two_one_support(fe.mesh, free);
  return fe;
}

// A mechanism of two-bore links under gravity -y: its fixed ground (body 0)
// and a link body to copy (the mesh's mass properties; its far bore's
// point "B2" = (0.24, 0)).
inline mech::MultibodyModel two_bore_link_mechanism(const std::string& name, double characteristic_length_m,
                                                    mech::Body& link) {
  mech::MultibodyModel m;
  m.name = name;
  m.characteristic_length_m = characteristic_length_m;
  m.gravity = {0.0, -9.81};
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  m.bodies = {ground};
  link = mech::Body{};
  loads::assign_mass_properties(link, two_bore_link_model());
  link.points["B2"] = {0.24, 0.0};
  return m;
}

// An angle drive of body_j against body_i (their origins) by `law`.
inline mech::MotionDrive angle_drive(const std::string& name, const std::string& body_i, const std::string& body_j,
                                     std::shared_ptr<mech::MotionLaw> law) {
  mech::MotionDrive d;
  d.name = name;
  d.coordinate = {mech::CoordinateType::Angle, body_i, "origin", body_j, "origin", {1, 0}};
  d.law = std::move(law);
  return d;
}

// A double pendulum of two such links driven through 60 and -90 degrees in
// 0.5 s, a 3 kg tip mass at the second link's far bore.
inline mech::MultibodyModel double_pendulum() {
  constexpr double kDeg = std::numbers::pi / 180.0;
  mech::Body link1;
  mech::MultibodyModel m = two_bore_link_mechanism("double pendulum", 0.3, link1);
  link1.name = "link1";
  mech::Body link2 = link1;
  link2.name = "link2";
  link2.pose = {0.24, 0.0, 0.0};
  link2.point_masses.push_back({"tip", 3.0, {0.24, 0.0}});
  m.bodies.push_back(link1);
  m.bodies.push_back(link2);
  m.joints.push_back({"J1", mech::JointType::Revolute, "ground", "origin", "link1", "origin"});
  m.joints.push_back({"J2", mech::JointType::Revolute, "link1", "B2", "link2", "origin"});
  m.motion_drives = {angle_drive("D1", "ground", "link1", std::make_shared<mech::CycloidalLaw>(60 * kDeg, 0.5)),
                     angle_drive("D2", "link1", "link2", std::make_shared<mech::Polynomial345Law>(-90 * kDeg, 0.5))};
  return m;
}

// A parallelogram four-bar of such links (crank link1 from the ground's
// origin, coupler link2, rocker link3 from the ground's P4 = (0.24, 0)), the
// crank driven 20 degrees down from upright in 0.5 s under gravity, a 5 kg
// mass "mass" at the coupler's far bore: statically determinate in the
// plane, indeterminate out of it (four pins, three bodies).
inline mech::MultibodyModel parallelogram() {
  constexpr double kDeg = std::numbers::pi / 180.0;
  mech::Body link;
  mech::MultibodyModel m = two_bore_link_mechanism("parallelogram", 0.24, link);
  m.bodies[0].points["P4"] = {0.24, 0.0};
  mech::Body link1 = link, link2 = link, link3 = link;
  link1.name = "link1";
  link1.pose = {0.0, 0.0, 90 * kDeg};
  link2.name = "link2";
  link2.pose = {0.0, 0.24, 0.0};
  link2.point_masses.push_back({"mass", 5.0, {0.24, 0.0}});
  link3.name = "link3";
  link3.pose = {0.24, 0.0, 90 * kDeg};
  m.bodies.insert(m.bodies.end(), {link1, link2, link3});
  m.joints.push_back({"J1", mech::JointType::Revolute, "ground", "origin", "link1", "origin"});
  m.joints.push_back({"J2", mech::JointType::Revolute, "link1", "B2", "link2", "origin"});
  m.joints.push_back({"J3", mech::JointType::Revolute, "link2", "B2", "link3", "B2"});
  m.joints.push_back({"J4", mech::JointType::Revolute, "ground", "P4", "link3", "origin"});
  m.motion_drives = {angle_drive("D1", "ground", "link1", std::make_shared<mech::CycloidalLaw>(-20 * kDeg, 0.5))};
  return m;
}

// A link (mass properties from `model`, its pin at the body origin) turned
// through a full turn about that pin in `turn_time_s` (cycloidal law) under
// gravity, a point mass "mass" of `mass_kg` at `far_point_m`: in the link's
// frame its weight, and so the pin's force on the bore, turns once about the
// pin. Joint "J1" (ground, link), drive "D1".
inline mech::MultibodyModel turning_link(const fem::FeModel& model, const Eigen::Vector2d& far_point_m, double mass_kg,
                                         double turn_time_s) {
  mech::MultibodyModel m;
  m.name = "turning link";
  m.characteristic_length_m = far_point_m.norm();
  m.gravity = {0.0, -9.81};
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body link;
  link.name = "link";
  loads::assign_mass_properties(link, model);
  link.point_masses.push_back({"mass", mass_kg, far_point_m});
  m.bodies = {ground, link};
  m.joints.push_back({"J1", mech::JointType::Revolute, "ground", "origin", "link", "origin"});
  m.motion_drives = {angle_drive("D1", "ground", "link", std::make_shared<mech::CycloidalLaw>(2 * std::numbers::pi, turn_time_s))};
  return m;
}

// The two-bore link turned slowly (20 s) about its first bore, 40 kg at the other.
inline mech::MultibodyModel turning_link() { return turning_link(two_bore_link_model(), {0.24, 0.0}, 40.0, 20.0); }

inline std::vector<double> even_times(double end_s, int intervals) {
  std::vector<double> t;
  for (int k = 0; k <= intervals; ++k) t.push_back(end_s * k / intervals);
  return t;
}

}  // namespace kinetofem::testing
