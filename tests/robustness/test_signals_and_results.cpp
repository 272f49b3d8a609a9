// Faults around the results files and the processes that write them:
//  - `post` on a results file whose indices are damaged (a connectivity entry
//    equal to the node count, negative, huge; an envelope step past the last
//    time) ends with a one-line error naming the file, the dataset and the
//    value, exit code 1: never a read out of bounds or a crash;
//  - a run ended by SIGINT or SIGTERM while it writes leaves no temporary
//    results file (a SIGKILL cannot clean up: test_kill_during_run.cpp);
//  - a stale <name>.h5.tmp that is a symbolic link is not written through;
//  - SIGTERM to a `batch` stops its runs too, and the batch then resumes
//    without "unable to lock file" failures.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "run_program.hpp"

namespace fs = std::filesystem;
using kinetofem::test::Program;
using kinetofem::test::ProgramResult;
using kinetofem::test::read_text;

namespace {

const fs::path kFaults = fs::path(ROBUSTNESS_DATA_DIR) / "faults";

ProgramResult run_program(const std::vector<std::string>& args, const fs::path& capture, double timeout_s = 120.0) {
  Program program(args, {.working_dir = kFaults, .capture_dir = capture});
  return program.wait(timeout_s);
}

std::vector<std::string> run_args(const std::string& case_file, const fs::path& out) {
  return {KINETOFEM_EXE, "run", (kFaults / case_file).string(), "-o", out.string()};
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos) names.push_back(name);
  }
  return names;
}

// Overwrites entry `k` of the int64 dataset `path` in `file` with `value`.
void damage_index(const fs::path& file, const std::string& path, std::size_t k, long long value) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t d = H5Dopen2(f, path.c_str(), H5P_DEFAULT);
  ASSERT_GE(d, 0) << path;
  const hid_t space = H5Dget_space(d);
  const hssize_t n = H5Sget_simple_extent_npoints(space);
  ASSERT_GT(n, hssize_t(k));
  std::vector<long long> values(static_cast<std::size_t>(n));
  ASSERT_GE(H5Dread(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  values[k] = value;
  ASSERT_GE(H5Dwrite(d, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
  H5Sclose(space);
  H5Dclose(d);
  H5Fclose(f);
}

class DamagedIndex : public ::testing::TestWithParam<long long> {};

TEST_P(DamagedIndex, PostEndsWithAnErrorNamingTheDatasetAndValue) {
  const fs::path temp = kinetofem::test::fresh_temp_dir("damaged-index");
  const fs::path out = temp / "out";
  const auto run = run_program(run_args("fe_static.toml", out), temp);
  ASSERT_TRUE(run.exited && run.exit_code == 0) << run.describe();
  const fs::path damaged = temp / "damaged.h5";
  fs::copy_file(out / "r.h5", damaged);
  const std::string dataset = "/bodies/part/mesh/blocks/block_0/connectivity";
  // -1: the node count of this mesh (the first index past the end).
  const hid_t f = H5Fopen(damaged.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  const hid_t group = H5Gopen2(f, "/bodies/part", H5P_DEFAULT);
  ASSERT_GE(group, 0) << "the fault case's body is not called 'part'";
  long long nodes = 0;
  const hid_t attribute = H5Aopen(group, "node_count", H5P_DEFAULT);
  H5Aread(attribute, H5T_NATIVE_LLONG, &nodes);
  H5Aclose(attribute);
  H5Gclose(group);
  H5Fclose(f);
  const long long bad = GetParam() == -1 ? nodes : GetParam();
  damage_index(damaged, dataset, 5, bad);

  const std::vector<std::vector<std::string>> commands = {
      {KINETOFEM_EXE, "post", damaged.string(), "--png", (temp / "png").string()},
      {KINETOFEM_EXE, "post", damaged.string()},
      {KINETOFEM_EXE, "post", damaged.string(), "--csv", (temp / "csv").string()},
      {KINETOFEM_EXE, "post", damaged.string(), "--all"},
  };
  for (const auto& command : commands) {
    fs::create_directories(temp / "png");
    fs::create_directories(temp / "csv");
    const auto r = run_program(command, temp, 60.0);
    const std::string shown = command.size() > 3 ? command[3] : "(summary)";
    EXPECT_TRUE(r.exited && r.exit_code == 1) << shown << ": " << r.describe();
    EXPECT_NE(r.err.find("kinetofem: error: "), std::string::npos) << shown << ": " << r.err;
    EXPECT_NE(r.err.find(damaged.string()), std::string::npos) << shown << ": " << r.err;
    EXPECT_NE(r.err.find(dataset), std::string::npos) << shown << ": " << r.err;
    EXPECT_NE(r.err.find("is node " + std::to_string(bad)), std::string::npos) << shown << ": " << r.err;
  }
  if (!HasFailure()) fs::remove_all(temp);
}

// -1 stands for the node count.
INSTANTIATE_TEST_SUITE_P(Values, DamagedIndex, ::testing::Values(-1LL, -5LL, 1LL << 40));

// Starts the run and sends `signal_number` once its stdout holds `marker` and
// its results temporary exists.
ProgramResult signal_while_writing(const std::string& case_file, const fs::path& out, const fs::path& capture,
                                   int signal_number, const fs::path& temporary) {
  Program program(run_args(case_file, out), {.working_dir = kFaults, .capture_dir = capture});
  while ((program.stdout_text().find("time steps") == std::string::npos || !fs::exists(temporary)) &&
         program.seconds() < 120.0) {
    int status = 0;
    if (::waitpid(program.pid(), &status, WNOHANG) == program.pid()) {
      ADD_FAILURE() << "the run ended before it wrote";
      return {};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ::kill(program.pid(), signal_number);
  return program.wait(60.0);
}

class SignalWhileWriting : public ::testing::TestWithParam<int> {};

TEST_P(SignalWhileWriting, LeavesNoTemporaryResultsFile) {
  const int signal_number = GetParam();
  const fs::path temp = kinetofem::test::fresh_temp_dir("signal-writing");
  const fs::path out = temp / "out";
  const auto r = signal_while_writing("manipulator.toml", out, temp, signal_number, out / "r.h5.tmp");
  ASSERT_FALSE(r.timed_out) << r.describe();
  EXPECT_FALSE(r.exited) << "not ended by the signal: " << r.describe();
  EXPECT_EQ(r.signal, signal_number) << r.describe();
  EXPECT_EQ(temporaries(out), std::vector<std::string>{});
  EXPECT_FALSE(fs::exists(out / "r.h5"));
  if (!HasFailure()) fs::remove_all(temp);
}

INSTANTIATE_TEST_SUITE_P(Signals, SignalWhileWriting, ::testing::Values(SIGINT, SIGTERM));

TEST(StaleTemporary, SymbolicLinkIsNotWrittenThrough) {
  const fs::path temp = kinetofem::test::fresh_temp_dir("stale-symlink");
  const fs::path out = temp / "out";
  fs::create_directories(out);
  const fs::path target = temp / "precious.txt";
  std::ofstream(target) << "keep me\n";
  fs::create_symlink(target, out / "r.h5.tmp");
  fs::create_symlink(target, out / "r.xdmf.tmp");
  const auto r = run_program(run_args("fe_static.toml", out), temp);
  ASSERT_TRUE(r.exited && r.exit_code == 0) << r.describe();
  EXPECT_EQ(read_text(target), "keep me\n");
  EXPECT_FALSE(fs::is_symlink(out / "r.h5"));
  EXPECT_FALSE(fs::is_symlink(out / "r.xdmf"));
  EXPECT_TRUE(fs::is_regular_file(out / "r.h5"));
  EXPECT_EQ(temporaries(out), std::vector<std::string>{});
  if (!HasFailure()) fs::remove_all(temp);
}

// Processes whose command line mentions `text` (the test's own folder).
std::vector<pid_t> processes_mentioning(const std::string& text) {
  std::vector<pid_t> pids;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/proc", ec)) {
    const std::string name = entry.path().filename().string();
    if (name.find_first_not_of("0123456789") != std::string::npos) continue;
    std::string cmdline = read_text(entry.path() / "cmdline");
    std::replace(cmdline.begin(), cmdline.end(), '\0', ' ');
    if (cmdline.find(text) != std::string::npos) pids.push_back(pid_t(std::stol(name)));
  }
  return pids;
}

TEST(BatchTerminated, StopsItsRunsAndResumesWithoutLockFailures) {
  const fs::path temp = kinetofem::test::fresh_temp_dir("batch-sigterm");
  const fs::path out = temp / "out";
  std::vector<std::string> args = {KINETOFEM_EXE, "batch"};
  const std::string text = read_text(kFaults / "manipulator.toml");
  for (const std::string name : {"m1", "m2"}) {
    std::string copy = text;
    copy.replace(copy.find("name = \"r\""), 10, "name = \"" + name + "\"");
    std::ofstream(temp / (name + ".toml")) << copy;
    args.push_back((temp / (name + ".toml")).string());
  }
  for (const std::string a : {"--jobs", "2", "-o"}) args.push_back(a);
  args.push_back(out.string());
  {
    Program batch(args, {.working_dir = temp, .capture_dir = temp});
    while (!(fs::exists(out / "m1.h5.tmp") && fs::exists(out / "m2.h5.tmp")) && batch.seconds() < 120.0)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(fs::exists(out / "m1.h5.tmp") && fs::exists(out / "m2.h5.tmp")) << "the runs did not start writing";
    ::kill(batch.pid(), SIGTERM);
    const auto r = batch.wait(60.0);
    EXPECT_FALSE(r.exited) << r.describe();
    EXPECT_EQ(r.signal, SIGTERM) << r.describe();
  }
  const auto left = processes_mentioning(out.string());
  EXPECT_TRUE(left.empty()) << left.size() << " runs outlived the batch";
  for (const pid_t pid : left) ::kill(pid, SIGKILL);  // not to disturb what follows
  EXPECT_EQ(temporaries(out), std::vector<std::string>{});

  // The documented resume: the same command again.
  const auto again = run_program(args, temp, 180.0);
  EXPECT_TRUE(again.exited && again.exit_code == 0) << again.describe();
  EXPECT_EQ(again.out.find("unable to lock"), std::string::npos) << again.out;
  EXPECT_NE(read_text(out / "batch_summary.csv").find("m1,done"), std::string::npos);
  EXPECT_NE(read_text(out / "batch_summary.csv").find("m2,done"), std::string::npos);
  if (!HasFailure()) fs::remove_all(temp);
}

}  // namespace
