// The driver of the motion-to-stress pipeline (driver/motion_to_stress.hpp):
// the stages in order, what it writes, and its errors (case and stage named).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/four_bar.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "kinetofem/driver/motion_to_stress.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/verification/spec2_four_bar.hpp"
#include "../pipeline/pipeline_fixtures.hpp"

namespace kinetofem::driver {
namespace {

using namespace kinetofem::pipeline;  // the stages and their types

namespace fs = std::filesystem;
using test::error_of;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
bool starts_with(const std::string& text, const std::string& head) { return text.rfind(head, 0) == 0; }

// The beam pendulum (pipeline_fixtures.hpp) without parts: 60 deg in 0.5 s,
// 6 output times, the tip tracked.
MotionStressCase rigid_case(const std::string& dir) {
  MotionStressCase c;
  c.label = "case.toml";
  c.model = test::beam_pendulum();
  c.times = mech::equally_spaced_times(0.5, 6);
  c.tracked_points = {{"beam", "tip"}};
  c.results_file = test::fresh_dir(dir) / "run.h5";
  return c;
}

// The same with the beam as a part read from a .msh file (in m), held
// horizontal at rest for the static study.
MotionStressCase beam_case(const std::string& dir) {
  MotionStressCase c = rigid_case(dir);
  const fs::path msh = c.results_file.parent_path() / "beam.msh";
  meshes::write_msh(test::beam_mesh(), msh);
  PartSpec part;
  part.source = PartSource::File;
  part.file = msh;
  part.file_options.length_unit_m = 1.0;
  part.attachments = test::beam_pendulum_attachments();
  part.label = "part 'beam' (beam.msh)";
  c.parts = {part};
  c.static_pose = std::vector<double>{0.0};
  c.material = test::steel();
  return c;
}

std::vector<std::string> files_in(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& entry : fs::directory_iterator(dir)) out.push_back(entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}

TEST(RunMotionToStress, WithoutPartsWritesOnlyTheHistories) {
  const MotionStressCase c = rigid_case("driver_rigid");
  const MotionStressRun run = run_motion_to_stress(c, Log::quiet());
  EXPECT_TRUE(run.parts.empty());
  EXPECT_EQ(run.motion.frames.size(), 6u);
  EXPECT_FALSE(run.static_pose.has_value());
  EXPECT_EQ(run.model.bodies[1].mass_kg, 1.0);  // the case's own mass: no part replaces it
  ASSERT_TRUE(fs::exists(c.results_file));
  EXPECT_TRUE(fs::exists(fs::path(c.results_file).replace_extension(".xdmf")));
  const auto file = post::ResultsFile::open(c.results_file);
  EXPECT_TRUE(file.bodies().empty());
  EXPECT_EQ(file.mechanism_time(), c.times);
  const auto names = file.histories();
  for (const char* name : {"body.beam.angle", "joint.pivot.on_beam.force_world", "drive.swing.effort", "point.beam.tip"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(RunMotionToStress, PartGivesItsBodyTheMeshMassAndItsStressToTheFile) {
  const MotionStressCase c = beam_case("driver_beam");
  const MotionStressRun run = run_motion_to_stress(c, Log::quiet());
  // The body's mass from the mesh (analytic box: rho L H T; HEX20 exact to
  // round-off, 1e-12 relative), not the case's 1 kg placeholder.
  const test::BeamSize size;
  const double L = size.length_m, m_beam = 7850.0 * L * size.height_m * size.thickness_m, m_tip = 2.0;
  EXPECT_NEAR(run.model.bodies[1].mass_kg, m_beam, 1e-12 * m_beam);
  // Both the motion and the static study use it. Reference (analytic
  // statics): held horizontal, and at t = 0 of the 3-4-5 rise (at rest, zero
  // acceleration), the drive carries g (m_beam L/2 + m_tip L); 1e-9 relative.
  const double torque = units::kStandardGravity * (m_beam * L / 2 + m_tip * L);
  ASSERT_TRUE(run.static_pose.has_value());
  EXPECT_NEAR(run.static_pose->drives[0].effort, torque, 1e-9 * torque);
  EXPECT_NEAR(run.motion.frames[0].drives[0].effort, torque, 1e-9 * torque);
  // The part's stress, in equilibrium (1e-9, as tests/unit/loads), and in the file.
  ASSERT_EQ(run.parts.size(), 1u);
  EXPECT_EQ(run.parts[0].body, "beam");
  EXPECT_LT(run.parts[0].worst_equilibrium_residual, 1e-9);
  EXPECT_GT(run.parts[0].static_von_mises_pa, 0.0);
  const auto file = post::ResultsFile::open(c.results_file);
  EXPECT_EQ(file.bodies(), std::vector<std::string>{"beam"});
  EXPECT_EQ(file.series_times("beam"), c.times);
  EXPECT_FALSE(file.static_fields("beam").empty());
  EXPECT_FALSE(file.histories().empty());
}

TEST(RunMotionToStress, MotionErrorIsPrefixedByTheCaseAndTheStage) {
  // The SPEC §2 four-bar turned at a constant rate past its upper limit of
  // assembly (closed form, verification/spec2_four_bar.hpp) at t = 0.63 s.
  mech::ManipulatorDefinition def = test::lever_chain_definition(mech::ManipulatorType::Lever);
  const mech::FourBar four_bar = mech::make_equivalent_four_bar(def.geometry);
  const double limit =
      verification::spec2::closed_form_assembly_limits(def.geometry, four_bar).hi_rad - four_bar.design_input_rad();
  def.lever_motion = std::make_shared<mech::ConstantVelocityLaw>(limit / 0.63);
  MotionStressCase c = rigid_case("driver_motion_error");
  c.model = mech::make_manipulator_model(def);
  c.times = mech::equally_spaced_times(1.0, 21);
  c.tracked_points.clear();
  const std::string message = error_of([&] { run_motion_to_stress(c, Log::quiet()); });
  EXPECT_TRUE(starts_with(message, "case.toml: the motion cannot be run: mechanism 'lever manipulator'")) << message;
  EXPECT_FALSE(fs::exists(c.results_file));
}

TEST(RunMotionToStress, DynamicsErrorIsPrefixedByTheCaseAndTheStage) {
  MotionStressCase c = rigid_case("driver_dynamics_error");
  c.model.motion_drives.clear();  // a free pendulum: 1 DoF
  c.dynamics.method = DynamicsMethod::Kinematic;
  const std::string message = error_of([&] { run_motion_to_stress(c, Log::quiet()); });
  EXPECT_TRUE(starts_with(message, "case.toml: the motion cannot be run: the kinematic method needs a fully driven "
                                   "linkage (0 DoF); this one has 1 DoF"))
      << message;
}

TEST(RunMotionToStress, StaticPoseErrorIsPrefixedByTheCaseAndTheStage) {
  MotionStressCase c = rigid_case("driver_static_error");
  c.static_pose = std::vector<double>{0.1, 0.2};
  const std::string message = error_of([&] { run_motion_to_stress(c, Log::quiet()); });
  EXPECT_TRUE(starts_with(message, "case.toml: the static study's pose cannot be reached: static pose: 2 target values "
                                   "for 1 motion drives"))
      << message;
}

TEST(RunMotionToStress, PartErrorIsPrefixedByTheCase) {
  // A part file in m declared in mm: 1000 times too small. The size check
  // needs two joints on the part: a second link "link2" hangs on the beam's
  // tip (joint J2, 300 mm from the pivot), driven relative to the beam.
  MotionStressCase c = beam_case("driver_part_error");
  c.parts[0].file_options.length_unit_m = 1e-3;
  c.model.bodies[1].points["far"] = {0.3, 0.0};
  mech::Body link2;
  link2.name = "link2";
  link2.mass_kg = 1.0;
  link2.inertia_kgm2 = 0.01;
  link2.pose = {0.3, 0.0, 0.0};
  c.model.bodies.push_back(link2);
  c.model.joints.push_back(mech::make_revolute("J2", "beam", "far", "link2", "origin"));
  c.model.motion_drives.push_back(c.model.motion_drives[0]);
  c.model.motion_drives[1].name = "swing2";
  c.model.motion_drives[1].coordinate = {mech::CoordinateType::Angle, "beam", "origin", "link2", "origin", {1, 0}};
  c.parts[0].attachments.joints.push_back({"J2", "x1"});
  c.static_pose.reset();
  const std::string message = error_of([&] { run_motion_to_stress(c, Log::quiet()); });
  EXPECT_TRUE(starts_with(message, "case.toml: ")) << message;
  EXPECT_TRUE(contains(message, "part 'beam' (beam.msh): the part spans 0.3027 mm in the plane but its load points 'pivot' "
                                "and 'J2' are 300 mm apart: is its length unit right?"))
      << message;
  EXPECT_EQ(files_in(c.results_file.parent_path()), std::vector<std::string>{"beam.msh"});  // no results, no .tmp
}

TEST(RunMotionToStress, StressErrorLeavesNoResultsFile) {
  // The part keeps case mass properties 5 % off its mesh: its loads are out
  // of equilibrium (d'Alembert), found after the results file was started.
  MotionStressCase c = beam_case("driver_stress_error");
  c.parts[0].mass_from_mesh = false;
  c.model.bodies[1].mass_kg = 1.05 * 7850.0 * 0.3 * 0.04 * 0.02;
  c.model.bodies[1].inertia_kgm2 = 1.05 * 7850.0 * 0.3 * 0.04 * 0.02 * (0.09 + 0.0016) / 12;
  c.model.bodies[1].com_body = {0.15, 0.0};
  const std::string message = error_of([&] { run_motion_to_stress(c, Log::quiet()); });
  EXPECT_TRUE(starts_with(message, "case.toml: ")) << message;
  EXPECT_TRUE(contains(message, "link 'beam' at t = ")) << message;
  EXPECT_EQ(files_in(c.results_file.parent_path()), std::vector<std::string>{"beam.msh"});  // no results, no .tmp
}

TEST(RunMotionToStress, ResultsFileWithoutDirectoryGoesToTheWorkingDirectory) {
  // "run.h5" (no directory part): the file is written where the run is.
  struct InDirectory {  // the working directory changed for this test only
    fs::path before = fs::current_path();
    explicit InDirectory(const fs::path& dir) { fs::current_path(dir); }
    ~InDirectory() { fs::current_path(before); }
  };
  MotionStressCase c = rigid_case("driver_bare_name");
  const fs::path dir = c.results_file.parent_path();
  c.results_file = "run.h5";
  std::string message;
  {
    const InDirectory in(dir);
    message = error_of([&] { run_motion_to_stress(c, Log::quiet()); });
  }
  EXPECT_EQ(message, "(no error)");
  EXPECT_TRUE(fs::exists(dir / "run.h5"));
}

}  // namespace
}  // namespace kinetofem::driver
