#pragma once
// Small models shared by the pipeline stage tests (tests/unit/pipeline/):
//
//   beam_mesh     a straight beam L x H x T (structured HEX20 box,
//                 tests/support box_mesh) in the body frame of a link whose
//                 joints lie on the beam axis: x in [0, L], y in [-H/2, H/2],
//                 z in [-T/2, T/2] (symmetric about the mechanism plane, as
//                 the parametric links are), so the centre of face "x0" is
//                 the body origin and that of "x1" is (L, 0). Face sets and
//                 node sets x0, x1, y0, y1, z0, z1; node set "boundary".
//   beam_part     that mesh as a pipeline::Part of body `body` (built by
//                 hand, no Gmsh), with its mass properties.
//   beam_pendulum a frame and the beam "beam" on a revolute "pivot" at the
//                 beam's origin, driven by "swing" (3-4-5 rise of the beam's
//                 angle), with a point mass "tip_mass" at the tip (L, 0).
//   double_link   frame - "beam" - "link2": joints "J1" (frame origin, beam
//                 origin) and "J2" (beam point "tip" = (L, 0), link2 origin):
//                 a two-joint link for the fit checks.
//   lever_chain_definition  the SPEC §1 example (a = 500, c = 350, h = 100,
//                 r = 75 mm) as a mech::ManipulatorDefinition.
//   error_of      the message of the Error a callable throws.
// SI units throughout.
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/testing/box_mesh.hpp"

namespace kinetofem::pipeline::test {

inline constexpr double kDeg = std::numbers::pi / 180.0;

struct BeamSize {
  double length_m = 0.30, height_m = 0.04, thickness_m = 0.02;
  int cells_along = 10;
  fem::ElementType type = fem::ElementType::Hex20;
};

inline fem::Mesh beam_mesh(const BeamSize& size = {}) {
  testing::BoxMeshOptions box;
  box.length_m = {size.length_m, size.height_m, size.thickness_m};
  box.divisions = {size.cells_along, 2, 1};
  box.type = size.type;
  fem::Mesh mesh = testing::box_mesh(box);
  mesh.nodes.col(1).array() -= 0.5 * size.height_m;
  mesh.nodes.col(2).array() -= 0.5 * size.thickness_m;
  return mesh;
}

inline fem::IsotropicMaterial steel() { return fem::IsotropicMaterial{}; }  // E 210 GPa, nu 0.3, 7850 kg/m^3

inline Part beam_part(const std::string& body, loads::LinkDefinition attachments, const BeamSize& size = {}) {
  Part part;
  attachments.body = body;
  attachments.model = nullptr;  // set by the stages that need it (a copied Part would dangle)
  part.attachments = std::move(attachments);
  part.label = "part '" + body + "' (test beam)";
  part.model.mesh = beam_mesh(size);
  part.model.material = steel();
  part.mass = fem::mass_properties(part.model.mesh, part.model.material);
  return part;
}

inline mech::MultibodyModel beam_pendulum(double stroke_rad = 60 * kDeg, double duration_s = 0.5,
                                          double tip_mass_kg = 2.0, const BeamSize& size = {}) {
  mech::MultibodyModel m;
  m.name = "beam pendulum";
  m.characteristic_length_m = size.length_m;
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body beam;
  beam.name = "beam";
  beam.mass_kg = 1.0;  // placeholders: the part's mass properties replace them
  beam.inertia_kgm2 = 0.01;
  beam.points["tip"] = {size.length_m, 0.0};
  if (tip_mass_kg > 0) beam.point_masses.push_back({"tip_mass", tip_mass_kg, {size.length_m, 0.0}});
  m.bodies = {frame, beam};
  m.joints.push_back(mech::make_revolute("pivot", "frame", "origin", "beam", "origin"));
  mech::MotionDrive swing;
  swing.name = "swing";
  swing.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "beam", "origin", {1, 0}};
  swing.law = std::make_shared<mech::Polynomial345Law>(stroke_rad, duration_s);
  m.motion_drives.push_back(swing);
  return m;
}

// The beam's loads: the pivot and the drive's torque on face x0, the tip mass on x1.
inline loads::LinkDefinition beam_pendulum_attachments() {
  return {"beam", nullptr, {{"pivot", "x0"}}, {{"tip_mass", "x1"}}, {{"swing", "x0"}}};
}

inline mech::MultibodyModel double_link(const BeamSize& size = {}) {
  mech::MultibodyModel m;
  m.name = "double link";
  m.characteristic_length_m = size.length_m;
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body beam;
  beam.name = "beam";
  beam.mass_kg = 1.0;
  beam.inertia_kgm2 = 0.01;
  beam.points["tip"] = {size.length_m, 0.0};
  mech::Body link2 = beam;
  link2.name = "link2";
  link2.pose = {size.length_m, 0.0, 0.0};
  m.bodies = {frame, beam, link2};
  m.joints.push_back(mech::make_revolute("J1", "frame", "origin", "beam", "origin"));
  m.joints.push_back(mech::make_revolute("J2", "beam", "tip", "link2", "origin"));
  return m;
}

inline loads::LinkDefinition double_link_attachments() { return {"beam", nullptr, {{"J1", "x0"}, {"J2", "x1"}}}; }

inline mech::ManipulatorDefinition lever_chain_definition(mech::ManipulatorType type = mech::ManipulatorType::LeverChain) {
  mech::ManipulatorDefinition def;
  def.type = type;
  def.geometry = mech::make_lever_chain_geometry(0.500, 0.350, 0.100, 0.075);
  def.lever = {12.0, {0.0, 0.25}, 0.3};
  def.arm = {8.0, {-0.15, 0.0}, 0.1};
  def.rocker = {10.0, {0.0, 0.2}, 0.15};
  def.gripper_mass_kg = 20.0;
  def.casting_mass_kg = 15.0;
  def.lever_motion = std::make_shared<mech::Polynomial345Law>(80 * kDeg, 2.0);
  return def;
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

inline std::filesystem::path fresh_dir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("kinetofem_test_pipeline_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Three beam pendulum parts of different lengths: different parts, different
// factors (the factor-sharing tests).
inline std::vector<Part> three_beams() {
  std::vector<Part> parts;
  for (int k = 0; k < 3; ++k) {
    BeamSize size;
    size.length_m *= 1.0 + 0.25 * k;
    parts.push_back(beam_part("beam" + std::to_string(k), beam_pendulum_attachments(), size));
  }
  return parts;
}

// A quiet log that outlives the analyses made with it (they keep a reference
// to their log: a temporary Log::quiet() would dangle).
inline const Log& quiet_log() {
  static const Log log = Log::quiet();
  return log;
}

}  // namespace kinetofem::pipeline::test
