// Stage "loads and stress over the motion" for one part
// (pipeline/part_stress.hpp) on a small beam (structured HEX20, 10 x 2 x 1
// cells) swung as a driven pendulum with a tip mass (pipeline_fixtures.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

namespace fs = std::filesystem;
using test::kDeg;

struct BeamRun {
  Part part;
  mech::MultibodyModel model;
  mech::Results motion;
  std::optional<mech::Frame> static_pose;
  PartSummary summary;
  fs::path file;
};

// The beam swings 60 deg in 0.5 s (6 output times, kinematic); with
// `with_static`, also held horizontal at rest (law value 0).
BeamRun run_beam(bool with_static, const std::string& name) {
  BeamRun r;
  r.part = test::beam_part("beam", test::beam_pendulum_attachments());
  r.model = test::beam_pendulum();
  apply_mass_properties(r.model, {r.part}, Log::quiet());
  const mech::MultibodySystem system(r.model);
  r.motion = mech::run_kinematics(system, mech::equally_spaced_times(0.5, 6));
  if (with_static) r.static_pose = solve_static_pose(r.model, {0.0});
  r.file = test::fresh_dir(name) / "beam.h5";
  post::ResultsWriter writer(r.file, {});
  r.summary = analyse_part_over_motion(r.part, r.model, r.motion.frames, r.static_pose, writer, {}, Log::quiet());
  writer.commit();
  return r;
}

// Computed once per process; the folder is named after the test that asks
// first, because ctest runs the tests of this file in parallel processes.
const BeamRun& with_static() {
  static const BeamRun run =
      run_beam(true, std::string("part_stress_static_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  return run;
}

TEST(AnalysePartOverMotion, LoadsAreInEquilibriumAndTheSupportCarriesNothing) {
  // Reference: d'Alembert equilibrium of the beam (its body has the mesh's
  // mass properties; the couplings reproduce each reaction exactly): 1e-9,
  // as tests/unit/loads/test_link_loads.cpp. The 3-2-1 support of a
  // self-equilibrated load carries nothing: 1e-8 of the total load.
  const BeamRun& r = with_static();
  EXPECT_LT(r.summary.worst_equilibrium_residual, 1e-9);
  EXPECT_LT(r.summary.worst_support_reaction, 1e-8);
  EXPECT_EQ(r.summary.body, "beam");
  EXPECT_EQ(r.summary.nodes, r.part.model.mesh.node_count());
  EXPECT_EQ(r.summary.dofs, 3 * r.part.model.mesh.node_count());
  // Unit-load superposition (the default): one right-hand side per load
  // pattern stored in the file, for 6 output times + the static pose.
  EXPECT_TRUE(r.summary.superposed);
  EXPECT_EQ(r.summary.output_times, 6);
  EXPECT_EQ(size_t(r.summary.right_hand_sides), post::ResultsFile::open(r.file).read_load_patterns("beam").names.size());
}

TEST(AnalysePartOverMotion, ResultsFileHasTheBodyWithItsSeries) {
  const BeamRun& r = with_static();
  const auto file = post::ResultsFile::open(r.file);
  EXPECT_EQ(file.bodies(), std::vector<std::string>{"beam"});
  EXPECT_EQ(file.read_mesh("beam").node_count(), r.part.model.mesh.node_count());
  const std::vector<double> times = file.series_times("beam");
  ASSERT_EQ(times.size(), r.motion.frames.size());
  for (std::size_t k = 0; k < times.size(); ++k) EXPECT_EQ(times[k], r.motion.frames[k].t);
  const auto fields = file.series_fields("beam");
  EXPECT_NE(std::find(fields.begin(), fields.end(), "displacement"), fields.end());
  EXPECT_NE(std::find(fields.begin(), fields.end(), "von_mises"), fields.end());
  const post::FieldData u = file.read_step("beam", "displacement", 3);
  EXPECT_EQ(u.units, "m");
  EXPECT_EQ(u.values.rows(), r.part.model.mesh.node_count());
  EXPECT_EQ(u.values.cols(), 3);
  const post::FieldData vm = file.read_step("beam", "von_mises", 3);
  EXPECT_EQ(vm.units, "Pa");
  EXPECT_GT(vm.values.maxCoeff(), 0.0);  // a loaded beam
}

TEST(AnalysePartOverMotion, EnvelopeMaxIsAtLeastEveryStepsMaxAndExcludesTheStaticPose) {
  const BeamRun& r = with_static();
  const auto file = post::ResultsFile::open(r.file);
  const post::EnvelopeData env = file.read_envelope("beam", "von_mises");
  EXPECT_EQ(env.operation, "max");
  const fem::Index steps = fem::Index(r.motion.frames.size());
  double peak = 0.0;
  for (fem::Index k = 0; k < steps; ++k) {
    const post::FieldData vm = file.read_step("beam", "von_mises", k);
    // Exact: the envelope is the per-node maximum of the written steps.
    EXPECT_TRUE((env.values.array() >= vm.values.array()).all()) << "step " << k;
  }
  for (fem::Index n = 0; n < env.values.rows(); ++n) {
    const fem::Index k = env.step(n, 0);
    ASSERT_GE(k, 0);
    ASSERT_LT(k, steps);  // a motion step, never the static pose appended after them
    EXPECT_EQ(env.values(n, 0), file.read_step("beam", "von_mises", k).values(n, 0)) << "node " << n;
    peak = std::max(peak, env.values(n, 0));
  }
  EXPECT_EQ(r.summary.peak_von_mises_pa, peak);
  const std::vector<double> times = file.series_times("beam");
  EXPECT_NE(std::find(times.begin(), times.end(), r.summary.peak_von_mises_time_s), times.end())
      << r.summary.peak_von_mises_time_s;
  const post::EnvelopeData u = file.read_envelope("beam", "displacement_magnitude");
  EXPECT_EQ(u.units, "m");
  EXPECT_NEAR(r.summary.peak_displacement_m, u.values.maxCoeff(), 0.0);
}

TEST(AnalysePartOverMotion, StaticPoseGivesStaticFields) {
  const BeamRun& r = with_static();
  const auto file = post::ResultsFile::open(r.file);
  EXPECT_EQ(file.static_fields("beam"),
            (std::vector<std::string>{"static_displacement", "static_stress", "static_von_mises"}));
  const post::FieldData vm = file.read_static("beam", "static_von_mises");
  EXPECT_EQ(vm.units, "Pa");
  EXPECT_EQ(r.summary.static_von_mises_pa, vm.values.maxCoeff());
  EXPECT_EQ(file.read_static("beam", "static_stress").values.cols(), 6);
}

TEST(AnalysePartOverMotion, StaticPoseStressAtMidspanIsTheCantileverBendingStress) {
  // The beam held horizontal at rest: a cantilever from its root face x0
  // under its own weight w = rho g H T and the tip mass P = m g at x = L.
  // Reference (Euler-Bernoulli beam): at x = L/2 the top fibre (y = H/2)
  // carries sigma_xx = M c / I, M = w (L/2)^2 / 2 + P L/2, c = H/2,
  // I = T H^3 / 12 (tension: the beam hangs down). Tolerance 1 %: HEX20 with
  // 2 cells through the depth and nodal averaging, 3.75 depths from the root
  // coupling (Saint-Venant); measured -0.15 %.
  const BeamRun& r = with_static();
  const auto file = post::ResultsFile::open(r.file);
  const post::FieldData s = file.read_static("beam", "static_stress");
  ASSERT_EQ(s.component_names.front(), "xx");
  const test::BeamSize size;
  const double L = size.length_m, H = size.height_m, T = size.thickness_m, g = units::kStandardGravity;
  const double w = 7850.0 * g * H * T, P = 2.0 * g;
  const double M = w * (L / 2) * (L / 2) / 2 + P * L / 2;
  const double expected = M * (H / 2) / (T * H * H * H / 12);
  const fem::Mesh& mesh = r.part.model.mesh;
  double sum = 0.0;
  int count = 0;
  for (fem::Index n = 0; n < mesh.node_count(); ++n)
    if (std::abs(mesh.nodes(n, 0) - L / 2) < 1e-9 && std::abs(mesh.nodes(n, 1) - H / 2) < 1e-9) sum += s.values(n, 0), ++count;
  ASSERT_GT(count, 0);
  EXPECT_NEAR(sum / count, expected, 0.01 * expected);
}

TEST(AnalysePartOverMotion, NoStaticPoseWritesNoStaticFields) {
  const BeamRun r = run_beam(false, "part_stress_motion_only");
  const auto file = post::ResultsFile::open(r.file);
  EXPECT_TRUE(file.static_fields("beam").empty());
  EXPECT_EQ(r.summary.static_von_mises_pa, 0.0);
  EXPECT_EQ(size_t(r.summary.right_hand_sides), file.read_load_patterns("beam").names.size());
  // The motion's results do not depend on the static study solved beside them
  // (same factor, same loads: equal to round-off, 1e-12 relative).
  EXPECT_NEAR(r.summary.peak_von_mises_pa, with_static().summary.peak_von_mises_pa,
              1e-12 * with_static().summary.peak_von_mises_pa);
}

TEST(AnalysePartOverMotion, NoOutputTimesIsAnErrorNamingThePart) {
  const Part part = test::beam_part("beam", test::beam_pendulum_attachments());
  mech::MultibodyModel model = test::beam_pendulum();
  apply_mass_properties(model, {part}, Log::quiet());
  post::ResultsWriter writer(test::fresh_dir("part_stress_empty") / "beam.h5", {});
  const std::string message = test::error_of(
      [&] { analyse_part_over_motion(part, model, {}, std::nullopt, writer, {}, Log::quiet()); });
  EXPECT_NE(message.find("part 'beam' (test beam): no output times to analyse"), std::string::npos) << message;
}

TEST(AnalysePartOverMotion, BodyMassNotFromTheMeshIsAnErrorNamingThePartAndTime) {
  // The body keeps case mass properties 5 % off the mesh's: the loads are out
  // of equilibrium (d'Alembert) beyond the 1e-6 check, named with the time.
  Part part = test::beam_part("beam", test::beam_pendulum_attachments());
  mech::MultibodyModel model = test::beam_pendulum();
  apply_mass_properties(model, {part}, Log::quiet());
  model.bodies[1].mass_kg *= 1.05;
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(model), mech::equally_spaced_times(0.5, 3));
  post::ResultsWriter writer(test::fresh_dir("part_stress_mass") / "beam.h5", {});
  const std::string message = test::error_of(
      [&] { analyse_part_over_motion(part, model, motion.frames, std::nullopt, writer, {}, Log::quiet()); });
  EXPECT_NE(message.find("link 'beam' at t = "), std::string::npos) << message;
}

}  // namespace
}  // namespace kinetofem::pipeline
