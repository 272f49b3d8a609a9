// Stage "write the histories" (pipeline/histories.hpp): the mechanism's
// quantities over the output times in the results file's /mechanism group,
// their names and units (docs/results.md), and the world path of body points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/pipeline/histories.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

namespace fs = std::filesystem;
using test::error_of;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct Written {
  mech::MultibodyModel model;
  mech::Results results;
  fs::path file;
};

// The SPEC §1 lever-chain manipulator, 80 deg in 2 s, 11 output times
// (kinematic), its drive renamed "lever drive" and a point "grip point" at H
// on the arm; histories with the tracked points H and "grip point".
const Written& lever_chain_histories() {
  static const Written w = [] {
    Written out;
    out.model = mech::make_manipulator_model(test::lever_chain_definition());
    out.model.motion_drives[0].name = "lever drive";
    out.model.bodies[2].points["grip point"] = out.model.bodies[2].points.at("H");
    out.results = mech::run_kinematics(mech::MultibodySystem(out.model), mech::equally_spaced_times(2.0, 11));
    // One folder per test process: ctest runs the tests of this file in parallel.
    out.file = test::fresh_dir(std::string("histories_") + ::testing::UnitTest::GetInstance()->current_test_info()->name()) /
               "lever_chain.h5";
    post::ResultsWriter writer(out.file, {});
    write_mechanism_histories(writer, out.model, out.results, {{"arm", "H"}, {"arm", "grip point"}});
    writer.commit();
    return out;
  }();
  return w;
}

TEST(WriteMechanismHistories, EveryQuantityIsWrittenWithItsUnit) {
  // Reference: the names and units of histories.hpp / docs/results.md.
  const Written& w = lever_chain_histories();
  const auto file = post::ResultsFile::open(w.file);
  EXPECT_TRUE(file.bodies().empty());
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"body.arm.position", "m"},          {"body.lever.angle", "rad"},
      {"body.arm.velocity", "m/s"},        {"body.arm.angular_velocity", "rad/s"},
      {"body.arm.acceleration", "m/s^2"},  {"body.lever.angular_acceleration", "rad/s^2"},
      {"body.arm.com_position", "m"},      {"body.arm.com_acceleration", "m/s^2"},
      {"joint.A.on_arm.force_world", "N"}, {"joint.A.on_lever.force_body", "N"},
      {"joint.A0.on_lever.moment", "N*m"}, {"joint.chain.on_arm.force_world", "N"},
      {"drive.lever_drive.s", "rad"},      {"drive.lever_drive.s_dot", "rad/s"},
      {"drive.lever_drive.s_ddot", "rad/s^2"}, {"drive.lever_drive.effort", "N*m"},
      {"drive.lever_drive.power", "W"},    {"chain.chain.tension", "N"},
      {"chain.chain.free_length", "m"},    {"chain.chain.wrap_angle", "rad"},
      {"energy.kinetic", "J"},             {"energy.potential", "J"},
      {"energy.work_drives", "J"},         {"energy.work_other", "J"},
      {"check.drift_position", "m"},       {"check.equilibrium_residual", "1"},
      {"point.arm.H", "m"},                {"point.arm.grip_point", "m"}};
  const auto names = file.histories();
  for (const auto& [name, unit] : expected) {
    ASSERT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
    const post::FieldData h = file.read_history(name);
    EXPECT_EQ(h.units, unit) << name;
    EXPECT_EQ(h.values.rows(), 11) << name;
  }
  const post::FieldData position = file.read_history("body.arm.position");
  EXPECT_EQ(position.component_names, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(file.read_history("point.arm.H").values.cols(), 2);
  EXPECT_EQ(file.read_history("body.lever.angle").values.cols(), 1);
}

TEST(WriteMechanismHistories, NamesWithOtherCharactersGetAnUnderscore) {
  // "lever drive" and "grip point" (histories.hpp: letters, digits, '_', '-'
  // and '.' are kept, anything else becomes '_'); no name with a space.
  const auto names = post::ResultsFile::open(lever_chain_histories().file).histories();
  EXPECT_NE(std::find(names.begin(), names.end(), "drive.lever_drive.effort"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "point.arm.grip_point"), names.end());
  for (const auto& name : names) EXPECT_EQ(name.find(' '), std::string::npos) << name;
}

TEST(WriteMechanismHistories, ValuesAreTheFramesValuesAtTheMechanismTimes) {
  const Written& w = lever_chain_histories();
  const auto file = post::ResultsFile::open(w.file);
  const std::vector<double> t = file.mechanism_time();
  ASSERT_EQ(t.size(), w.results.frames.size());
  const auto angle = file.read_history("body.arm.angle").values;
  const auto force = file.read_history("joint.A.on_arm.force_world").values;  // arm = body_j of joint A
  const auto effort = file.read_history("drive.lever_drive.effort").values;
  const auto tension = file.read_history("chain.chain.tension").values;
  for (std::size_t k = 0; k < t.size(); ++k) {
    const mech::Frame& f = w.results.frames[k];
    const auto r = Eigen::Index(k);
    // Exact: the histories are copies of the frames' doubles.
    EXPECT_EQ(t[k], f.t);
    EXPECT_EQ(angle(r, 0), f.bodies[2].q.z());
    EXPECT_EQ(force(r, 0), f.joints[1].on_j.force_world.x());
    EXPECT_EQ(force(r, 1), f.joints[1].on_j.force_world.y());
    EXPECT_EQ(effort(r, 0), f.drives[0].effort);
    EXPECT_EQ(tension(r, 0), f.chains[0].tension_N);
  }
}

TEST(WriteMechanismHistories, PointPathIsTheClosedFormPathOfH) {
  // Reference: H of the SPEC §1 position function (mechanisms/lever_chain.hpp,
  // (15)) at the lever angle of each frame; 1e-9 m (the kinematic positions
  // are exact to the Newton tolerance 1e-13 of a).
  const Written& w = lever_chain_histories();
  const auto path = post::ResultsFile::open(w.file).read_history("point.arm.H").values;
  const mech::LeverChain closed(test::lever_chain_definition().geometry);
  for (std::size_t k = 0; k < w.results.frames.size(); ++k) {
    const Eigen::Vector2d h = closed.pose(w.results.frames[k].bodies[1].q.z()).h.p;
    EXPECT_NEAR(path(Eigen::Index(k), 0), h.x(), 1e-9) << k;
    EXPECT_NEAR(path(Eigen::Index(k), 1), h.y(), 1e-9) << k;
  }
}

mech::MultibodyModel slider_and_motor() {
  mech::MultibodyModel m;
  m.name = "slider";
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body slider;
  slider.name = "slider";
  slider.mass_kg = 2.0;
  slider.inertia_kgm2 = 0.01;
  m.bodies = {frame, slider};
  m.joints.push_back(mech::make_prismatic("rail", "frame", "origin", "slider", "origin", {1.0, 0.0}));
  mech::MotionDrive push;
  push.name = "push";
  push.coordinate = {mech::CoordinateType::Displacement, "frame", "origin", "slider", "origin", {1, 0}};
  push.law = std::make_shared<mech::Polynomial345Law>(0.1, 1.0);
  m.motion_drives.push_back(push);
  return m;
}

TEST(WriteMechanismHistories, DisplacementDriveHasLengthAndForceUnits) {
  const mech::MultibodyModel model = slider_and_motor();
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), mech::equally_spaced_times(1.0, 5));
  const fs::path path = test::fresh_dir("histories_slider") / "slider.h5";
  post::ResultsWriter writer(path, {});
  write_mechanism_histories(writer, model, results);
  writer.commit();
  const auto file = post::ResultsFile::open(path);
  EXPECT_EQ(file.read_history("drive.push.s").units, "m");
  EXPECT_EQ(file.read_history("drive.push.s_dot").units, "m/s");
  EXPECT_EQ(file.read_history("drive.push.s_ddot").units, "m/s^2");
  EXPECT_EQ(file.read_history("drive.push.effort").units, "N");
  // The stroke of the law (0.1 m) at the end (exact to the assembly's 1e-13 m).
  EXPECT_NEAR(file.read_history("drive.push.s").values(4, 0), 0.1, 1e-12);
}

TEST(DriveEffortUnit, CountsMotionDrivesFirstThenForceDrives) {
  // mech::Frame::drives order: motion drives, then force drives.
  mech::MultibodyModel model = slider_and_motor();
  mech::ForceDrive motor;
  motor.name = "motor";
  motor.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "slider", "origin", {1, 0}};
  model.force_drives.push_back(motor);
  EXPECT_EQ(drive_effort_unit(model, 0), "N");
  EXPECT_EQ(drive_effort_unit(model, 1), "N*m");
}

TEST(PointInWorld, PointOfARotatedBodyIsTurnedAndMoved) {
  // Reference (analytic): r = (x, y) + R(theta) p; theta = 90 deg,
  // p = (0.3, 0.1): (1 - 0.1, 2 + 0.3). Tolerance 1e-15 m: cos(pi/2) = 6e-17
  // in double, times 0.3 m, plus the sums' round-off.
  mech::MultibodyModel model;
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body link;
  link.name = "link";
  link.points["P"] = {0.3, 0.1};
  model.bodies = {ground, link};
  mech::Frame frame;
  frame.bodies.resize(2);
  frame.bodies[0].q = Eigen::Vector3d::Zero();
  frame.bodies[1].q = {1.0, 2.0, std::numbers::pi / 2};
  const Eigen::Vector2d p = point_in_world(model, frame, {"link", "P"});
  EXPECT_NEAR(p.x(), 0.9, 1e-15);
  EXPECT_NEAR(p.y(), 2.3, 1e-15);
  EXPECT_EQ(point_in_world(model, frame, {"link", "origin"}), Eigen::Vector2d(1.0, 2.0));
}

TEST(PointInWorld, UnknownPointOrBodyIsAnErrorNamingIt) {
  mech::MultibodyModel model;
  mech::Body link;
  link.name = "link";
  link.points["P"] = {0.3, 0.1};
  model.bodies = {link};
  mech::Frame frame;
  frame.bodies.resize(1);
  frame.bodies[0].q = Eigen::Vector3d::Zero();
  EXPECT_TRUE(contains(error_of([&] { point_in_world(model, frame, {"link", "Q"}); }), "body 'link' has no point 'Q'"));
  EXPECT_TRUE(contains(error_of([&] { point_in_world(model, frame, {"crank", "P"}); }),
                       "no body 'crank' to track point 'P' on"));
}

}  // namespace
}  // namespace kinetofem::pipeline
