// The manipulator pipeline end to end on a coarse mesh: meshes -> multibody
// with the meshes' mass properties -> IDAS -> link loads -> block solves ->
// envelope -> results file.
#include <gtest/gtest.h>

#include <filesystem>

#include <fmt/format.h>

#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/testing/manipulator_cases.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

std::string coarse_case(const std::string& type, double stroke_deg) {
  return testing::coarse_manipulator_case(type, stroke_deg);
}

std::string coarse_case_with(const std::string& type, const std::string& extra) {
  return testing::coarse_manipulator_case(type, 80.0, extra);
}

RunOptions quiet_options(const std::string& dir) {
  RunOptions options;
  options.output_dir = fs::temp_directory_path() / dir;
  fs::remove_all(options.output_dir);
  options.quiet = true;
  return options;
}

TEST(ManipulatorJob, LeverChainRunWritesEveryLinkOverTheMotion) {
  const CaseFile c = CaseFile::parse(coarse_case("lever_chain", 80.0), "case.toml", manipulator_schema());
  const RunOptions options = quiet_options("kinetofem_manip_chain");
  const ManipulatorSummary s = run_manipulator(c, options);
  ASSERT_EQ(s.links.size(), 2u);
  EXPECT_GT(s.min_chain_tension_n, 0.0);  // the chain stays taut over this motion
  EXPECT_GT(s.max_von_mises_pa, 0.0);
  // The motion starts from rest at the design position, which is the static
  // study's pose: the two stress states are the same (round-off).
  for (const auto& link : s.links) {
    EXPECT_GE(link.peak_von_mises_pa, link.static_von_mises_pa * (1 - 1e-9)) << link.body;
  }
  const auto file = post::ResultsFile::open(options.output_dir / "m.h5");
  const auto bodies = file.bodies();
  ASSERT_EQ(bodies.size(), 4u);  // lever, arm and the elastic assembly's assembly.lever, assembly.arm
  for (const std::string body : {"lever", "arm"}) {
    EXPECT_EQ(file.series_times(body).size(), 11u) << body;
    const auto step0 = file.read_step(body, "von_mises", 0);
    const auto statics = file.read_static(body, "static_von_mises");
    EXPECT_LT((step0.values - statics.values).cwiseAbs().maxCoeff(), 1e-6 * statics.values.maxCoeff()) << body;
    // The lever-chain is statically determinate: the assembly's link stresses are
    // the per-link model's, within 1e-6 of the peak (the same link loads, the same meshes).
    ASSERT_EQ(file.series_times("assembly." + body).size(), 11u) << body;
    for (fem::Index k : {0, 5, 10}) {
      const auto per_link = file.read_step(body, "von_mises", k);
      const auto assembly = file.read_step("assembly." + body, "von_mises", k);
      EXPECT_LT((per_link.values - assembly.values).cwiseAbs().maxCoeff(), 1e-6 * per_link.values.maxCoeff())
          << body << " step " << k;
    }
  }
  ASSERT_TRUE(s.assembly.has_value());
  EXPECT_EQ(s.assembly->indeterminacy.in_plane, 0);
  EXPECT_LT(s.assembly->worst_chain_mismatch, 1e-8);
  EXPECT_GT(s.assembly->static_max_displacement_m, 0.0);
  EXPECT_TRUE(fs::exists(options.output_dir / "m.xdmf"));
}

TEST(ManipulatorJob, PinsInContactWriteTheirPressureOverTheMotion) {
  // Every pin in contact (H7/g6): each link's series, envelope and static
  // field contact_pressure, one table per pin, the summary's pins. The
  // contact's resultant is the joint reaction at every time (the link's
  // support carries nothing: the run checks it, 1e-6), the pressure is >= 0
  // and the envelope is the series' maximum.
  const CaseFile c = CaseFile::parse(
      coarse_case_with("lever_chain", "[loads]\nbore_load = \"contact\"\nfit = \"H7/g6\"\n[assembly]\nenabled = false\n"),
      "case.toml", manipulator_schema());
  const RunOptions options = quiet_options("kinetofem_manip_contact");
  const ManipulatorSummary s = run_manipulator(c, options);
  ASSERT_EQ(s.links.size(), 2u);
  EXPECT_EQ(s.links[0].contacts.size(), 2u);  // lever: A0 and A
  EXPECT_EQ(s.links[1].contacts.size(), 1u);  // arm: A (the chain keeps its coupling)
  for (const auto& link : s.links) {
    EXPECT_LE(link.worst_support_reaction, 1e-6) << link.body;
    EXPECT_LE(link.contact_worst_resultant_error, 1e-8) << link.body;
    for (const auto& pin : link.contacts) {
      EXPECT_GT(pin.peak_pressure_pa, 0.0) << link.body << " " << pin.joint;
      EXPECT_NEAR(pin.clearance_m, 0.25 * (9e-6 + 50e-6), 1e-12) << pin.joint;  // H7/g6 at 40 mm: 9 .. 50 um
    }
  }
  const auto file = post::ResultsFile::open(options.output_dir / "m.h5");
  for (const std::string body : {"lever", "arm"}) {
    const auto envelope = file.read_envelope(body, "contact_pressure");
    double series_max = 0.0;
    for (fem::Index k = 0; k < 11; ++k) {
      const auto p = file.read_step(body, "contact_pressure", k);
      EXPECT_GE(p.values.minCoeff(), 0.0) << body;
      series_max = std::max(series_max, p.values.maxCoeff());
    }
    EXPECT_DOUBLE_EQ(envelope.values.maxCoeff(), series_max) << body;
    EXPECT_GT(file.read_static(body, "static_contact_pressure").values.maxCoeff(), 0.0) << body;
  }
  for (const char* table : {"contact.lever.A0", "contact.lever.A", "contact.arm.A"}) {
    const auto t = file.read_table(table);
    EXPECT_EQ(t.values.rows(), 11) << table;
    EXPECT_EQ(t.values.cols(), 4) << table;
  }
}

TEST(ManipulatorJob, VibrationKeysRunTheModesAndTheResponseOfH) {
  const CaseFile c = CaseFile::parse(
      testing::coarse_manipulator_case("lever_chain", 80.0,
                                       "[vibration]\nenabled = true\nmodes = 3\ndamping_ratio = 0.05\n"
                                       "settling_tolerance_mm = 0.001\n"),
      "case.toml", manipulator_schema());
  const RunOptions options = quiet_options("kinetofem_manip_vibration");
  const ManipulatorSummary s = run_manipulator(c, options);
  ASSERT_TRUE(s.vibration.has_value());
  EXPECT_EQ(s.vibration->modes, 3);
  EXPECT_DOUBLE_EQ(s.vibration->damping_ratio, 0.05);
  EXPECT_DOUBLE_EQ(s.vibration->settling_tolerance_m, 1e-6);
  EXPECT_EQ(s.vibration->frequency_hz.rows(), 11);
  EXPECT_GT(s.vibration->lowest_first_hz, 0.0);
  ASSERT_TRUE(s.vibration->has_static_study);
  ASSERT_EQ(s.vibration->points.size(), 1u);
  EXPECT_EQ(s.vibration->points[0].name, "H");
  EXPECT_GT(s.vibration->points[0].peak_dynamic_m, 0.0);
  EXPECT_NE(s.vibration->rule_check.find("holds"), std::string::npos) << s.vibration->rule_check;
  const auto file = post::ResultsFile::open(options.output_dir / "m.h5");
  EXPECT_EQ(file.read_history("vibration.frequency").values.cols(), 3);
  EXPECT_EQ(file.read_table("vibration.damping_ratio").values(0, 0), 0.05);
}

TEST(ManipulatorJob, FactorsThatDoNotFitTogetherAreMadeOneAtATimeWithTheSameResult) {
  // solver.max_factor_gb below the links' factors together but above each:
  // one factor in memory at a time, each freed after the elastic assembly's
  // solves of its link (driver). Reference: the same case with the default
  // limit (factors side by side, all kept). The per-link path is the same
  // factor up to the round-off of the BLAS's thread count (side by side: one
  // thread each; one after the other: all of them): 1e-12 relative. The
  // assembly superposes its loads in the limited run (11 output times: one
  // solve per pose otherwise), exact up to round-off: 1e-9 relative.
  const std::string base = testing::coarse_manipulator_case("lever_chain", 80.0);
  const ManipulatorSummary together = run_manipulator(CaseFile::parse(base, "case.toml", manipulator_schema()),
                                                      quiet_options("kinetofem_manip_together"));
  ASSERT_GT(together.factorization.predicted_factor_bytes, 0.0);
  const double limit_gb = 0.75 * together.factorization.predicted_factor_bytes * 1e-9;
  const std::string limited = base + fmt::format("[solver]\nmax_factor_gb = {:.17g}\n", limit_gb);
  const ManipulatorSummary apart = run_manipulator(CaseFile::parse(limited, "case.toml", manipulator_schema()),
                                                   quiet_options("kinetofem_manip_apart"));
  EXPECT_EQ(apart.factorization.side_by_side, 1);
  EXPECT_NE(apart.factorization.why.find("exceed"), std::string::npos) << apart.factorization.why;
  ASSERT_EQ(apart.links.size(), together.links.size());
  ASSERT_TRUE(apart.assembly && together.assembly);
  const auto near = [](double a, double b, double tolerance = 1e-9) { return std::abs(a - b) <= tolerance * std::abs(b); };
  for (size_t k = 0; k < apart.links.size(); ++k) {
    EXPECT_FALSE(apart.links[k].iterative_solver) << apart.links[k].body;
    EXPECT_TRUE(near(apart.links[k].peak_von_mises_pa, together.links[k].peak_von_mises_pa, 1e-12))
        << apart.links[k].body;
    EXPECT_TRUE(near(apart.links[k].peak_displacement_m, together.links[k].peak_displacement_m, 1e-12))
        << apart.links[k].body;
  }
  EXPECT_TRUE(near(apart.assembly->max_displacement_m, together.assembly->max_displacement_m))
      << apart.assembly->max_displacement_m << " vs " << together.assembly->max_displacement_m;
  EXPECT_TRUE(near(apart.assembly->static_max_displacement_m, together.assembly->static_max_displacement_m));
  ASSERT_EQ(apart.assembly->points.size(), 1u);
  EXPECT_TRUE(near(apart.assembly->points[0].max_displacement_m, together.assembly->points[0].max_displacement_m));
  for (size_t p = 0; p < apart.assembly->parts.size(); ++p)
    EXPECT_TRUE(near(apart.assembly->parts[p].max_von_mises_pa, together.assembly->parts[p].max_von_mises_pa))
        << apart.assembly->parts[p].body;

  // The vibration borrows the factors one at a time too (each made again for
  // its reductions): the same frequencies as with every factor kept, 1e-12
  // relative (the same factor made twice: the same arithmetic).
  const std::string vibration = "[vibration]\nenabled = true\nmodes = 3\n";
  const ManipulatorSummary vibrating_apart = run_manipulator(
      CaseFile::parse(limited + vibration, "case.toml", manipulator_schema()),
      quiet_options("kinetofem_manip_apart_vibration"));
  const ManipulatorSummary vibrating_together = run_manipulator(
      CaseFile::parse(base + vibration, "case.toml", manipulator_schema()),
      quiet_options("kinetofem_manip_together_vibration"));
  ASSERT_TRUE(vibrating_apart.vibration && vibrating_together.vibration);
  const Eigen::MatrixXd& fa = vibrating_apart.vibration->frequency_hz;
  const Eigen::MatrixXd& ft = vibrating_together.vibration->frequency_hz;
  ASSERT_EQ(fa.rows(), ft.rows());
  ASSERT_EQ(fa.cols(), ft.cols());
  for (Eigen::Index i = 0; i < fa.size(); ++i) EXPECT_TRUE(near(fa(i), ft(i), 1e-12)) << fa(i) << " vs " << ft(i);
}

TEST(ManipulatorJob, FactorAboveTheLimitSwitchesToTheIterativeSolverWithTheSameResult) {
  // solver.method = "auto" with a factor limit no link fits: CHOLMOD's symbolic
  // analysis predicts more and every link goes to AMG-PCG. Reference: the same
  // case with the direct solver; required: 1e-6 relative (the iterative path's
  // acceptance criterion) on each link's peak von Mises and deformation.
  // The elastic assembly is off: this is the per-link iterative path (the
  // assembly's interface solves on AMG-PCG would only add run time).
  // 30 mm elements (about 7 k DoFs a link): AMG-PCG's ~100 iterations a
  // right-hand side on 20 mm meshes made this the suite's longest test.
  const std::string base =
      testing::coarse_manipulator_case("lever_chain", 40.0, "[assembly]\nenabled = false\n", 30.0);
  const CaseFile direct = CaseFile::parse(base + "[solver]\nmethod = \"direct\"\n", "case.toml", manipulator_schema());
  const CaseFile automatic =
      CaseFile::parse(base + "[solver]\nmax_factor_gb = 1e-6\n", "case.toml", manipulator_schema());
  const ManipulatorSummary d = run_manipulator(direct, quiet_options("kinetofem_manip_direct"));
  const ManipulatorSummary a = run_manipulator(automatic, quiet_options("kinetofem_manip_auto"));
  ASSERT_EQ(d.links.size(), a.links.size());
  for (size_t k = 0; k < d.links.size(); ++k) {
    EXPECT_FALSE(d.links[k].iterative_solver) << d.links[k].body;
    EXPECT_TRUE(a.links[k].iterative_solver) << a.links[k].body;
    EXPECT_NE(a.links[k].solver_summary.find("AMG-PCG"), std::string::npos) << a.links[k].solver_summary;
    EXPECT_NEAR(a.links[k].peak_von_mises_pa, d.links[k].peak_von_mises_pa, 1e-6 * d.links[k].peak_von_mises_pa);
    EXPECT_NEAR(a.links[k].peak_displacement_m, d.links[k].peak_displacement_m,
                1e-6 * d.links[k].peak_displacement_m);
    EXPECT_NEAR(a.links[k].static_von_mises_pa, d.links[k].static_von_mises_pa,
                1e-6 * d.links[k].static_von_mises_pa);
  }
}

TEST(ManipulatorJob, LeverManipulatorHasThreeLinks) {
  const CaseFile c = CaseFile::parse(coarse_case("lever", 30.0), "case.toml", manipulator_schema());
  const RunOptions options = quiet_options("kinetofem_manip_lever");
  const ManipulatorSummary s = run_manipulator(c, options);
  ASSERT_EQ(s.links.size(), 3u);
  EXPECT_EQ(s.links[2].body, "rocker");
}

TEST(ManipulatorJob, FourBarDrivenPastItsAssemblyLimitIsAClearError) {
  // SPEC §2: the example four-bar assembles only up to dphi = +36.4 deg.
  const CaseFile c = CaseFile::parse(coarse_case("lever", 60.0), "case.toml", manipulator_schema());
  const RunOptions options = quiet_options("kinetofem_manip_limit");
  try {
    run_manipulator(c, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("the motion cannot be run"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(options.output_dir / "m.h5"));
}

}  // namespace
}  // namespace kinetofem::app
