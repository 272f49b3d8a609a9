// The bundled SPEC §5 spherical manipulator with its parts
// (cases/spherical_manipulator_parts) through the whole chain at a coarse
// setting (4 output intervals, 40 mm linear elements, a thick arm and long guide
// lands so that the arm has few slide stations): the closed form, the spatial
// core, the parts' stress, the spatial elastic assembly (M's positioning
// error and its split) and the natural frequencies per pose, as the program
// writes them.
// References: the unit-load method, M's shares add up to its error
// (Maxwell-Betti, 1e-9 of it, read back from the results file); the
// assembly's M error equals what the file's history holds (the write is
// exact); the arm's share dominates (a 2.7 m cantilever against a short
// column and sleeve: more than half); the frequencies are positive and
// ascending in every pose, and the first lies within the band the summary
// prints.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include <fmt/format.h>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/postproc/results_file.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

TEST(SphericalManipulatorPartsCase, MsPositioningErrorSplitsIntoThePartsAndTheStructureHasItsFrequencies) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("kinetofem_spherical_parts_case_{}", ::getpid());
  fs::remove_all(dir);
  RunOptions options;
  options.output_dir = dir;
  options.quiet = true;
  options.overrides = {"motion.intervals=4",     "mesh.element_size_mm=40.0",    "check.forward_dynamics=false",
                       "fatigue.enabled=false",  "parts.arm_diameter_ratio=0.3", "parts.guide_length_ratio=2.0",
                       "parts.vibration_modes=3",      "mesh.order=1"};
  const CaseFile c = CaseFile::load("cases/spherical_manipulator_parts/case.toml", spherical_manipulator_schema(),
                                    false, options.overrides);
  const MechanismCaseSummary summary = run_spherical_manipulator(c, options);
  double error_mm = -1.0, first_hz = -1.0;
  for (const auto& [key, value] : summary.values) {
    if (key == "M_error_mm") error_mm = value;
    if (key == "first_frequency_min_hz") first_hz = value;
  }
  ASSERT_GT(error_mm, 0.0);
  ASSERT_GT(first_hz, 0.0);

  const post::ResultsFile file = post::ResultsFile::open(summary.results_file);
  const Eigen::MatrixXd u = file.read_history("assembly.point.M.displacement").values;
  ASSERT_EQ(u.rows(), 5);
  EXPECT_NEAR(u.rowwise().norm().maxCoeff() * 1e3, error_mm, 1e-12 * error_mm);
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(u.rows(), 3);
  double arm_share = 0.0;
  for (const char* part : {"column", "sleeve", "arm"}) {
    const Eigen::MatrixXd share = file.read_history(fmt::format("assembly.point.M.from.part.{}", part)).values;
    sum += share;
    if (std::string(part) == "arm") arm_share = share.rowwise().norm().maxCoeff();
  }
  EXPECT_LT((sum - u).cwiseAbs().maxCoeff(), 1e-9 * u.cwiseAbs().maxCoeff());  // Maxwell-Betti
  EXPECT_GT(arm_share, 0.5 * u.rowwise().norm().maxCoeff());

  const Eigen::MatrixXd f = file.read_history("vibration.frequency").values;
  ASSERT_EQ(f.rows(), 5);
  ASSERT_EQ(f.cols(), 3);
  for (Eigen::Index k = 0; k < f.rows(); ++k) {
    EXPECT_GT(f(k, 0), 0.0);
    for (Eigen::Index m = 1; m < f.cols(); ++m) EXPECT_GE(f(k, m), f(k, m - 1));
  }
  EXPECT_NEAR(f.col(0).minCoeff(), first_hz, 1e-12 * first_hz);
  fmt::print("spherical parts case: M error {:.4f} mm (arm {:.4f} mm), first frequency {:.3f}-{:.3f} Hz\n", error_mm,
             1e3 * arm_share, f.col(0).minCoeff(), f.col(0).maxCoeff());
  fs::remove_all(dir);
}

}  // namespace
}  // namespace kinetofem::app
