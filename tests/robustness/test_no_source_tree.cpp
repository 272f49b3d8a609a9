// The program needs no source tree at run time: the link geometry
// (meshes/geometry/*.geo), the verification geometry and the SPEC §3 case
// files are compiled in. The built program, copied alone into a temporary
// directory and run there (no cases/ or meshes/ below its working directory,
// TMPDIR in a directory of its own), passes `kinetofem verify --quick` and
// runs the lever case at a coarse mesh, and leaves no temporary geometry
// behind; the executable holds no path to the source tree's data folders.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "run_program.hpp"

namespace {

namespace fs = std::filesystem;
using kinetofem::test::Program;
using kinetofem::test::read_text;

constexpr double kTimeoutS = 300.0;
// tests/data/robustness -> the source root.
const fs::path kSourceRoot = fs::path(ROBUSTNESS_DATA_DIR).parent_path().parent_path().parent_path();

// The program copied into `dir`/bin, a working directory `dir`/work and
// TMPDIR = `dir`/tmp for the children started while this object lives.
class CopiedProgram {
 public:
  explicit CopiedProgram(const std::string& tag) : dir_(kinetofem::test::fresh_temp_dir(tag)) {
    for (const char* sub : {"bin", "work", "tmp"}) fs::create_directories(dir_ / sub);
    fs::copy_file(KINETOFEM_EXE, exe());
    if (const char* old = std::getenv("TMPDIR")) old_tmpdir_ = old;
    ::setenv("TMPDIR", (dir_ / "tmp").c_str(), 1);
  }
  ~CopiedProgram() {
    if (old_tmpdir_) ::setenv("TMPDIR", old_tmpdir_->c_str(), 1);
    else ::unsetenv("TMPDIR");
    if (!::testing::Test::HasFailure()) fs::remove_all(dir_);
  }
  fs::path exe() const { return dir_ / "bin" / "kinetofem"; }
  fs::path work() const { return dir_ / "work"; }
  fs::path tmp() const { return dir_ / "tmp"; }
  kinetofem::test::ProgramResult run(std::vector<std::string> args) const {
    args.insert(args.begin(), exe().string());
    Program program(args, {.working_dir = work(), .capture_dir = dir_});
    return program.wait(kTimeoutS);
  }

 private:
  fs::path dir_;
  std::optional<std::string> old_tmpdir_;
};

std::size_t entries(const fs::path& dir) {
  return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(NoSourceTree, ProgramHoldsNoPathToTheSourceDataFolders) {
  const std::string binary = read_text(KINETOFEM_EXE);
  ASSERT_FALSE(binary.empty());
  for (const char* folder : {"meshes/geometry", "verification/geometry", "cases"})
    EXPECT_EQ(binary.find((kSourceRoot / folder).string()), std::string::npos) << folder;
}

TEST(NoSourceTree, CopiedProgramPassesVerifyQuick) {
  const CopiedProgram program("no-source-verify");
  const auto r = program.run({"verify", "--quick", "-q", "-o", "report"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r.describe();
  const std::string md = read_text(program.work() / "report" / "verification_report.md");
  EXPECT_NE(md.find("result: **PASS**"), std::string::npos) << md;
  EXPECT_EQ(entries(program.tmp()), 0u) << "temporary files left in " << program.tmp();
}

TEST(NoSourceTree, CopiedProgramRunsTheLeverCase) {
  const CopiedProgram program("no-source-run");
  // The case file is the user's input: it comes along; the lever's geometry does not.
  fs::copy_file(kSourceRoot / "cases" / "lever_static" / "case.toml", program.work() / "case.toml");
  const auto r = program.run({"run", "case.toml", "--set", "mesh.element_size_mm=20", "-o", "out", "-q"});
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r.describe();
  EXPECT_TRUE(fs::exists(program.work() / "out" / "lever_static.h5"));
  EXPECT_EQ(entries(program.tmp()), 0u) << "temporary files left in " << program.tmp();
}

}  // namespace
