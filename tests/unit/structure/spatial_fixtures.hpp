#pragma once
// Small spatial mechanisms with box parts shared by the spatial elastic
// assembly's tests (tests/verification/structure/, tests/verification/
// vibration/): HEX20 bars (structure_fixtures.hpp bar_mesh) as
// structure::SpatialPart, SI units.
//
//   spatial_bar    a bar as the part of a body, its joints and point masses
//                  through named face sets.
//   give_mass_of   each body of the model gets its part's mass properties.
//   spatial_arm    a two-link arm: "J1" a revolute about the vertical
//                  (ground - link1), "J2" a revolute about link1's own y
//                  axis (link1 "tip" - link2), so link2 pitches out of any
//                  plane; motion drives "d1", "d2" (3-4-5 rises of 60 and
//                  -50 deg in 1 s); a 3 kg payload with rotary inertia at
//                  link2's "tip" (face x1); gravity -z.
//   slide_model    an arm on the two lands (50 mm windows of the sleeve's
//                  face y0, 25 mm from its ends) of a sleeve fixed to the
//                  ground, its axis oblique, pushed by the translation drive
//                  "push" by push_m in 1 s from 0.2 m behind the sleeve's
//                  origin; the arm's stations every 25 mm on its face y1;
//                  a 5 kg payload at the arm's tip.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/slide_stations.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/structure/spatial_part.hpp"
#include "structure_fixtures.hpp"

namespace kinetofem::structure::test {

namespace sp = mech::spatial;

inline SpatialPart spatial_bar(const std::string& body, const BarSize& size,
                               std::vector<loads::SpatialAttachment> joints,
                               std::vector<loads::SpatialAttachment> masses = {}) {
  SpatialPart part;
  part.label = "part '" + body + "' (test bar)";
  part.attachments.body = body;
  part.attachments.joints = std::move(joints);
  part.attachments.point_masses = std::move(masses);
  part.model.mesh = bar_mesh(size);
  part.model.material = steel();
  return part;
}

inline void give_mass_of(sp::Model& model, const std::vector<SpatialPart>& parts) {
  for (const SpatialPart& p : parts)
    for (sp::Body& b : model.bodies)
      if (b.name == p.body()) loads::assign_mass_properties(b, p.model);
}

struct SpatialArm {
  sp::Model model;
  std::vector<SpatialPart> parts;
};

inline SpatialArm spatial_arm() {
  const BarSize link1_size{.length_m = 0.40, .height_m = 0.04, .thickness_m = 0.03, .cells = {16, 2, 2}};
  const BarSize link2_size{.length_m = 0.30, .height_m = 0.03, .thickness_m = 0.03, .cells = {12, 2, 2}};
  SpatialArm arm;
  sp::Model& m = arm.model;
  m.name = "spatial two-link arm";
  m.characteristic_length_m = 0.7;
  sp::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  const Eigen::Matrix3d R1 = Eigen::AngleAxisd(30 * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d R2 = R1 * Eigen::AngleAxisd(-40 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  sp::Body link1;
  link1.name = "link1";
  sp::set_rotation(link1, R1);
  link1.points["tip"] = Eigen::Vector3d(link1_size.length_m, 0, 0);
  sp::Body link2;
  link2.name = "link2";
  sp::set_rotation(link2, R2);
  link2.position = R1 * Eigen::Vector3d(link1_size.length_m, 0, 0);
  link2.points["tip"] = Eigen::Vector3d(link2_size.length_m, 0, 0);
  sp::PointMass payload;
  payload.name = "payload";
  payload.mass_kg = 3.0;
  payload.position_body = link2.points["tip"];
  payload.inertia_kgm2 = Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal();
  link2.point_masses = {payload};
  m.bodies = {ground, link1, link2};
  m.joints = {sp::make_joint("J1", sp::JointType::Revolute, "ground", "origin", "link1", "origin",
                             Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()),
              sp::make_joint("J2", sp::JointType::Revolute, "link1", "tip", "link2", "origin", Eigen::Vector3d::UnitY(),
                             Eigen::Vector3d::UnitY())};
  sp::MotionDrive d1;
  d1.name = "d1";
  d1.joint = "J1";
  d1.law = std::make_shared<mech::Polynomial345Law>(60 * kDeg, 1.0);
  sp::MotionDrive d2 = d1;
  d2.name = "d2";
  d2.joint = "J2";
  d2.law = std::make_shared<mech::Polynomial345Law>(-50 * kDeg, 1.0);
  m.motion_drives = {d1, d2};
  arm.parts = {spatial_bar("link1", link1_size, {{"J1", "x0"}, {"d1", "x0"}, {"J2", "x1"}, {"d2", "x1"}}),
               spatial_bar("link2", link2_size, {{"J2", "x0"}, {"d2", "x0"}}, {{"payload", "x1"}})};
  give_mass_of(m, arm.parts);
  return arm;
}

struct SlideModel {
  sp::Model model;
  std::vector<SpatialPart> parts;
};

inline SlideModel slide_model(double push_m) {
  const BarSize sleeve_size{.length_m = 0.40, .height_m = 0.06, .thickness_m = 0.06, .cells = {16, 2, 2}};
  const BarSize arm_size{.length_m = 0.60, .height_m = 0.03, .thickness_m = 0.03, .cells = {48, 2, 2}};
  SlideModel out;
  sp::Model& m = out.model;
  m.name = "arm in a sleeve";
  m.characteristic_length_m = 0.6;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(20 * kDeg, Eigen::Vector3d(0.3, -1.0, 0.2).normalized()).toRotationMatrix();
  sp::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  sp::Body sleeve;
  sleeve.name = "sleeve";
  sp::set_rotation(sleeve, R);
  sp::Body arm;
  arm.name = "arm";
  sp::set_rotation(arm, R);
  arm.position = R * Eigen::Vector3d(-0.2, 0, 0);
  arm.points["tip"] = Eigen::Vector3d(arm_size.length_m, 0, 0);
  sp::PointMass payload;
  payload.name = "payload";
  payload.mass_kg = 5.0;
  payload.position_body = arm.points["tip"];
  arm.point_masses = {payload};
  m.bodies = {ground, sleeve, arm};
  m.joints = {sp::make_joint("fix", sp::JointType::Fixed, "ground", "origin", "sleeve", "origin"),
              sp::make_joint("slide", sp::JointType::Prismatic, "sleeve", "origin", "arm", "origin",
                             Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX())};
  sp::MotionDrive push;
  push.name = "push";
  push.joint = "slide";
  push.coordinate = sp::DriveCoordinate::Translation;
  push.law = std::make_shared<mech::Polynomial345Law>(push_m, 1.0);
  m.motion_drives = {push};

  SpatialPart sleeve_part = spatial_bar("sleeve", sleeve_size, {{"fix", "x0"}});
  SpatialPart arm_part = spatial_bar("arm", arm_size, {}, {{"payload", "x1"}});
  // The lands: two windows 50 mm long on the sleeve's face y0, centred 25 mm
  // from its ends; the arm's stations on its face y1 every 25 mm.
  const loads::SlideStations lands = loads::add_slide_stations(sleeve_part.model.mesh, "y0", Eigen::Vector3d::Zero(),
                                                               Eigen::Vector3d::UnitX(), 0.05, 0.35);
  require(lands.face_sets.size() == 2, "slide_model: the sleeve has {} lands, not 2", lands.face_sets.size());
  loads::SpatialSlideAttachment slide;
  slide.joint = "slide";
  slide.drive = "push";
  slide.rear_m = lands.s_m.front();
  slide.front_m = lands.s_m.back();
  slide.rear_face_set = lands.face_sets.front();
  slide.front_face_set = lands.face_sets.back();
  slide.stations = loads::add_slide_stations(arm_part.model.mesh, "y1", Eigen::Vector3d::Zero(),
                                             Eigen::Vector3d::UnitX(), 0.05, 0.025);
  sleeve_part.attachments.slides = {slide};
  arm_part.attachments.slides = {slide};
  out.parts = {sleeve_part, arm_part};
  give_mass_of(m, out.parts);
  return out;
}

}  // namespace kinetofem::structure::test
