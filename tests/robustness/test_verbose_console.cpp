// The console of a run: each solve's statistics (the CHOLMOD solve and
// factorize lines, the ordering) only under -v; the stage lines (the factor's
// size from CHOLMOD analyze) and the summary either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_program.hpp"

namespace fs = std::filesystem;
using kinetofem::test::Program;

namespace {

const fs::path kFaults = fs::path(ROBUSTNESS_DATA_DIR) / "faults";

TEST(VerboseConsole, SolveStatisticsOnlyWithVerbose) {
  const fs::path temp = kinetofem::test::fresh_temp_dir("verbose-console");
  auto run = [&](const std::string& flag, const std::string& sub) {
    std::vector<std::string> args = {KINETOFEM_EXE, "run", (kFaults / "fe_static.toml").string(), "-o",
                                     (temp / sub).string()};
    if (!flag.empty()) args.push_back(flag);
    Program program(args, {.working_dir = kFaults, .capture_dir = temp});
    const auto r = program.wait(120.0);
    EXPECT_TRUE(r.exited && r.exit_code == 0) << flag << ": " << r.describe();
    return r.out;
  };
  const std::string normal = run("", "normal"), verbose = run("-v", "verbose");
  for (const std::string& out : {normal, verbose}) {
    EXPECT_NE(out.find("CHOLMOD analyze: "), std::string::npos) << out;
    EXPECT_NE(out.find("Summary of 'r'"), std::string::npos) << out;
  }
  EXPECT_EQ(normal.find("CHOLMOD solve: "), std::string::npos) << normal;
  EXPECT_EQ(normal.find("CHOLMOD factorize: "), std::string::npos) << normal;
  EXPECT_NE(verbose.find("CHOLMOD solve: "), std::string::npos) << verbose;
  EXPECT_NE(verbose.find("CHOLMOD factorize: "), std::string::npos) << verbose;
  EXPECT_EQ(normal.find("ordering: "), std::string::npos) << normal;
  EXPECT_NE(verbose.find("ordering: "), std::string::npos) << verbose;
  if (!HasFailure()) fs::remove_all(temp);
}

}  // namespace
