// Stage "the rotary gripper module" (pipeline/rotary_module_stage.hpp) on the
// lever-chain manipulator fixture with its lever and arm as FE parts: the
// lever's 80 deg stroke in 2 s, then the casting turned 90 deg about the arm
// in 0.5 s.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <unistd.h>

#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/pipeline/rotary_module_stage.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "../structure/structure_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

namespace fs = std::filesystem;

TEST(AnalyseRotaryModule, EveryPartBalancesOverTheStrokeAndTheTurn) {
  const mech::ManipulatorDefinition def = structure::test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<Part> parts = structure::test::lever_chain_parts(def, structure::test::steel());
  apply_mass_properties(model, parts, Log::quiet());
  RotaryModuleSettings s;
  s.angle_rad = 90 * structure::test::kDeg;
  s.start_s = 2.0;
  s.duration_s = 0.5;
  s.gripper_inertia_kgm2 = Eigen::Vector3d(0.15, 0.15, 0.15).asDiagonal();
  s.casting_offset_m = {0.0, -0.12, 0.0};
  s.casting_inertia_kgm2 = Eigen::Vector3d(0.05, 0.05, 0.05).asDiagonal();
  const fs::path dir = fs::temp_directory_path() / fmt::format("kinetofem_rotary_stage_{}", ::getpid());
  fs::create_directories(dir);
  const RotaryModuleSummary r =
      analyse_rotary_module(model, parts, {0.0, 0.5, 1.0, 1.5, 2.0}, s, dir / "rotary.h5", {}, {}, Log::quiet());
  // The turn's output times are added at the motion's spacing.
  ASSERT_EQ(r.times.size(), 6u);
  EXPECT_DOUBLE_EQ(r.times.back(), 2.5);
  // Reference: d'Alembert equilibrium of each part under the spatial loads
  // (its body has the mesh's mass properties; the planar model's bodies are
  // lifted with the polar rule for the out-of-plane inertias, which the
  // turning module's loads do not touch: the lever and the arm do not turn
  // out of the plane): 1e-9; the 3-2-1 support's reactions, 1e-9.
  ASSERT_EQ(r.parts.size(), parts.size());
  for (const PartSummary& p : r.parts) {
    EXPECT_LT(p.worst_equilibrium_residual, 1e-9) << p.body;
    EXPECT_LT(p.worst_support_reaction, 1e-9) << p.body;
    EXPECT_EQ(p.output_times, 6) << p.body;
  }
  // The casting's weight about the arm's axis needs a torque once it leaves
  // the plane: the largest is at least that of its weight 45 deg round.
  EXPECT_GT(std::abs(r.peak_torque_nm), 15.0 * 9.80665 * 0.12 * std::sin(45 * structure::test::kDeg) * 0.5);
  EXPECT_GE(r.peak_torque_time_s, 2.0);
  const post::ResultsFile file = post::ResultsFile::open(r.results_file);
  const std::vector<std::string> bodies = file.bodies();
  EXPECT_NE(std::find(bodies.begin(), bodies.end(), mech::manipulator::kArm), bodies.end());
  fs::remove_all(dir);
}

// With the elastic assembly (chain EA 2e6 N, the gripper point H on the arm's
// mount face): the module's casting is a tracked point of the spatial
// assembly. References: the unit-load split adds up to the displacement
// (Maxwell-Betti, 1e-9); before the turn everything stays in the plane (the
// planar linkage, |u_z| < 1e-9 |u|); once turned, the casting hangs off the
// plane and the arm twists under its weight, so the casting moves out of the
// plane (|u_z| > 1e-3 |u| at the end of the turn). Its natural frequencies
// per pose come out positive and ascending, and each part has its fatigue.
TEST(AnalyseRotaryModule, TheGripperDeflectsOutOfThePlaneOnceTheCastingIsTurned) {
  const mech::ManipulatorDefinition def = structure::test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<Part> parts = structure::test::lever_chain_parts(def, structure::test::steel());
  apply_mass_properties(model, parts, Log::quiet());
  RotaryModuleSettings s;
  s.angle_rad = 90 * structure::test::kDeg;
  s.start_s = 2.0;
  s.duration_s = 0.5;
  s.gripper_inertia_kgm2 = Eigen::Vector3d(0.15, 0.15, 0.15).asDiagonal();
  s.casting_offset_m = {0.0, -0.12, 0.0};
  s.casting_inertia_kgm2 = Eigen::Vector3d(0.05, 0.05, 0.05).asDiagonal();
  structure::AssemblyOptions assembly;
  assembly.chains = {{"chain", 2e6}};
  assembly.points = {{"H", "arm", "H", "x0"}};
  const fs::path dir = fs::temp_directory_path() / fmt::format("kinetofem_rotary_assembly_{}", ::getpid());
  fs::create_directories(dir);
  vibration::AssemblyModesOptions modes;
  modes.modes = 3;
  const FatigueSettings fatigue;  // EN 1993-1-9 detail 71, one cycle a minute
  const RotaryModuleSummary r = analyse_rotary_module(model, parts, {0.0, 0.5, 1.0, 1.5, 2.0}, s, dir / "rotary.h5", {},
                                                      {}, Log::quiet(), &assembly, &modes, &fatigue);
  ASSERT_TRUE(r.assembly.has_value());
  ASSERT_EQ(r.assembly->points.size(), 2u);
  for (const PointSummary& p : r.assembly->points) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const structure::PointContribution& c : p.contributions_at_max) sum += c.displacement_m;
    EXPECT_LT((sum - p.displacement_at_max_m).norm(), 1e-9 * p.displacement_at_max_m.norm()) << p.name;
    EXPECT_GT(p.max_displacement_m, 1e-5) << p.name;  // the chain alone stretches by ~0.4 mm
  }
  const Eigen::MatrixXd& casting = r.assembly->points[1].displacement_history_m;
  ASSERT_EQ(casting.rows(), 6);
  for (Eigen::Index k = 0; k < 5; ++k) EXPECT_LT(std::abs(casting(k, 2)), 1e-9 * casting.row(k).norm()) << k;
  EXPECT_GT(std::abs(casting(5, 2)), 1e-3 * casting.row(5).norm());
  // Each part's fatigue over the stroke and the turn: a utilization > 0 (the
  // parts carry load) and finite.
  ASSERT_EQ(r.fatigue.size(), parts.size());
  for (const PartFatigue& f : r.fatigue) EXPECT_TRUE(f.max_utilization > 0 && std::isfinite(f.max_utilization)) << f.body;
  // The natural frequencies with the module, per pose: positive, ascending.
  ASSERT_TRUE(r.assembly->vibration.has_value());
  const Eigen::MatrixXd& f = r.assembly->vibration->frequency_hz;
  ASSERT_EQ(f.rows(), 6);
  for (Eigen::Index k = 0; k < f.rows(); ++k) {
    EXPECT_GT(f(k, 0), 0.0) << k;
    EXPECT_GE(f(k, 2), f(k, 1)) << k;
    EXPECT_GE(f(k, 1), f(k, 0)) << k;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kinetofem::pipeline
