#pragma once
// Mechanisms of two-bore links (tests/data/meshes/link_two_bores.geo: a link
// 300 x 60 x 20 mm, bores of diameter 30 mm at x = 0 and x = 0.24, TET10 of
// 10 mm) for the load-transfer and contact tests. The multibody bodies take
// the FE mesh's mass properties, so every link's loads are in equilibrium.
#include <memory>
#include <numbers>
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

// A double pendulum of two such links driven through 60 and -90 degrees in
// 0.5 s, a 3 kg tip mass at the second link's far bore.
inline mech::MultibodyModel double_pendulum() {
  constexpr double kDeg = std::numbers::pi / 180.0;
  mech::MultibodyModel m;
  m.name = "double pendulum";
  m.characteristic_length_m = 0.3;
  m.gravity = {0.0, -9.81};
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body link1;
  link1.name = "link1";
  loads::assign_mass_properties(link1, two_bore_link_model());
  link1.points["B2"] = {0.24, 0.0};
  mech::Body link2 = link1;
  link2.name = "link2";
  link2.pose = {0.24, 0.0, 0.0};
  link2.point_masses.push_back({"tip", 3.0, {0.24, 0.0}});
  m.bodies = {ground, link1, link2};
  m.joints.push_back({"J1", mech::JointType::Revolute, "ground", "origin", "link1", "origin"});
  m.joints.push_back({"J2", mech::JointType::Revolute, "link1", "B2", "link2", "origin"});
  mech::MotionDrive d1;
  d1.name = "D1";
  d1.coordinate = {mech::CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  d1.law = std::make_shared<mech::CycloidalLaw>(60 * kDeg, 0.5);
  mech::MotionDrive d2;
  d2.name = "D2";
  d2.coordinate = {mech::CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  d2.law = std::make_shared<mech::Polynomial345Law>(-90 * kDeg, 0.5);
  m.motion_drives = {d1, d2};
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
  mech::MotionDrive d;
  d.name = "D1";
  d.coordinate = {mech::CoordinateType::Angle, "ground", "origin", "link", "origin", {1, 0}};
  d.law = std::make_shared<mech::CycloidalLaw>(2 * std::numbers::pi, turn_time_s);
  m.motion_drives = {d};
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
