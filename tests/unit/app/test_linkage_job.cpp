// The "linkage" case type: the generic TOML format mapped onto
// mech::MultibodyModel, its runs and its error messages.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;
constexpr double kDeg = std::numbers::pi / 180.0;
const char* kLeverChainCase = "cases/mechanisms/lever_chain_linkage/case.toml";

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("kinetofem_test_linkage_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

LinkageRun run_file(const fs::path& path, const std::string& dir) {
  RunOptions options;
  options.case_path = path;
  options.output_dir = fresh_dir(dir);
  options.quiet = true;
  return run_linkage(CaseFile::load(path, linkage_schema()), options);
}

// The error message of reading (and, with run, running) a linkage case text.
std::string error_of(const std::string& text, bool run = false, const fs::path& path = "case.toml") {
  try {
    const CaseFile c = CaseFile::parse(text, path, linkage_schema());
    if (run) {
      RunOptions options;
      options.case_path = path;
      options.output_dir = fresh_dir("errors");
      options.quiet = true;
      run_linkage(c, options);
    } else {
      read_linkage_model(c);
    }
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// A pendulum lever of 100 mm on a frame; line 13 is joint[0].body_j.
const std::string kPendulum = R"([case]
type = "linkage"
[[body]]
name = "frame"
fixed = true
[[body]]
name = "lever"
mass_kg = 1.0
inertia_kgm2 = 0.001
pose_mm_deg = [0.0, 0.0, 60.0]
[[point]]
body = "lever"
name = "tip"
at_mm = [100.0, 0.0]
)";

std::string with_joint(const std::string& body_j = "lever", const std::string& point_i = "origin") {
  return kPendulum + "[[joint]]\nname = \"pivot\"\ntype = \"revolute\"\nbody_i = \"frame\"\npoint_i = \"" + point_i +
         "\"\nbody_j = \"" + body_j + "\"\n[simulation]\nduration_s = 1.0\noutput_times = 11\nmethod = \"kinematic\"\n";
}

std::string with_drive(const std::string& drive) {
  return with_joint() + "[[motion_drive]]\nname = \"push\"\n" + drive;
}

TEST(LinkageLeverChain, ReproducesClosedFormPositionFunction) {
  // Reference: SPEC §1 position function (4)-(7), mechanisms/lever_chain.hpp
  // (dpsi = arm angle - lever angle), and the 3-4-5 law of the drive
  // (80 deg in 2 s). Tolerance 1e-9 rad: the IDAS run keeps the constraints at
  // the Newton tolerance (drift ~1e-12 of a = 0.5 m).
  const LinkageRun run = run_file(kLeverChainCase, "lever_chain");
  const mech::LeverChain closed(mech::make_lever_chain_geometry(0.5, 0.35, 0.1, 0.075));
  const mech::Polynomial345Law law(80 * kDeg, 2.0);
  ASSERT_EQ(run.results.frames.size(), 101u);
  for (std::size_t k : {0u, 17u, 50u, 83u, 100u}) {
    const mech::Frame& f = run.results.frames[k];
    const double dphi = f.bodies[1].q.z(), theta = f.bodies[2].q.z();
    EXPECT_NEAR(dphi, law.at(f.t).s, 1e-9) << "t = " << f.t;
    EXPECT_NEAR(theta - dphi, closed.ctm(dphi).dpsi_rad, 1e-9) << "t = " << f.t;
    const mech::LeverChainPose pose = closed.pose(dphi);
    const Eigen::Vector2d h = f.bodies[2].q.head<2>() + Eigen::Rotation2Dd(theta) * Eigen::Vector2d(-0.35, 0.1);
    EXPECT_NEAR((h - pose.h.p).norm(), 0.0, 1e-9) << "t = " << f.t;
  }
  EXPECT_GT(run.min_chain_tension_n, 0.0);
}

TEST(LinkageLeverChain, ChainTensionMatchesManipulatorModel) {
  // Reference: the built-in manipulator model (make_manipulator_model, used by
  // the "manipulator" case type) with the same inputs: link masses, centres of
  // mass and inertias as in the linkage case, gripper 20 kg + casting 15 kg at
  // H, 3-4-5 law 80 deg in 2 s, gravity -y, IDAS. Both frames recompute the
  // multipliers from (q, v), so tension and torque agree to the integrators'
  // position accuracy: 1e-7 relative.
  const LinkageRun run = run_file(kLeverChainCase, "lever_chain_tension");
  mech::ManipulatorDefinition def;
  def.geometry = mech::make_lever_chain_geometry(0.5, 0.35, 0.1, 0.075);
  const auto& bodies = run.model.bodies;
  def.lever = {bodies[1].mass_kg, bodies[1].com_body, bodies[1].inertia_kgm2};
  def.arm = {bodies[2].mass_kg, bodies[2].com_body, bodies[2].inertia_kgm2};
  def.gripper_mass_kg = 20.0;
  def.casting_mass_kg = 15.0;
  def.lever_motion = std::make_shared<mech::Polynomial345Law>(80 * kDeg, 2.0);
  const mech::MultibodySystem system(mech::make_manipulator_model(def));
  std::vector<double> times;
  for (const auto& f : run.results.frames) times.push_back(f.t);
  const mech::Results ref = mech::simulate_ggl(system, times);
  double scale = 0.0;
  for (const auto& f : ref.frames) scale = std::max(scale, std::abs(f.chains[0].tension_N));
  for (std::size_t k = 0; k < times.size(); ++k) {
    EXPECT_NEAR(run.results.frames[k].chains[0].tension_N, ref.frames[k].chains[0].tension_N, 1e-7 * scale) << times[k];
    EXPECT_NEAR(run.results.frames[k].drives[0].effort, ref.frames[k].drives[0].effort, 1e-7 * scale * 0.5) << times[k];
  }
}

TEST(LinkageJob, WritesHistoriesOnlyResultsFile) {
  const LinkageRun run = run_file(kLeverChainCase, "histories");
  ASSERT_TRUE(fs::exists(run.results_file));
  EXPECT_TRUE(fs::exists(fs::path(run.results_file).replace_extension(".xdmf")));
  const auto file = post::ResultsFile::open(run.results_file);
  EXPECT_TRUE(file.bodies().empty());
  EXPECT_EQ(file.mechanism_time().size(), 101u);
  const auto names = file.histories();
  for (const char* name : {"body.arm.position", "body.arm.angle", "body.lever.angular_acceleration", "body.arm.com_acceleration",
                           "joint.A.on_arm.force_world", "joint.A.on_lever.force_body", "joint.chain.on_arm.moment",
                           "drive.lever_drive.effort", "drive.lever_drive.power", "chain.chain.tension",
                           "chain.chain.free_length"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  const auto tension = file.read_history("chain.chain.tension");
  EXPECT_EQ(tension.units, "N");
  EXPECT_DOUBLE_EQ(tension.values(50, 0), run.results.frames[50].chains[0].tension_N);
}

TEST(LinkageJob, DcMotorSliderCrankConservesEnergy) {
  // The slider-crank case (1 DoF, IDAS): energy balance dT + dV = W_motor + W_load
  // to 1e-6 of the energy scale, constraint drift below 1e-8 of the length.
  const LinkageRun run = run_file("cases/mechanisms/slider_crank/case.toml", "slider_crank");
  EXPECT_LT(run.results.summary.energy_balance_error, 1e-6);
  EXPECT_LT(run.results.summary.max_drift_relative, 1e-8);
  EXPECT_LT(run.results.summary.max_equilibrium_residual, 1e-12);
  EXPECT_GT(run.results.frames.back().drives[0].s_dot, 0.0);  // the motor turns the crank forward
}

TEST(LinkageErrors, UnknownBodyNamesFileLineAndBodies) {
  const std::string message = error_of(with_joint("lever2"));
  EXPECT_NE(message.find("case.toml:20: key 'joint[0].body_j' = \"lever2\": no body of that name (bodies: frame, lever)"),
            std::string::npos)
      << message;
}

TEST(LinkageErrors, UnknownPointNamesBodyAndItsPoints) {
  const std::string message = error_of(with_joint("lever", "tip"));
  EXPECT_NE(message.find("key 'joint[0].point_i' = \"tip\": body 'frame' has no point of that name (points: origin)"),
            std::string::npos)
      << message;
}

TEST(LinkageErrors, BadLawIsRejectedWithAllowedLaws) {
  const std::string message =
      error_of(with_drive("body_i = \"frame\"\nbody_j = \"lever\"\nlaw = \"sine\"\nstroke_deg = 10\nduration_s = 1\n"));
  EXPECT_NE(message.find("case.toml:29: key 'motion_drive"), std::string::npos) << message;
  EXPECT_NE(message.find(".law' = \"sine\" is not allowed"), std::string::npos) << message;
  EXPECT_NE(message.find("\"polynomial345\""), std::string::npos) << message;
}

TEST(LinkageErrors, StrokeInTheWrongUnitNamesTheRightKey) {
  const std::string message =
      error_of(with_drive("body_i = \"frame\"\nbody_j = \"lever\"\nlaw = \"cycloidal\"\nstroke_mm = 10\nduration_s = 1\n"));
  EXPECT_NE(message.find("key 'motion_drive[0].stroke_mm'"), std::string::npos) << message;
  EXPECT_NE(message.find("use 'stroke_deg'"), std::string::npos) << message;
}

TEST(LinkageErrors, MissingCsvFileNamesKeyAndPath) {
  const std::string message =
      error_of(with_drive("body_i = \"frame\"\nbody_j = \"lever\"\nlaw = \"csv\"\nfile = \"no_such_law.csv\"\n"), false,
               fresh_dir("csv") / "case.toml");
  EXPECT_NE(message.find("key 'motion_drive[0].file' = \"no_such_law.csv\": no such file"), std::string::npos) << message;
}

TEST(LinkageErrors, CsvLawInDegreesDrivesTheLever) {
  // A table s(t) in deg, relative to the case file: the lever follows it
  // (natural cubic spline through the knots: exact at the knots).
  const fs::path dir = fresh_dir("csv_ok");
  std::ofstream(dir / "law.csv") << "t_s, s_deg\n0, 0\n0.5, 10\n1.0, 30\n";
  std::ofstream(dir / "case.toml") << with_drive("body_i = \"frame\"\nbody_j = \"lever\"\nlaw = \"csv\"\nfile = \"law.csv\"\n");
  const LinkageRun run = run_file(dir / "case.toml", "csv_ok_out");
  EXPECT_NEAR(run.results.frames[5].bodies[1].q.z(), (60 + 10) * kDeg, 1e-10);
  EXPECT_NEAR(run.results.frames[10].bodies[1].q.z(), (60 + 30) * kDeg, 1e-10);
}

TEST(LinkageErrors, MechanismThatCannotBeAssembledNamesTheTime) {
  // The tip of a 100 mm lever is pushed along x from 50 mm by 100 mm: it
  // reaches its dead centre (x = 100 mm) at t = 0.5 s and cannot follow beyond.
  const std::string message = error_of(
      with_drive("coordinate = \"displacement\"\nbody_i = \"frame\"\nbody_j = \"lever\"\npoint_j = \"tip\"\n"
                 "law = \"polynomial345\"\nstroke_mm = 100\nduration_s = 1\n"),
      true);
  EXPECT_NE(message.find("the motion cannot be run"), std::string::npos) << message;
  EXPECT_NE(message.find("at t = "), std::string::npos) << message;
}

TEST(LinkageErrors, DuplicateJointName) {
  std::string text = with_joint();
  text += "[[joint]]\nname = \"pivot\"\ntype = \"revolute\"\nbody_i = \"frame\"\nbody_j = \"lever\"\n";
  const std::string message = error_of(text);
  EXPECT_NE(message.find("key 'joint[1].name' = \"pivot\": a second joint, motion drive or transmission of that name"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace kinetofem::app
