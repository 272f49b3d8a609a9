// `kinetofem run --set` and `kinetofem batch`: overrides and their errors,
// the batch's statuses and summary table, skipping up-to-date runs, resuming
// a killed batch, sweeps, and MPI ranks. The batch tests start the built
// program (KINETOFEM_EXE) on copies of tests/data/cases/bar_tension (about
// 1 s a run).
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "kinetofem/app/batch.hpp"
#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

// A fresh folder for one test, removed at its end unless the test failed.
struct TempDir {
  explicit TempDir(const std::string& name)
      : path(fs::temp_directory_path() / fmt::format("kinetofem_batch_{}_{}", name, ::getpid())) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    if (!::testing::Test::HasFailure()) fs::remove_all(path, ec);
  }
  fs::path path;
};

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// A copy of the bar-in-tension case in dir/<folder>/case.toml, named `name`,
// with `extra` appended to its text.
fs::path bar_case(const fs::path& dir, const std::string& folder, const std::string& name,
                  const std::string& extra = "") {
  const fs::path case_dir = dir / folder;
  fs::create_directories(case_dir);
  fs::copy_file("tests/data/cases/bar_tension/bar.geo", case_dir / "bar.geo");
  std::string text = read_text("tests/data/cases/bar_tension/case.toml");
  const std::string old_name = "name = \"bar_tension\"";
  text.replace(text.find(old_name), old_name.size(), "name = \"" + name + "\"");
  std::ofstream(case_dir / "case.toml") << text << extra;
  return case_dir / "case.toml";
}

struct Command {
  int exit_code;
  std::string output;
};

// Runs the kinetofem program with `args` (a shell command line), output captured.
Command kinetofem(const std::string& args, const fs::path& dir, const std::string& prefix = "") {
  const fs::path out = dir / "command_output.txt";
  const std::string command = prefix + KINETOFEM_EXE + " " + args + " > " + out.string() + " 2>&1";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(out)};
}

// case -> status from DIR/batch_summary.csv (the first two columns hold no commas).
std::map<std::string, std::string> statuses(const fs::path& dir) {
  std::map<std::string, std::string> out;
  std::istringstream in(read_text(dir / "batch_summary.csv"));
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const auto comma = line.find(',');
    out[line.substr(0, comma)] = line.substr(comma + 1, line.find(',', comma + 1) - comma - 1);
  }
  return out;
}

std::string error_of(const std::string& text, const std::vector<std::string>& overrides) {
  try {
    CaseFile::parse(text, "case.toml", fe_static_schema(), false, overrides);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

const char* kCase =
    "[case]\ntype = \"fe_static\"\n[mesh]\nelement_size_mm = 10\n[[force]]\nset = \"x1\"\ntotal_n = [1, 0, 0]\n";

TEST(CaseOverride, SetReplacesAndAddsKeysInSiUnits) {
  const CaseFile c = CaseFile::parse(
      kCase, "case.toml", fe_static_schema(), false,
      {"mesh.element_size_mm=20", "material.youngs_modulus_mpa = 7e4", "mesh.family=hex",
       "force[0].total_n=[0, 5000, 0]", "case.name=\"bar 2\""});
  EXPECT_DOUBLE_EQ(c.number("mesh.element_size_mm"), 0.02);          // replaced
  EXPECT_DOUBLE_EQ(c.number("material.youngs_modulus_mpa"), 70e9);   // added ([material] absent)
  EXPECT_EQ(c.text_value("mesh.family"), "hex");                      // a bare word is a string
  EXPECT_DOUBLE_EQ(c.vector3("force[].total_n", 0).y(), 5000.0);
  EXPECT_EQ(c.text_value("case.name"), "bar 2");
  EXPECT_EQ(c.overrides().size(), 5u);
  EXPECT_NE(c.where("mesh.element_size_mm").find("(--set mesh.element_size_mm=20)"), std::string::npos)
      << c.where("mesh.element_size_mm");
  EXPECT_EQ(c.where("mesh.order"), "case.toml: key 'mesh.order'");  // not overridden
}

TEST(CaseOverride, ErrorsNameTheOverride) {
  std::string e = error_of(kCase, {"mesh.element_sise_mm=20"});
  EXPECT_NE(e.find("--set mesh.element_sise_mm=20: unknown key 'mesh.element_sise_mm'"), std::string::npos) << e;
  e = error_of(kCase, {"mesh.element_size_mm=-2"});
  EXPECT_NE(e.find("--set mesh.element_size_mm=-2: key 'mesh.element_size_mm' = -2 mm is out of range"),
            std::string::npos)
      << e;
  e = error_of(kCase, {"mesh.element_size_mm=fine"});
  EXPECT_NE(e.find("--set mesh.element_size_mm=fine: key 'mesh.element_size_mm' must be a number"),
            std::string::npos)
      << e;
  e = error_of(kCase, {"mesh.family=\"quad\""});
  EXPECT_NE(e.find("--set mesh.family=\"quad\""), std::string::npos) << e;
  EXPECT_NE(e.find("is not allowed"), std::string::npos) << e;
  e = error_of(kCase, {"force[3].total_n=[1, 0, 0]"});
  EXPECT_NE(e.find("the case has 1 [[force]] element(s)"), std::string::npos) << e;
  e = error_of(kCase, {"force[0].total_n=[1, 0"});
  EXPECT_NE(e.find("is not a TOML value"), std::string::npos) << e;
  e = error_of(kCase, {"mesh"});
  EXPECT_NE(e.find("--set mesh: expected KEY=VALUE"), std::string::npos) << e;
  e = error_of(kCase, {"support=1"});
  EXPECT_NE(e.find("is an array of tables"), std::string::npos) << e;
}

TEST(CaseOverride, RunCommandAppliesSetAndReportsItsErrors) {
  const TempDir temp("run_set");
  const fs::path& dir = temp.path;
  const fs::path c = bar_case(dir, "bar", "bar");
  Command r = kinetofem(fmt::format("run {} -q -o {} --set mesh.element_size_mm=20 --set case.name=bar_set",
                                    c.string(), (dir / "out").string()),
                        dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto summary = read_run_summary(dir / "out" / "bar_set.summary.toml");
  ASSERT_TRUE(summary.has_value());
  // Reference: sigma = F / A = 10 kN / 400 mm^2 = 25 MPa, exact for TET10 (tolerance 1e-6 relative).
  ASSERT_TRUE(summary->max_von_mises_pa.has_value());
  EXPECT_NEAR(*summary->max_von_mises_pa, 25e6, 25.0);
  EXPECT_EQ(summary->type, "fe_static");

  r = kinetofem(fmt::format("run {} -q -o {} --set mesh.order=3", c.string(), (dir / "out").string()), dir);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("--set mesh.order=3: key 'mesh.order' = 3 is out of range"), std::string::npos)
      << r.output;
}

TEST(Batch, OneFailureDoesNotStopTheOthersAndASecondRunSkipsTheDone) {
  const TempDir temp("three");
  const fs::path& dir = temp.path;
  const fs::path a = bar_case(dir, "a", "a"), b = bar_case(dir, "b", "b");
  const fs::path bad = bar_case(dir, "c", "c", "\n[solver]\nordering_typo = \"amd\"\n");
  const std::string args =
      fmt::format("batch {} {} {} --jobs 2 -o {}", a.string(), bad.string(), b.string(), (dir / "out").string());
  Command r = kinetofem(args, dir);
  EXPECT_NE(r.exit_code, 0) << r.output;
  auto s = statuses(dir / "out");
  EXPECT_EQ(s, (std::map<std::string, std::string>{{"a", "done"}, {"b", "done"}, {"c", "failed"}})) << r.output;
  const std::string csv = read_text(dir / "out" / "batch_summary.csv");
  EXPECT_NE(csv.find("unknown key 'solver.ordering_typo'"), std::string::npos) << csv;  // the error line
  EXPECT_NE(read_text(dir / "out" / "batch_summary.md").find("| a | done |"), std::string::npos);
  EXPECT_NE(r.output.find("case a: done in"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "a.h5.hash"));
  EXPECT_FALSE(fs::exists(dir / "out" / "c.h5.hash"));

  const auto first_write = fs::last_write_time(dir / "out" / "a.h5");
  r = kinetofem(args, dir);
  EXPECT_NE(r.exit_code, 0);
  s = statuses(dir / "out");
  EXPECT_EQ(s, (std::map<std::string, std::string>{{"a", "skipped"}, {"b", "skipped"}, {"c", "failed"}}))
      << r.output;
  EXPECT_EQ(fs::last_write_time(dir / "out" / "a.h5"), first_write);
  // The table of the skipped runs is rebuilt from their summaries on disk.
  EXPECT_NE(read_text(dir / "out" / "batch_summary.md").find("| a | skipped |"), std::string::npos);
  EXPECT_NE(read_text(dir / "out" / "batch_summary.csv").find("a,skipped,"), std::string::npos);

  // A changed override changes the hash: the runs are done again.
  r = kinetofem(args + " --set mesh.element_size_mm=20", dir);
  s = statuses(dir / "out");
  EXPECT_EQ(s["a"], "done");
  EXPECT_EQ(s["b"], "done");
}

TEST(Batch, KilledHalfWayThenResumedRunsEveryCaseExactlyOnce) {
  const TempDir temp("killed");
  const fs::path& dir = temp.path;
  const fs::path out = dir / "out";
  std::vector<std::string> names = {"k1", "k2", "k3", "k4"};
  std::string cases;
  for (const auto& n : names) cases += fmt::format(" {}", bar_case(dir, n, n).string());

  // The batch in a process group of its own, so that kill -9 reaches it and its runs.
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    ::setpgid(0, 0);
    const std::string command =
        fmt::format("exec {} batch{} --jobs 1 -o {} > {} 2>&1", KINETOFEM_EXE, cases, out.string(),
                    (dir / "first.txt").string());
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  std::vector<std::string> done_before;
  while (done_before.empty() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    for (const auto& n : names)
      if (fs::exists(out / (n + ".h5.hash"))) done_before.push_back(n);
  }
  ::kill(-pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_FALSE(done_before.empty()) << "no run finished within 60 s";
  ASSERT_LT(done_before.size(), names.size()) << "the batch finished before it could be killed";
  std::map<std::string, fs::file_time_type> written;
  for (const auto& n : done_before) written[n] = fs::last_write_time(out / (n + ".h5"));

  const Command r = kinetofem("batch" + cases + " --jobs 1 -o " + out.string(), dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = statuses(out);
  ASSERT_EQ(s.size(), names.size());
  for (const auto& n : names) {
    const bool before = written.count(n) > 0;
    EXPECT_EQ(s.at(n), before ? "skipped" : "done") << n << "\n" << r.output;
    EXPECT_TRUE(fs::exists(out / (n + ".h5"))) << n;
    if (before) {
      EXPECT_EQ(fs::last_write_time(out / (n + ".h5")), written[n]) << n << " was run again";
    }
  }
}

TEST(Batch, SweepOfFourValuesGivesFourRuns) {
  const TempDir temp("sweep");
  const fs::path& dir = temp.path;
  const fs::path c = bar_case(dir, "bar", "bar",
                              "\n[sweep]\nparameters = [\"material.youngs_modulus_mpa\"]\n"
                              "values = [[100000, 200000, 300000, 400000]]\n");
  // The [sweep] table does not disturb a plain run of the case.
  Command r = kinetofem(fmt::format("run {} -q -o {}", c.string(), (dir / "plain").string()), dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;

  r = kinetofem(fmt::format("batch {} --jobs 2 -o {}", c.string(), (dir / "out").string()), dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = statuses(dir / "out");
  ASSERT_EQ(s.size(), 4u) << r.output;
  std::map<double, double> displacement;  // E [MPa] -> max |u| [m]
  for (double e : {100000.0, 200000.0, 300000.0, 400000.0}) {
    const std::string name = fmt::format("bar__youngs_modulus_mpa={}", e);
    EXPECT_EQ(s.at(name), "done");
    const auto summary = read_run_summary(dir / "out" / (name + ".summary.toml"));
    ASSERT_TRUE(summary) << name;
    ASSERT_TRUE(summary->max_displacement_m.has_value()) << name;
    displacement[e] = *summary->max_displacement_m;
  }
  // Linear elasticity on the same mesh: u is proportional to 1/E (reference:
  // u = F L / (E A)); only round-off differs, tolerance 1e-9 relative.
  for (const auto& [e, u] : displacement)
    EXPECT_NEAR(u * e, displacement[100000.0] * 100000.0, 1e-9 * u * e) << e;
}

TEST(Batch, SweepPlanIsTheCartesianProductOfValuesAndLinspace) {
  const TempDir temp("plan");
  const fs::path& dir = temp.path;
  const fs::path c = bar_case(dir, "bar", "bar",
                              "\n[sweep]\nparameters = [\"mesh.order\", \"material.youngs_modulus_mpa\"]\n"
                              "values = [[1, 2], []]\nlinspace = [[], [1e5, 2e5, 3]]\n");
  const auto runs = plan_batch({c}, {"mesh.element_size_mm=20"});
  ASSERT_EQ(runs.size(), 6u);
  EXPECT_EQ(runs[0].name, "bar__order=1__youngs_modulus_mpa=100000");
  EXPECT_EQ(runs[1].name, "bar__order=1__youngs_modulus_mpa=150000");
  EXPECT_EQ(runs[5].name, "bar__order=2__youngs_modulus_mpa=200000");
  EXPECT_EQ(runs[1].overrides,
            (std::vector<std::string>{"mesh.element_size_mm=20", "mesh.order=1",
                                      "material.youngs_modulus_mpa=150000.0",
                                      "case.name=\"bar__order=1__youngs_modulus_mpa=150000\""}));
  for (const auto& run : runs) EXPECT_TRUE(run.plan_error.empty()) << run.plan_error;
  EXPECT_NE(runs[0].hash, runs[1].hash);
  // The hash follows the referenced geometry file.
  const std::string before = plan_batch({c}, {})[0].hash;
  std::ofstream(dir / "bar" / "bar.geo", std::ios::app) << "// changed\n";
  EXPECT_NE(plan_batch({c}, {})[0].hash, before);
}

// Each parameter's count is capped, and so is their product: three of 100 000
// values would be 1e15 runs, refused with the count before any run is planned.
TEST(Batch, SweepBeyondTheMaximumIsRefusedWithItsCount) {
  const TempDir temp("huge_sweep");
  const fs::path c = bar_case(temp.path, "bar", "bar",
                              "\n[sweep]\nparameters = [\"material.youngs_modulus_mpa\", "
                              "\"material.poisson_ratio\", \"material.density_kg_m3\"]\n"
                              "linspace = [[1e5, 2e5, 100000], [0.2, 0.3, 100000], [7000, 8000, 100000]]\n");
  try {
    plan_batch({c}, {});
    ADD_FAILURE() << "a sweep of 1e15 runs was planned";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "[sweep] gives 100000 x 100000 x 100000 = 1e+15 runs, more than the 100000 a batch may plan"),
              std::string::npos)
        << e.what();
  }
  // The limit counts the runs of every case of the batch together.
  const fs::path c2 = bar_case(temp.path, "bar2", "bar2");
  const fs::path c3 = bar_case(temp.path, "bar3", "bar3",
                               "\n[sweep]\nparameters = [\"material.youngs_modulus_mpa\"]\n"
                               "linspace = [[1e5, 2e5, 100000]]\n");
  try {
    plan_batch({c2, c3}, {});
    ADD_FAILURE() << "100 001 runs were planned";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("[sweep] gives 100000 runs after the 1 run(s) of the cases before it, more "
                                         "than the 100000 a batch may plan"),
              std::string::npos)
        << e.what();
  }
  const Command r = kinetofem(fmt::format("batch {} -o {}", c.string(), (temp.path / "out").string()), temp.path);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("kinetofem: error: "), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1e+15 runs"), std::string::npos) << r.output;
}

// A case name is a file name: "../../x" would put the run's .log and .h5.hash
// (and its results) two folders above the output folder.
TEST(Batch, CaseNameThatLeavesTheOutputFolderFailsThatRunOnly) {
  const TempDir temp("escape");
  const fs::path& dir = temp.path;
  const fs::path bad = bar_case(dir, "bad", "../../x");
  const fs::path good = bar_case(dir, "good", "good");
  const fs::path out = dir / "a" / "b" / "out";
  const Command r = kinetofem(fmt::format("batch {} {} -q -o {}", bad.string(), good.string(), out.string()), dir);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  const auto s = statuses(out);
  EXPECT_EQ(s.at("good"), "done") << r.output;
  const std::string csv = read_text(out / "batch_summary.csv");
  // (CSV doubles the quotes.)
  EXPECT_NE(csv.find("key 'case.name' = \"\"../../x\"\" cannot be a file name in the output folder"), std::string::npos)
      << csv;
  for (const fs::path& p : {dir / "a" / "x.log", dir / "a" / "x.h5.hash", dir / "a" / "x.h5", dir / "x.log"})
    EXPECT_FALSE(fs::exists(p)) << p << " was written outside the output folder";
  // A sweep's run names are checked too (here: too long once the point is added).
  const fs::path long_name = bar_case(dir, "long", std::string(110, 'n'),
                                      "\n[sweep]\nparameters = [\"material.youngs_modulus_mpa\"]\n"
                                      "values = [[100000]]\n");
  const auto runs = plan_batch({long_name}, {});
  ASSERT_EQ(runs.size(), 1u);
  EXPECT_NE(runs[0].plan_error.find("the run name made of case.name and a [sweep] point"), std::string::npos)
      << runs[0].plan_error;
}

// --jobs 0 is a clear range error (not CLI11's range of a double, 309 digits);
// more than kJobsPerThread runs per hardware thread are lowered, and it says so.
TEST(Batch, JobsOutsideTheirRangeAreClear) {
  const TempDir temp("jobs");
  const fs::path c = bar_case(temp.path, "bar", "bar");
  Command r = kinetofem(fmt::format("batch {} --jobs 0 -o {}", c.string(), (temp.path / "out").string()), temp.path);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("--jobs: must be a whole number of runs at once, 1 or more, not 0"), std::string::npos) << r.output;
  EXPECT_LT(r.output.size(), 300u) << r.output;
  r = kinetofem(fmt::format("batch {} --jobs 1000 -o {}", c.string(), (temp.path / "out").string()), temp.path);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const int threads = std::max(1, int(std::thread::hardware_concurrency()));
  EXPECT_NE(r.output.find(fmt::format("--jobs 1000 lowered to {}: at most {} runs at once per hardware thread ({} here)",
                                      kJobsPerThread * threads, kJobsPerThread, threads)),
            std::string::npos)
      << r.output;
}

// A stale temporary that is a symbolic link (left, or planted, at the name the
// writer uses) is replaced, never written through: its target is unchanged.
TEST(Batch, AtomicWriteNeverFollowsASymlinkAtItsTemporaryName) {
  const TempDir temp("symlink");
  const fs::path file = temp.path / "batch_summary.csv", target = temp.path / "precious.txt";
  std::ofstream(target) << "keep me";
  const fs::path temporary = file.string() + fmt::format(".tmp{}", static_cast<long>(::getpid()));
  fs::create_symlink(target, temporary);
  write_file_atomically(file, "case,status\n");
  EXPECT_EQ(read_text(target), "keep me");
  EXPECT_FALSE(fs::is_symlink(file));
  EXPECT_EQ(read_text(file), "case,status\n");
  EXPECT_FALSE(fs::exists(fs::symlink_status(temporary)));
}

// The trust decision reaches every run: a part .geo that calls Exit is refused
// by the scan without it, and reaches Gmsh (which the meshing process reports
// as the file ending Gmsh) with it.
TEST(Batch, TrustPartFilesIsPassedToEveryRun) {
  const TempDir temp("trust");
  const fs::path& dir = temp.path;
  fs::copy("tests/data/robustness/131_part_geo_exit", dir / "exit");
  const std::string args = fmt::format("batch {} -o {}", (dir / "exit" / "case.toml").string(), (dir / "out").string());

  Command r = kinetofem(args, dir);
  EXPECT_NE(r.exit_code, 0) << r.output;
  EXPECT_EQ(statuses(dir / "out")["r"], "failed") << r.output;
  EXPECT_NE(read_text(dir / "out" / "batch_summary.csv").find("'Exit' ends the program"), std::string::npos)
      << read_text(dir / "out" / "batch_summary.csv");

  r = kinetofem(args + " --trust-part-files", dir);
  EXPECT_NE(r.exit_code, 0) << r.output;
  const std::string csv = read_text(dir / "out" / "batch_summary.csv");
  EXPECT_EQ(csv.find("'Exit' ends the program"), std::string::npos) << csv;
  EXPECT_NE(csv.find("the file ended Gmsh"), std::string::npos) << csv;
}

TEST(Batch, MpiTwoRanksRunEveryCaseExactlyOnce) {
  if (std::system("command -v mpirun > /dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found";
  const TempDir temp("mpi");
  const fs::path& dir = temp.path;
  std::string cases;
  for (const auto& n : {"m1", "m2", "m3"}) cases += fmt::format(" {}", bar_case(dir, n, n).string());
  const Command r = kinetofem("batch" + cases + " --jobs 1 -o " + (dir / "out").string(), dir,
                              "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 "
                              "mpirun --allow-run-as-root --oversubscribe -n 2 ");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto s = statuses(dir / "out");
  EXPECT_EQ(s, (std::map<std::string, std::string>{{"m1", "done"}, {"m2", "done"}, {"m3", "done"}})) << r.output;
  // Each run reported once, by the rank index % 2 gives it.
  for (const auto& [n, rank] : std::map<std::string, int>{{"m1", 0}, {"m2", 1}, {"m3", 0}}) {
    const std::string line = fmt::format("case {}: done in", n);
    const auto first = r.output.find(line);
    ASSERT_NE(first, std::string::npos) << r.output;
    EXPECT_EQ(r.output.find(line, first + 1), std::string::npos) << n << " ran twice\n" << r.output;
    const std::string reported = r.output.substr(first, r.output.find('\n', first) - first);
    EXPECT_NE(reported.find(fmt::format("(rank {})", rank)), std::string::npos) << reported;
  }
}

}  // namespace
}  // namespace kinetofem::app
