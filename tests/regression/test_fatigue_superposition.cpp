// Issue 15, verification 5: the work cycle's fatigue damage from the stress
// of unit-load superposition and from per-step solves, on the two SPEC
// manipulators (SPEC §1 lever-chain, SPEC §2 lever) through the whole program
// path (case keys -> pipeline -> fatigue stage -> results file), coarse
// meshes (tests/support manipulator_cases.hpp).
//
// Reference: the same case with solver.load_path = "step_by_step" (one solve
// and one stress recovery per output time, every step's stress kept).
// Superposition is exact in exact arithmetic, so the stresses differ by
// round-off (1e-10 of the peak, tests/regression/test_superposition.cpp), and
// so do the counted ranges and the damage: tolerance 1e-10 relative to the
// part's largest damage per cycle for every node's damage (and to the
// largest utilization for the utilization), 1e-10 relative for each part's
// shortest life; the critical node the same.
//
// The links are made thin (8 mm), the casting heavy (150 kg) and the detail
// the lowest category (36 MPa, gamma_Ff 2.0) so that ranges exceed the
// cut-off limit and the damage is not zero (the bundled cases' is: their
// ranges are below the cut-off, cases/*/README.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/testing/manipulator_cases.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

const char* kFatigueCase =
    "[assembly]\nenabled = false\n[payload]\ncasting_mass_kg = 150.0\n[links]\nlever_thickness_mm = 8.0\n"
    "arm_thickness_mm = 8.0\n[fatigue]\nenabled = true\ndetail_category_mpa = 36\ngamma_ff = 2.0\n";

struct FatigueRun {
  fs::path file;
  ManipulatorSummary summary;
};

FatigueRun run(const std::string& type, double stroke_deg, const std::string& dir, const std::vector<std::string>& set) {
  RunOptions options;
  options.output_dir = fs::temp_directory_path() / dir;
  fs::remove_all(options.output_dir);
  options.quiet = true;
  const CaseFile c = CaseFile::parse(testing::coarse_manipulator_case(type, stroke_deg, kFatigueCase), "case.toml",
                                     manipulator_schema(), false, set);
  FatigueRun r;
  r.summary = run_manipulator(c, options);
  r.file = options.output_dir / "m.h5";
  return r;
}

void expect_same_damage(const std::string& type, double stroke_deg) {
  const FatigueRun superposed = run(type, stroke_deg, "kinetofem_fatigue_superposed_" + type, {});
  const FatigueRun per_step =
      run(type, stroke_deg, "kinetofem_fatigue_per_step_" + type, {"solver.load_path=\"step_by_step\""});
  ASSERT_EQ(superposed.summary.fatigue.size(), per_step.summary.fatigue.size());
  const auto a = post::ResultsFile::open(superposed.file), b = post::ResultsFile::open(per_step.file);
  for (std::size_t k = 0; k < per_step.summary.fatigue.size(); ++k) {
    const pipeline::PartFatigue& fa = superposed.summary.fatigue[k];
    const pipeline::PartFatigue& fb = per_step.summary.fatigue[k];
    EXPECT_TRUE(fa.superposed);
    EXPECT_FALSE(fb.superposed);
    ASSERT_GT(fb.max_damage_per_cycle, 0.0) << fb.body << ": the test needs damage";
    const post::FieldMatrix da = a.read_static(fa.body, "fatigue_damage_per_cycle").values;
    const post::FieldMatrix db = b.read_static(fb.body, "fatigue_damage_per_cycle").values;
    const post::FieldMatrix ua = a.read_static(fa.body, "fatigue_utilization").values;
    const post::FieldMatrix ub = b.read_static(fb.body, "fatigue_utilization").values;
    ASSERT_EQ(da.rows(), db.rows());
    const double damage_error = (da - db).cwiseAbs().maxCoeff() / fb.max_damage_per_cycle;
    const double utilization_error = (ua - ub).cwiseAbs().maxCoeff() / fb.max_utilization;
    const double life_error = std::abs(fa.min_life_cycles - fb.min_life_cycles) / fb.min_life_cycles;
    std::printf("  %s %s: damage per cycle %.6e (critical node %ld), superposition vs step by step: damage %.2e, "
                "utilization %.2e of the largest, life %.2e relative\n",
                type.c_str(), fb.body.c_str(), fb.max_damage_per_cycle, fb.critical_node, damage_error,
                utilization_error, life_error);
    EXPECT_LT(damage_error, 1e-10) << fb.body;
    EXPECT_LT(utilization_error, 1e-10) << fb.body;
    EXPECT_LT(life_error, 1e-10) << fb.body;
    EXPECT_EQ(fa.critical_node, fb.critical_node) << fb.body;
  }
}

TEST(FatigueSuperposition, LeverChainManipulatorDamageEqualsPerStepSolves) { expect_same_damage("lever_chain", 80.0); }

// Fields written at some output times only (output.field_every = 4): the
// fatigue stage still gets every output time's stress on the step-by-step
// path, so the damage is the same doubles as with every field written.
TEST(FatigueSuperposition, StepByStepWithSomeFieldsWrittenCountsEveryOutputTime) {
  const std::string step = "solver.load_path=\"step_by_step\"";
  const FatigueRun all = run("lever_chain", 80.0, "kinetofem_fatigue_all_fields", {step});
  const FatigueRun some = run("lever_chain", 80.0, "kinetofem_fatigue_some_fields", {step, "output.field_every=4"});
  ASSERT_EQ(all.summary.fatigue.size(), some.summary.fatigue.size());
  for (std::size_t k = 0; k < all.summary.fatigue.size(); ++k) {
    EXPECT_EQ(all.summary.fatigue[k].damage_per_cycle, some.summary.fatigue[k].damage_per_cycle) << k;
    EXPECT_EQ(all.summary.fatigue[k].critical_node, some.summary.fatigue[k].critical_node) << k;
  }
  EXPECT_EQ(post::ResultsFile::open(some.file).series_times("lever").size(), 4u);  // steps 0, 4, 8, 10
}

TEST(FatigueSuperposition, LeverManipulatorDamageEqualsPerStepSolves) { expect_same_damage("lever", 30.0); }

}  // namespace
}  // namespace kinetofem::app
