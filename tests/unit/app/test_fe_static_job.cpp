// The fe_static pipeline end to end on a bar in uniaxial tension: case file
// -> Gmsh mesh -> assembly -> CHOLMOD -> stress recovery -> HDF5/XDMF.
#include <gtest/gtest.h>

#include <filesystem>

#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("kinetofem_test_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(FeStaticJob, BarInTensionMatchesTheExactUniaxialSolution) {
  // Reference: sigma_xx = F / A = 10 kN / (20 mm x 20 mm) = 25 MPa uniform
  // (von Mises = 25 MPa); u_x(L) = F L / (E A) = 1e4 * 0.1 / (2e11 * 4e-4)
  // = 1.25e-5 m; |u| adds the lateral Poisson contraction nu * eps * 20 mm
  // at the far corner: sqrt(1.25e-5^2 + 2 * (0.3 * 1.25e-4 * 0.02)^2).
  // TET10 reproduces a constant strain state exactly: tolerance 1e-6 relative.
  RunOptions options;
  options.case_path = "tests/data/cases/bar_tension/case.toml";
  options.output_dir = fresh_dir("bar");
  options.quiet = true;
  const CaseFile c = CaseFile::load(options.case_path, fe_static_schema());
  const FeStaticSummary s = run_fe_static(c, options);
  EXPECT_NEAR(s.max_von_mises_pa, 25e6, 25e6 * 1e-6);
  const double lateral = 0.3 * 1.25e-4 * 0.02;
  const double corner = std::sqrt(1.25e-5 * 1.25e-5 + 2 * lateral * lateral);
  EXPECT_NEAR(s.max_displacement_m, corner, corner * 1e-6);
  EXPECT_LT(s.reaction_balance, 1e-9);
  EXPECT_TRUE(fs::exists(options.output_dir / "bar_tension.h5"));
  EXPECT_TRUE(fs::exists(options.output_dir / "bar_tension.xdmf"));
  EXPECT_FALSE(fs::exists(options.output_dir / "bar_tension.h5.tmp"));
}

TEST(FeStaticJob, UnknownSupportSetIsAnErrorAndWritesNoResult) {
  const fs::path dir = fresh_dir("badset");
  fs::copy_file("tests/data/cases/bar_tension/bar.geo", dir / "bar.geo");
  std::string text =
      "[case]\nname = \"bad\"\ntype = \"fe_static\"\n[geometry]\nkind = \"file\"\nfile = \"bar.geo\"\n"
      "[mesh]\nelement_size_mm = 20\norder = 1\n[[support]]\nset = \"nowhere\"\n";
  const CaseFile c = CaseFile::parse(text, dir / "case.toml", fe_static_schema());
  RunOptions options;
  options.output_dir = dir / "out";
  options.quiet = true;
  try {
    run_fe_static(c, options);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("support[0].set"), std::string::npos) << what;
    EXPECT_NE(what.find("\"nowhere\""), std::string::npos) << what;
    EXPECT_NE(what.find("x0"), std::string::npos) << what;  // lists the sets present
  }
  EXPECT_FALSE(fs::exists(dir / "out" / "bad.h5"));
}

TEST(FeStaticJob, UnwritableOutputDirectoryIsAnError) {
  const CaseFile c = CaseFile::load("tests/data/cases/bar_tension/case.toml", fe_static_schema());
  RunOptions options;
  options.output_dir = "/proc/kinetofem_cannot_write_here";
  options.quiet = true;
  EXPECT_THROW(run_fe_static(c, options), Error);
}

}  // namespace
}  // namespace kinetofem::app
