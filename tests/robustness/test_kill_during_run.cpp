// Faults: a `kinetofem run` killed with SIGKILL while it works (no chance to
// clean up) must never leave a file under the results' final names
// (<name>.h5, <name>.xdmf): only a temporary <name>.h5.tmp may remain. An
// earlier results file under that name stays byte-identical, and the same
// command run again completes (and leaves no temporary).
// Reference: the atomic commit of post::ResultsWriter (results_writer.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <thread>

#include "kinetofem/postproc/results_file.hpp"
#include "run_program.hpp"

namespace fs = std::filesystem;
using kinetofem::test::Program;
using kinetofem::test::read_text;

namespace {

const fs::path kFaults = fs::path(ROBUSTNESS_DATA_DIR) / "faults";

std::vector<std::string> run_args(const std::string& case_file, const fs::path& out) {
  return {KINETOFEM_EXE, "run", (kFaults / case_file).string(), "-o", out.string()};
}

// Files under the output directory other than temporaries.
std::vector<std::string> final_files(const fs::path& out) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.ends_with(".tmp")) names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

bool has_temporaries(const fs::path& out) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out, ec))
    if (entry.path().filename().string().ends_with(".tmp")) return true;
  return false;
}

kinetofem::test::ProgramResult run_to_end(const std::string& case_file, const fs::path& out,
                                          const fs::path& capture) {
  Program program(run_args(case_file, out), {.working_dir = kFaults, .capture_dir = capture});
  return program.wait(120.0);
}

// Starts the run and kills it (SIGKILL) once its stdout holds `marker`.
kinetofem::test::ProgramResult kill_at_marker(const std::string& case_file, const fs::path& out,
                                              const fs::path& capture, const std::string& marker) {
  Program program(run_args(case_file, out), {.working_dir = kFaults, .capture_dir = capture});
  while (program.stdout_text().find(marker) == std::string::npos && program.seconds() < 120.0) {
    int status = 0;
    if (::waitpid(program.pid(), &status, WNOHANG) == program.pid()) {
      ADD_FAILURE() << "the run ended before '" << marker << "' appeared";
      return {};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return program.kill_and_wait();
}

TEST(KillDuringRun, ManipulatorKilledWhileWritingKeepsTheEarlierResults) {
  const fs::path temp = kinetofem::test::fresh_temp_dir("kill-manipulator");
  const fs::path out = temp / "out";
  // 1. A complete run: the results a later, killed run must not damage.
  const auto first = run_to_end("manipulator.toml", out, temp);
  ASSERT_TRUE(first.exited && first.exit_code == 0) << first.describe();
  ASSERT_TRUE(fs::exists(out / "r.h5") && fs::exists(out / "r.xdmf"));
  const std::string h5 = read_text(out / "r.h5"), xdmf = read_text(out / "r.xdmf");
  const auto before = final_files(out);

  // 2. The same run, killed once it solves the links over the motion: the
  // results file is open (r.h5.tmp) and being written step by step.
  const auto killed = kill_at_marker("manipulator.toml", out, temp, "time steps");
  ASSERT_FALSE(killed.exited) << "the run was not killed: " << killed.describe();
  EXPECT_EQ(killed.signal, SIGKILL);
  EXPECT_TRUE(fs::exists(out / "r.h5.tmp")) << "killed before the writer started: the test proves nothing";
  EXPECT_EQ(final_files(out), before);
  EXPECT_TRUE(read_text(out / "r.h5") == h5) << "r.h5 changed";
  EXPECT_TRUE(read_text(out / "r.xdmf") == xdmf) << "r.xdmf changed";

  // 3. The same command again completes and leaves no temporary behind.
  const auto again = run_to_end("manipulator.toml", out, temp);
  ASSERT_TRUE(again.exited && again.exit_code == 0) << again.describe();
  EXPECT_EQ(final_files(out), before);
  EXPECT_FALSE(has_temporaries(out));
  if (!HasFailure()) fs::remove_all(temp);
}

TEST(KillDuringRun, KilledAtFixedDelaysLeavesNoResultsUnderFinalNames) {
  // No earlier results: whatever the phase the kill hits (reading, meshing,
  // solving, writing), no r.h5, r.xdmf or r.summary.toml may appear before
  // the results file is committed (renamed into place). A kill after that
  // (the process still printing its summary or, under LeakSanitizer,
  // checking for leaks at exit) leaves a complete, readable results file.
  for (const double delay_s : {0.2, 0.6, 1.0, 1.5}) {
    const fs::path temp = kinetofem::test::fresh_temp_dir("kill-fe-static");
    const fs::path out = temp / "out";
    Program program(run_args("fe_static.toml", out), {.working_dir = kFaults, .capture_dir = temp});
    std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
    const auto killed = program.kill_and_wait();
    if (killed.exited) {  // finished before the kill: then it must have finished properly
      EXPECT_EQ(killed.exit_code, 0) << killed.describe();
      continue;
    }
    if (fs::exists(out / "r.h5")) {  // killed after the commit: complete results only
      const auto results = kinetofem::post::ResultsFile::open(out / "r.h5");
      EXPECT_EQ(results.bodies().size(), 1u) << "delay " << delay_s << " s";
      EXPECT_FALSE(fs::exists(out / "r.h5.tmp")) << "delay " << delay_s << " s";
      if (!HasFailure()) fs::remove_all(temp);
      continue;
    }
    EXPECT_FALSE(fs::exists(out / "r.xdmf")) << "delay " << delay_s << " s";
    EXPECT_FALSE(fs::exists(out / "r.summary.toml")) << "delay " << delay_s << " s";
    const auto again = run_to_end("fe_static.toml", out, temp);
    ASSERT_TRUE(again.exited && again.exit_code == 0) << again.describe();
    EXPECT_TRUE(fs::exists(out / "r.h5"));
    EXPECT_FALSE(has_temporaries(out));
    if (!HasFailure()) fs::remove_all(temp);
  }
}

}  // namespace
