// Unit-load superposition (load_patterns.hpp) against the step-by-step solves, on the
// two SPEC manipulators (SPEC §1 lever-chain, SPEC §2 lever) through the
// whole program path (case keys -> pipeline -> results file), coarse meshes.
//
// Reference: the same case with solver.load_path = "step_by_step" (one solve
// and one stress recovery per output time). Superposition is exact in exact
// arithmetic (the loads are linear in the pattern coefficients, the solve and
// the stress recovery linear in the loads), so the difference is round-off:
// tolerance 1e-10 of the peak for the displacement and von Mises series at
// every output time and for the envelope values; the envelope steps equal,
// or a tie within 1e-10 of the peak.
// Field output: output.field_every = 4 writes steps 0, 4, 8 and 10 only, the
// envelope still covers all 11 output times (equal to the full run's), and
// the stored patterns reconstruct a step that was not written (post::superpose)
// within 1e-10 of the peak.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/postproc/load_patterns.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/testing/manipulator_cases.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

std::string coarse_case(const std::string& type, double stroke_deg) {
  return testing::coarse_manipulator_case(type, stroke_deg, "[assembly]\nenabled = false\n");
}

fs::path run(const std::string& type, double stroke_deg, const std::string& dir, const std::vector<std::string>& set) {
  RunOptions options;
  options.output_dir = fs::temp_directory_path() / dir;
  fs::remove_all(options.output_dir);
  options.quiet = true;
  const CaseFile c = CaseFile::parse(coarse_case(type, stroke_deg), "case.toml", manipulator_schema(), false, set);
  run_manipulator(c, options);
  return options.output_dir / "m.h5";
}

double relative_difference(const post::FieldMatrix& a, const post::FieldMatrix& b, double peak) {
  return (a - b).cwiseAbs().maxCoeff() / peak;
}

void expect_same_motion(const std::string& type, double stroke_deg) {
  const fs::path superposed = run(type, stroke_deg, "kinetofem_superposed_" + type, {});
  const fs::path per_step = run(type, stroke_deg, "kinetofem_per_step_" + type, {"solver.load_path=\"step_by_step\""});
  const auto a = post::ResultsFile::open(superposed), b = post::ResultsFile::open(per_step);
  for (const std::string& body : b.bodies()) {
    ASSERT_TRUE(a.has_load_patterns(body)) << body;
    EXPECT_FALSE(b.has_load_patterns(body)) << body;
    const auto times = b.series_times(body);
    ASSERT_EQ(a.series_times(body).size(), times.size()) << body;
    for (const std::string field : {"von_mises", "displacement_magnitude"}) {
      const post::EnvelopeData ea = a.read_envelope(body, field), eb = b.read_envelope(body, field);
      const double peak = eb.values.maxCoeff();
      const double error = relative_difference(ea.values, eb.values, peak);
      long tie_steps = 0;
      for (Eigen::Index i = 0; i < eb.step.rows(); ++i)
        if (ea.step(i, 0) != eb.step(i, 0)) {
          // A tie: the other run's step has the same value within round-off.
          const std::string series = field == "von_mises" ? "von_mises" : "displacement";
          const auto at = b.read_step(body, series, ea.step(i, 0)).values.row(i);
          const double value = field == "von_mises" ? at(0) : at.norm();
          EXPECT_LT(std::abs(value - eb.values(i, 0)), 1e-10 * peak) << body << " node " << i;
          ++tie_steps;
        }
      std::printf("  %s %s, envelope %s: superposition vs step by step %.2e of the peak %.6g; %ld tied steps\n",
                  type.c_str(), body.c_str(), field.c_str(), error, peak, tie_steps);
      EXPECT_LT(error, 1e-10) << body << " " << field;
    }
    double worst_u = 0.0, worst_vm = 0.0;
    const double peak_u = b.read_envelope(body, "displacement_magnitude").values.maxCoeff();
    const double peak_vm = b.read_envelope(body, "von_mises").values.maxCoeff();
    for (fem::Index k = 0; k < fem::Index(times.size()); ++k) {
      worst_u = std::max(worst_u, relative_difference(a.read_step(body, "displacement", k).values,
                                                      b.read_step(body, "displacement", k).values, peak_u));
      worst_vm = std::max(worst_vm, relative_difference(a.read_step(body, "von_mises", k).values,
                                                        b.read_step(body, "von_mises", k).values, peak_vm));
    }
    std::printf("  %s %s, %zu output times: displacement %.2e, von Mises %.2e of the peak\n", type.c_str(),
                body.c_str(), times.size(), worst_u, worst_vm);
    EXPECT_LT(worst_u, 1e-10) << body;
    EXPECT_LT(worst_vm, 1e-10) << body;
    const double static_error = relative_difference(a.read_static(body, "static_von_mises").values,
                                                    b.read_static(body, "static_von_mises").values, peak_vm);
    EXPECT_LT(static_error, 1e-10) << body;
  }
}

TEST(Superposition, LeverChainManipulatorEqualsTheStepByStepSolves) { expect_same_motion("lever_chain", 80.0); }

TEST(Superposition, LeverManipulatorEqualsTheStepByStepSolves) { expect_same_motion("lever", 30.0); }

TEST(Superposition, FieldsAtEveryKthTimeKeepTheFullEnvelopeAndReconstructTheOthers) {
  const fs::path all = run("lever_chain", 80.0, "kinetofem_fields_all", {});
  const fs::path some = run("lever_chain", 80.0, "kinetofem_fields_some", {"output.field_every=4"});
  const auto a = post::ResultsFile::open(all), s = post::ResultsFile::open(some);
  for (const std::string body : {"lever", "arm"}) {
    const auto times = a.series_times(body);
    ASSERT_EQ(times.size(), 11u);
    const auto written = s.series_times(body);
    ASSERT_EQ(written.size(), 4u) << body;  // steps 0, 4, 8 and the last, 10
    EXPECT_EQ(written[1], times[4]);
    EXPECT_EQ(written[2], times[8]);
    EXPECT_EQ(written[3], times[10]);
    const post::EnvelopeData ea = a.read_envelope(body, "von_mises"), es = s.read_envelope(body, "von_mises");
    EXPECT_EQ(es.times_s, times) << body;  // the envelope's steps index every output time
    EXPECT_EQ(ea.values, es.values) << body;
    EXPECT_EQ(ea.step, es.step) << body;
    const post::LoadPatternData patterns = s.read_load_patterns(body);
    ASSERT_EQ(patterns.time_s, times);
    const post::SuperposedFields at7 = post::superpose(patterns, 7);
    const double peak = ea.values.maxCoeff();
    const double error =
        (at7.von_mises_pa - a.read_step(body, "von_mises", 7).values.col(0)).cwiseAbs().maxCoeff() / peak;
    std::printf("  %s: step 7 (not written) from the stored patterns vs the full run: %.2e of the peak\n",
                body.c_str(), error);
    EXPECT_LT(error, 1e-10) << body;
  }
}

TEST(Superposition, FieldTimesAreMergedIntoTheOutputTimes) {
  const fs::path file = run("lever_chain", 80.0, "kinetofem_field_times", {"output.field_times_s=[0.2, 0.6]"});
  const auto r = post::ResultsFile::open(file);
  const auto written = r.series_times("lever");
  ASSERT_EQ(written.size(), 2u);
  EXPECT_DOUBLE_EQ(written[0], 0.2);  // a new output time (the grid has 0.15, 0.3, ...)
  EXPECT_DOUBLE_EQ(written[1], 0.6);  // an output time of the grid
  EXPECT_EQ(r.read_envelope("lever", "von_mises").times_s.size(), 12u);
}

}  // namespace
}  // namespace kinetofem::app
