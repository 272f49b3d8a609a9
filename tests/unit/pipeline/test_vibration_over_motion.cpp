// The stage "vibration over the motion" (pipeline/vibration_over_motion.hpp):
// what it writes, its physics in the limits (a slow motion is quasi-static,
// a fast one rings; no damping never settles), the reduced model's static
// deflection against the elastic assembly's, and its errors. The lever-chain
// manipulator of structure_fixtures.hpp with box parts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <unistd.h>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/histories.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/pipeline/vibration_over_motion.hpp"
#include "../structure/structure_fixtures.hpp"

namespace kinetofem::structure {
namespace {

using namespace kinetofem::pipeline;  // the stage under test

namespace fs = std::filesystem;

struct StageRun {
  fs::path file;
  VibrationSummary vibration;
  AssemblySummary assembly;
  std::vector<pipeline::Part> parts;
  size_t output_times = 0;
};

AssemblyOptions lever_chain_options() {
  AssemblyOptions o;
  o.chains = {{"chain", 5e6}};
  o.points = {{"H", "arm", "H", "x0"}};
  return o;
}

std::vector<double> times_over(double duration, int count) {
  std::vector<double> t;
  for (int k = 0; k < count; ++k) t.push_back(duration * k / (count - 1));
  return t;
}

enum class Fixture { LeverChain, TwoLinkArm };

// The lever-chain manipulator (chain 5e6 N, H tracked) moving its lever by
// 80 deg, or the two-link arm (payload 3 kg at link2's tip, tracked),
// over `duration_s` with a 3-4-5 law.
StageRun run_stage(const std::string& name, double duration_s, const VibrationOptions& options, int output_times = 41,
                   double density_factor = 1.0, Fixture fixture = Fixture::LeverChain) {
  StageRun r;
  mech::MultibodyModel model;
  fem::IsotropicMaterial steel = test::steel();
  steel.density_kg_m3 *= density_factor;
  AssemblyOptions ao;
  std::vector<double> static_targets;
  if (fixture == Fixture::LeverChain) {
    mech::ManipulatorDefinition def = test::lever_chain_definition();
    def.lever_motion = std::make_shared<mech::Polynomial345Law>(80 * test::kDeg, duration_s);
    model = mech::make_manipulator_model(def);
    r.parts = test::lever_chain_parts(def, steel);
    ao = lever_chain_options();
    static_targets = {0.0};
  } else {
    test::TwoLinkArm arm;
    arm.duration_s = duration_s;
    model = test::two_link_arm(arm);
    r.parts = test::two_link_parts(arm, steel);
    ao.points = {{"tip", "link2", "tip", "x1"}};
    static_targets = {0.0, 0.0};
  }
  if (density_factor > 0) pipeline::apply_mass_properties(model, r.parts, Log::quiet());
  // A part without mass: its loads cannot match the multibody body's (the
  // placeholders stay), which is not what the test is about.
  if (density_factor == 0) ao.load_check_tolerance = std::numeric_limits<double>::infinity();
  const mech::Results motion = mech::run_kinematics(mech::MultibodySystem(model), times_over(duration_s, output_times));
  r.output_times = motion.frames.size();
  const mech::Frame statics = pipeline::solve_static_pose(model, static_targets);
  const fs::path dir = fs::temp_directory_path() / fmt::format("kinetofem_vibration_stage_{}", ::getpid());
  fs::create_directories(dir);
  r.file = dir / (name + ".h5");
  post::ResultsWriter writer(r.file, {});
  pipeline::write_mechanism_histories(writer, model, motion);
  r.assembly = analyse_assembly_over_motion(r.parts, model, motion.frames, statics, writer, ao, Log::quiet());
  r.vibration = analyse_vibration_over_motion(r.parts, model, motion.frames, statics, writer, ao, options, r.assembly,
                                              Log::quiet());
  writer.commit();
  return r;
}

TEST(VibrationOverMotion, WritesFrequenciesTheResponseOfHAndModeShapes) {
  VibrationOptions options;
  options.modes.modes = 4;
  const StageRun r = run_stage("written", 2.0, options);
  const auto file = post::ResultsFile::open(r.file);
  const auto f = file.read_history("vibration.frequency");
  ASSERT_EQ(f.values.rows(), Eigen::Index(r.output_times));
  ASSERT_EQ(f.values.cols(), 4);
  EXPECT_EQ(f.units, "Hz");
  for (Eigen::Index k = 0; k < f.values.rows(); ++k)
    for (int i = 1; i < 4; ++i) EXPECT_GE(f.values(k, i), f.values(k, i - 1));  // ascending in every pose
  EXPECT_NEAR(f.values(0, 0), r.vibration.frequency_hz(0, 0), 0.0);
  const auto time = file.read_table("vibration.response.time");
  const auto u = file.read_table("vibration.response.point.H.displacement");
  const auto qs = file.read_table("vibration.response.point.H.quasi_static");
  ASSERT_EQ(u.values.rows(), time.values.rows());
  ASSERT_EQ(qs.values.rows(), time.values.rows());
  EXPECT_GT(time.values.rows(), Eigen::Index(r.output_times));  // substeps and the settling window
  for (Eigen::Index s = 1; s < time.values.rows(); ++s) EXPECT_GT(time.values(s, 0), time.values(s - 1, 0));
  EXPECT_NEAR(file.read_table("vibration.response.stop_time").values(0, 0), 2.0, 1e-12);
  // The quasi-static curve is the elastic assembly's deflection at the output times.
  const auto assembly_h = file.read_history("assembly.point.H.displacement");
  for (Eigen::Index s = 0, k = 0; s < time.values.rows() && k < assembly_h.values.rows(); ++s)
    if (std::abs(time.values(s, 0) - 2.0 * double(k) / double(r.output_times - 1)) < 1e-12) {
      EXPECT_LT((qs.values.row(s) - assembly_h.values.row(k)).norm(), 1e-15);
      ++k;
    }
  // Mode shapes: static fields on meshes placed in world coordinates at the pose.
  double largest = 0.0;
  for (const auto& part : r.parts) {
    for (const std::string pose : {"static", "lowest"}) {
      const std::string body = "vibration." + pose + "." + part.body();
      EXPECT_TRUE(file.series_times(body).empty()) << body;  // the time axis stays the motion's
      const std::vector<std::string> fields = file.static_fields(body);
      for (int i = 1; i <= 4; ++i) {
        EXPECT_NE(std::find(fields.begin(), fields.end(), fmt::format("mode_{}", i)), fields.end()) << body;
        EXPECT_EQ(file.read_static(body, fmt::format("mode_{}", i)).values.cols(), 3);
      }
    }
    largest = std::max(largest, file.read_static("vibration.lowest." + part.body(), "mode_1_magnitude").values.maxCoeff());
  }
  // Normalized to max |u| = 1 over the parts.
  EXPECT_NEAR(largest, 1.0, 1e-12);
  // The static study is the design position: the arm's world placement there.
  const fem::Mesh arm = file.read_mesh("vibration.static.arm");
  EXPECT_EQ(arm.node_count(), r.parts[1].model.mesh.node_count());
}

TEST(VibrationOverMotion, TheReducedStaticDeflectionIsTheElasticAssemblys) {
  const StageRun r = run_stage("static", 2.0, {});
  ASSERT_EQ(r.vibration.points.size(), 1u);
  // Craig-Bampton with residual vectors spans the static response to the
  // interface loads and the rigid-acceleration inertia loads: the same
  // deflection to round-off (measured 2e-10 on the 8 mm case).
  EXPECT_LT(r.vibration.points[0].reduced_static_mismatch, 1e-6);
}

TEST(VibrationOverMotion, ASlowMotionIsQuasiStaticAFastOneRings) {
  VibrationOptions options;
  const StageRun slow = run_stage("slow", 4.0, options, 81, 1.0, Fixture::TwoLinkArm);
  const StageRun fast = run_stage("fast", 0.1, options, 41, 1.0, Fixture::TwoLinkArm);
  const PointVibration& s = slow.vibration.points[0];
  const PointVibration& f = fast.vibration.points[0];
  std::printf("  slow (4 s): amplification %.6f, vibration %.3e m, after the stop %.3e m\n", s.dynamic_amplification,
              s.peak_vibration_m, s.amplitude_at_stop_m);
  std::printf("  fast (0.1 s): amplification %.6f, vibration %.3e m, after the stop %.3e m\n", f.dynamic_amplification,
              f.peak_vibration_m, f.amplitude_at_stop_m);
  // Two-link arm, first frequency ~23 Hz (period 43 ms). A 4 s stroke: the
  // response follows the load (dynamic part ~ (T_1 / duration)^2 of the
  // inertia deflection).
  EXPECT_NEAR(s.dynamic_amplification, 1.0, 1e-3);
  EXPECT_LT(s.peak_vibration_m, 1e-3 * s.peak_quasi_static_m);
  // A 0.1 s stroke is two first periods: it rings, during and after.
  EXPECT_GT(f.peak_vibration_m, 30 * s.peak_vibration_m);
  EXPECT_GT(f.amplitude_at_stop_m, 30 * s.amplitude_at_stop_m);
}

TEST(VibrationOverMotion, WithoutDampingItNeverSettlesMoreDampingSettlesSooner) {
  VibrationOptions none, light, heavy;
  none.damping_ratio = 0.0;
  light.damping_ratio = 0.01;
  heavy.damping_ratio = 0.05;
  none.settling_tolerance_m = light.settling_tolerance_m = heavy.settling_tolerance_m = 1e-6;
  const StageRun a = run_stage("undamped", 0.1, none, 41, 1.0, Fixture::TwoLinkArm);
  const StageRun b = run_stage("light", 0.1, light, 41, 1.0, Fixture::TwoLinkArm);
  const StageRun c = run_stage("heavy", 0.1, heavy, 41, 1.0, Fixture::TwoLinkArm);
  EXPECT_TRUE(std::isinf(a.vibration.points[0].settling_time_s));
  const double tb = b.vibration.points[0].settling_time_s, tc = c.vibration.points[0].settling_time_s;
  std::printf("  settling within 1 um: zeta 0.01 %.4f s, zeta 0.05 %.4f s\n", tb, tc);
  EXPECT_GT(tb, 0.0);
  // The envelope decays like exp(-zeta w t): five times the damping settles
  // about five times sooner (the log of amplitude / tolerance differs a little).
  EXPECT_GT(tb / tc, 3.5);
  EXPECT_LT(tb / tc, 7.0);
  const auto file = post::ResultsFile::open(a.file);
  EXPECT_TRUE(std::isinf(file.read_table("vibration.point.tip.settling_time").values(0, 0)));
}

TEST(VibrationOverMotion, BadOptionsAreErrorsNamingTheValue) {
  auto message = [](VibrationOptions o, double density_factor = 1.0) {
    return test::error_of([&] { run_stage("bad", 0.5, o, 5, density_factor, Fixture::TwoLinkArm); });
  };
  VibrationOptions o;
  o.modes.modes = 0;
  EXPECT_NE(message(o).find("modes = 0"), std::string::npos) << message(o);
  o = {};
  o.damping_ratio = 1.0;
  EXPECT_NE(message(o).find("damping ratio 1"), std::string::npos) << message(o);
  o = {};
  o.settling_tolerance_m = 0.0;
  EXPECT_NE(message(o).find("settling tolerance 0"), std::string::npos) << message(o);
  o = {};
  const std::string zero_density = message(o, 0.0);
  EXPECT_NE(zero_density.find("link1"), std::string::npos) << zero_density;
  EXPECT_NE(zero_density.find("mass"), std::string::npos) << zero_density;
}

}  // namespace
}  // namespace kinetofem::structure
