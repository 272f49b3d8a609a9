// Faults: a `kinetofem run` ended by SIGINT (Ctrl-C) or SIGTERM while Gmsh
// meshes must leave nothing in $TMPDIR (the geometry text's folder
// kinetofem-geometry-*, the meshing process's kinetofem-mesh-*) and no Gmsh
// process running, and must still die of the signal (its exit status says so).
// SIGKILL to the program (no clean-up possible) must not leave Gmsh running
// either: the meshing process dies with its parent.
// Reference: core/termination_cleanup.hpp, meshes/src/meshing_process.hpp.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <thread>

#include "run_program.hpp"
#include "kinetofem/testing/scoped_tmpdir.hpp"

namespace fs = std::filesystem;
using kinetofem::test::Program;
using kinetofem::test::read_text;

namespace {

const fs::path kData = ROBUSTNESS_DATA_DIR;

using kinetofem::testing::ScopedTmpdir;

std::vector<std::string> entries(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) names.push_back(entry.path().filename().string());
  return names;
}

bool has_entry_starting(const fs::path& dir, const std::string& prefix) {
  for (const auto& name : entries(dir))
    if (name.rfind(prefix, 0) == 0) return true;
  return false;
}

// Processes whose command line holds `text` (the run's unique output folder).
int processes_with_argument(const std::string& text) {
  int count = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string pid = entry.path().filename().string();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = read_text(entry.path() / "cmdline");
    for (char& c : cmdline)
      if (c == '\0') c = ' ';
    if (cmdline.find(text) != std::string::npos) ++count;
  }
  return count;
}

bool wait_until(const std::function<bool()>& condition, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < end) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return condition();
}

struct RunFolders {
  fs::path work, tmp, out, capture;
};

RunFolders fresh(const std::string& tag) {
  RunFolders s;
  s.work = kinetofem::test::fresh_temp_dir("signal-meshing-" + tag);
  s.tmp = s.work / "tmp";
  s.out = s.work / "out";
  s.capture = s.work / "capture";
  fs::create_directories(s.tmp);
  fs::create_directories(s.capture);
  return s;
}

// The long-loop part of the catalogue (136_) with a time limit that does not
// stop it during the test.
fs::path long_loop_case(const RunFolders& s) {
  const fs::path source = kData / "136_part_geo_long_loop_time_limit";
  const fs::path folder = s.work / "case";
  fs::create_directories(folder);
  fs::copy_file(source / "block.geo", folder / "block.geo");
  std::string text = read_text(source / "case.toml");
  const std::string limit = "time_limit_s = 2.0";
  const auto at = text.find(limit);
  EXPECT_NE(at, std::string::npos);
  text.replace(at, limit.size(), "time_limit_s = 600.0");
  std::ofstream(folder / "case.toml") << text;
  return folder;
}

// Starts the run, waits until Gmsh works in its child process, sends `signal`.
kinetofem::test::ProgramResult signal_while_meshing(const RunFolders& s, const fs::path& folder, int signal) {
  const ScopedTmpdir scoped(s.tmp);
  Program program({KINETOFEM_EXE, "run", "case.toml", "-o", s.out.string()},
                  {.working_dir = folder, .capture_dir = s.capture});
  EXPECT_TRUE(wait_until([&] { return has_entry_starting(s.tmp, "kinetofem-mesh-"); }, 30.0))
      << "the meshing process did not start";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(program.pid(), signal);
  return program.wait(30.0);
}

TEST(SignalWhileMeshing, SigintDuringAPartFileLeavesNoTemporaryAndNoGmsh) {
  const RunFolders s = fresh("int");
  const auto result = signal_while_meshing(s, long_loop_case(s), SIGINT);
  EXPECT_FALSE(result.timed_out) << result.describe();
  EXPECT_EQ(result.signal, SIGINT) << result.describe();
  EXPECT_TRUE(entries(s.tmp).empty()) << "left in $TMPDIR: " << ::testing::PrintToString(entries(s.tmp));
  EXPECT_TRUE(wait_until([&] { return processes_with_argument(s.out.string()) == 0; }, 5.0))
      << "a Gmsh process of the run is still running";
  fs::remove_all(s.work);
}

TEST(SignalWhileMeshing, SigtermDuringTheBuiltInLeverLeavesNoTemporary) {
  // fe_static's parametric lever: its geometry text is written to
  // kinetofem-geometry-*; 1.5 mm TET10 keeps Gmsh busy for a while.
  const RunFolders s = fresh("term");
  const fs::path folder = s.work / "case";
  fs::create_directories(folder);
  std::string text = read_text(kData / "18_zero_length" / "case.toml");
  const std::string zero = "length_mm = 0.0";
  text.replace(text.find(zero), zero.size(), "length_mm = 500.0");
  const std::string size = "element_size_mm = 20.0";
  ASSERT_NE(text.find(size), std::string::npos);
  text.replace(text.find(size), size.size(), "element_size_mm = 1.5");
  std::ofstream(folder / "case.toml") << text;
  const ScopedTmpdir scoped(s.tmp);
  Program program({KINETOFEM_EXE, "run", "case.toml", "-o", s.out.string()},
                  {.working_dir = folder, .capture_dir = s.capture});
  ASSERT_TRUE(wait_until([&] { return has_entry_starting(s.tmp, "kinetofem-geometry-"); }, 30.0))
      << "meshing did not start: " << program.stdout_text();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(program.pid(), SIGTERM);
  const auto result = program.wait(30.0);
  EXPECT_EQ(result.signal, SIGTERM) << result.describe();
  EXPECT_TRUE(entries(s.tmp).empty()) << "left in $TMPDIR: " << ::testing::PrintToString(entries(s.tmp));
  EXPECT_TRUE(wait_until([&] { return processes_with_argument(s.out.string()) == 0; }, 5.0))
      << "a Gmsh process of the run is still running";
  fs::remove_all(s.work);
}

TEST(SignalWhileMeshing, SigkillOfTheProgramEndsItsMeshingProcess) {
  const RunFolders s = fresh("kill");
  const auto result = signal_while_meshing(s, long_loop_case(s), SIGKILL);
  EXPECT_EQ(result.signal, SIGKILL) << result.describe();
  EXPECT_TRUE(wait_until([&] { return processes_with_argument(s.out.string()) == 0; }, 5.0))
      << "the meshing process outlived the program";
  fs::remove_all(s.work);
}

}  // namespace
