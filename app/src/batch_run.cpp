// Running a batch: each run a child process `kinetofem run`, up to `jobs` at
// once; skipping up-to-date runs; gathering the rows and writing the table.
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include <fmt/format.h>

#include "kinetofem/app/batch.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/termination_cleanup.hpp"
#include "kinetofem/core/units.hpp"

extern char** environ;

namespace kinetofem::app {

namespace {

namespace fs = std::filesystem;

fs::path self_executable() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) fail("/proc/self/exe: cannot find the kinetofem executable to start the runs: {}", ec.message());
  return exe;
}

fs::path hash_path(const fs::path& dir, const std::string& name) { return dir / (name + ".h5.hash"); }
fs::path log_path(const fs::path& dir, const std::string& name) { return dir / (name + ".log"); }

std::string first_line_of(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// A matching hash (written only after the run succeeded, removed before it
// starts again) and the results its summary names: the run is done already.
// A case type that writes no summary is judged by the hash alone.
bool up_to_date(const BatchRun& run, const fs::path& dir) {
  if (first_line_of(hash_path(dir, run.name)) != run.hash) return false;
  const auto summary = read_run_summary(run_summary_path(dir, run.name));
  std::error_code ec;
  return !summary || fs::is_regular_file(summary->results_file, ec);
}

// The child's error message (main() prints "kinetofem: error: ..."), or what
// the exit status says.
std::string error_line(const fs::path& log, int wait_status) {
  std::ifstream in(log);
  std::string line, error, last;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    last = line;
    const auto at = line.find("error: ");
    if (line.rfind("kinetofem: ", 0) == 0 && at != std::string::npos) error = line.substr(at + 7);
  }
  if (!error.empty()) return error;
  if (WIFSIGNALED(wait_status))
    return fmt::format("killed by signal {} ({})", WTERMSIG(wait_status), strsignal(WTERMSIG(wait_status)));
  if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) != 0)
    return fmt::format("exit code {}{}", WEXITSTATUS(wait_status), last.empty() ? "" : "; last line: " + last);
  return last;
}

std::string one_line(std::string text) {
  for (char& ch : text)
    if (ch == '\n' || ch == '\t' || ch == '\r') ch = ' ';
  return text;
}

// Threads for each child's OpenMP / BLAS, when the user has not set them:
// the cores shared among the runs of every rank on this node.
int child_threads(int jobs) {
  int ranks_here = 1;
  if (const char* local = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE")) ranks_here = std::max(1, std::atoi(local));
  const int cores = std::max(1, int(std::thread::hardware_concurrency()));
  return std::max(1, cores / std::max(1, jobs * ranks_here));
}

// Starts `kinetofem run` for one run, its output into DIR/<name>.log.
pid_t spawn_run(const fs::path& exe, const BatchRun& run, const fs::path& dir, int threads, bool trust_part_files,
                bool verbose) {
  std::vector<std::string> args = {exe.string(), "run", run.case_path.string(), "-o", dir.string()};
  if (trust_part_files) args.push_back("--trust-part-files");
  if (verbose) args.push_back("--verbose");
  for (const auto& o : run.overrides) {
    args.push_back("--set");
    args.push_back(o);
  }
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  std::vector<std::string> env;
  for (char** e = environ; *e; ++e) env.emplace_back(*e);
  for (const char* name : {"OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"})
    if (!std::getenv(name)) env.push_back(fmt::format("{}={}", name, threads));
  std::vector<char*> envp;
  for (auto& e : env) envp.push_back(e.data());
  envp.push_back(nullptr);

  const std::string log = log_path(dir, run.name).string();
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, STDIN_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &actions, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) fail("{}: cannot start {}: {}", run.name, exe.string(), std::strerror(rc));
  return pid;
}

struct Outcome {
  RunStatus status = RunStatus::Failed;
  double wall_time_s = 0.0;
  std::string error;
};

// Rows cross ranks as text: "index<TAB>status<TAB>wall<TAB>error" per line.
std::string encode(const std::map<std::size_t, Outcome>& outcomes) {
  std::string out;
  for (const auto& [index, o] : outcomes)
    out += fmt::format("{}\t{}\t{}\t{}\n", index, int(o.status), o.wall_time_s, one_line(o.error));
  return out;
}

void decode(const std::string& text, std::map<std::size_t, Outcome>& outcomes) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string index, status, wall, error;
    std::getline(fields, index, '\t');
    std::getline(fields, status, '\t');
    std::getline(fields, wall, '\t');
    std::getline(fields, error);
    outcomes[std::stoul(index)] = {RunStatus(std::stoi(status)), std::stod(wall), error};
  }
}

// A batch under way on this rank: its plan, where it writes, and the outcome
// of each of this rank's runs so far.
struct Batch {
  const BatchOptions& options;
  const BatchComm& comm;
  std::vector<BatchRun> plan;
  fs::path dir;
  fs::path exe;
  int jobs = 1;     // runs at once on this rank
  int threads = 1;  // OpenMP / BLAS threads of each run
  std::vector<std::size_t> mine;  // this rank's runs: indices into plan
  std::string rank_tag;           // " (rank r)" when there are several
  std::map<std::size_t, Outcome> outcomes;
  std::size_t finished = 0;

  // One progress line for a finished (or skipped) run.
  void report(std::size_t index) {
    ++finished;
    if (options.quiet) return;
    const Outcome& o = outcomes[index];
    const std::string& name = plan[index].name;
    if (o.status == RunStatus::Skipped)
      std::printf("[%zu/%zu] case %s: skipped (up to date)%s\n", finished, mine.size(), name.c_str(),
                  rank_tag.c_str());
    else if (o.status == RunStatus::Done)
      std::printf("[%zu/%zu] case %s: done in %.1f s%s\n", finished, mine.size(), name.c_str(), o.wall_time_s,
                  rank_tag.c_str());
    else
      std::printf("[%zu/%zu] case %s: failed in %.1f s%s: %s (log: %s)\n", finished, mine.size(), name.c_str(),
                  o.wall_time_s, rank_tag.c_str(), o.error.c_str(), log_path(dir, name).string().c_str());
    std::fflush(stdout);
  }
  void settle(std::size_t index, Outcome outcome) {
    outcomes[index] = std::move(outcome);
    report(index);
  }
};

// --jobs, at most kJobsPerThread runs per hardware thread.
int allowed_jobs(const BatchOptions& options, const BatchComm& comm) {
  require(options.jobs >= 1, "--jobs {}: must be a whole number of runs at once, 1 or more", options.jobs);
  const int hardware_threads = std::max(1, int(std::thread::hardware_concurrency()));
  const int jobs = std::min(options.jobs, kJobsPerThread * hardware_threads);
  if (jobs < options.jobs && !options.quiet && comm.rank() == 0)
    std::printf("kinetofem batch: --jobs %d lowered to %d: at most %d runs at once per hardware thread (%d here)\n",
                options.jobs, jobs, kJobsPerThread, hardware_threads);
  return jobs;
}

// The plan, the output directory and this rank's share of the runs (round robin).
void plan_runs(Batch& b) {
  b.plan = plan_batch(b.options.cases, b.options.overrides);
  std::error_code ec;
  fs::create_directories(b.dir, ec);
  if (ec) fail("{}: cannot create the output directory: {}", b.dir.string(), ec.message());
  b.exe = b.options.executable.empty() ? self_executable() : b.options.executable;
  b.threads = child_threads(b.jobs);
  for (std::size_t i = 0; i < b.plan.size(); ++i)
    if (int(i % std::size_t(b.comm.size())) == b.comm.rank()) b.mine.push_back(i);
  b.rank_tag = b.comm.size() > 1 ? fmt::format(" (rank {})", b.comm.rank()) : "";
  if (!b.options.quiet && b.comm.rank() == 0)
    std::printf("kinetofem batch: %zu runs from %zu case files, %d at once%s, results in %s\n", b.plan.size(),
                b.options.cases.size(), b.jobs,
                b.comm.size() > 1 ? fmt::format(" on each of {} ranks", b.comm.size()).c_str() : "",
                b.dir.string().c_str());
  std::fflush(stdout);
}

// Settles the runs that need no child (a plan error, up to date); returns the others.
std::vector<std::size_t> runs_to_start(Batch& b) {
  std::vector<std::size_t> pending;
  for (std::size_t index : b.mine) {
    const BatchRun& run = b.plan[index];
    if (!run.plan_error.empty()) b.settle(index, {RunStatus::Failed, 0.0, run.plan_error});
    else if (!b.options.force && up_to_date(run, b.dir)) b.settle(index, {RunStatus::Skipped, 0.0, ""});
    else pending.push_back(index);
  }
  return pending;
}

// A finished child's outcome: done (and its hash written) or failed with its error line.
Outcome outcome_of(const Batch& b, const BatchRun& run, int wait_status, double wall_time_s) {
  Outcome o;
  o.wall_time_s = wall_time_s;
  if (WIFEXITED(wait_status) && WEXITSTATUS(wait_status) == 0) {
    try {
      write_file_atomically(hash_path(b.dir, run.name), run.hash + "\n");
      o.status = RunStatus::Done;
    } catch (const Error& e) {
      o.error = e.what();
    }
  } else {
    o.error = error_line(log_path(b.dir, run.name), wait_status);
  }
  return o;
}

// Runs the pending runs as children, at most b.jobs at once, until all have ended.
void run_children(Batch& b, const std::vector<std::size_t>& pending) {
  struct Running {
    std::size_t index;
    Stopwatch clock;
    // SIGTERM, SIGINT or SIGHUP to the batch reach its runs (which then remove
    // their temporaries) and are waited for: no run outlives the batch to hold
    // the lock on a results file that a resumed batch writes again.
    core::KillOnTermination stop_on_signal;
  };
  std::map<pid_t, Running> running;
  std::size_t next = 0;
  while (next < pending.size() || !running.empty()) {
    while (next < pending.size() && int(running.size()) < b.jobs) {
      const std::size_t index = pending[next++];
      const BatchRun& run = b.plan[index];
      // A stale hash or summary must not make a failed rerun look done.
      std::error_code ec;
      fs::remove(hash_path(b.dir, run.name), ec);
      fs::remove(run_summary_path(b.dir, run.name), ec);
      try {
        const pid_t pid = spawn_run(b.exe, run, b.dir, b.threads, b.options.trust_part_files, b.options.verbose);
        running.emplace(pid, Running{index, Stopwatch(), core::KillOnTermination(pid)});
      } catch (const Error& e) {
        b.settle(index, {RunStatus::Failed, 0.0, e.what()});
      }
    }
    if (running.empty()) continue;
    int wait_status = 0;
    const pid_t pid = ::waitpid(-1, &wait_status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      fail("waitpid: {}", std::strerror(errno));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;  // not one of the runs
    const std::size_t index = it->second.index;
    const double wall_time_s = it->second.clock.seconds();
    running.erase(it);
    b.settle(index, outcome_of(b, b.plan[index], wait_status, wall_time_s));
  }
}

// A run's row of the table: its outcome and the key results its summary file holds.
BatchRow row_of(const Batch& b, std::size_t index, const Outcome& o) {
  BatchRow row;
  row.name = b.plan[index].name;
  row.status = o.status;
  row.wall_time_s = o.wall_time_s;
  row.error = o.error;
  if (o.status != RunStatus::Failed)
    if (const auto s = read_run_summary(run_summary_path(b.dir, row.name))) {
      if (s->max_von_mises_pa && std::isfinite(*s->max_von_mises_pa)) row.max_von_mises_pa = s->max_von_mises_pa;
      if (s->max_displacement_m && std::isfinite(*s->max_displacement_m)) row.max_displacement_m = s->max_displacement_m;
      for (const auto& [key, value] : s->extra)
        if (key == "fatigue_min_life_h") row.min_fatigue_life_s = value * units::kHour;
      row.results_file = s->results_file.string();
      if (o.status == RunStatus::Skipped) row.wall_time_s = s->wall_time_s;
    }
  return row;
}

// Every rank's outcomes on rank 0, the rows built from what is on disk.
std::vector<BatchRow> gather_rows(Batch& b) {
  const std::vector<std::string> gathered = b.comm.gather(encode(b.outcomes));
  if (b.comm.rank() == 0)
    for (std::size_t r = 1; r < gathered.size(); ++r) decode(gathered[r], b.outcomes);
  std::vector<BatchRow> rows;
  for (const auto& [index, o] : b.outcomes) rows.push_back(row_of(b, index, o));
  return rows;
}

// batch_summary.csv and .md, and the table with the counts on the console.
void write_table(const Batch& b, const std::vector<BatchRow>& rows) {
  write_file_atomically(b.dir / "batch_summary.csv", summary_csv(rows));
  write_file_atomically(b.dir / "batch_summary.md", summary_markdown(rows));
  std::size_t count[3] = {0, 0, 0};
  for (const auto& row : rows) ++count[int(row.status)];
  if (!b.options.quiet) {
    std::printf("\n%s\nbatch: %zu runs: %zu done, %zu skipped (up to date), %zu failed; table in %s and %s\n",
                summary_markdown(rows).c_str(), rows.size(), count[0], count[1], count[2],
                (b.dir / "batch_summary.md").string().c_str(), (b.dir / "batch_summary.csv").string().c_str());
    std::fflush(stdout);
  }
}

}  // namespace

std::vector<BatchRow> run_batch(const BatchOptions& options, const BatchComm& comm) {
  Batch b{.options = options, .comm = comm, .dir = options.output_dir};
  b.jobs = allowed_jobs(options, comm);
  plan_runs(b);
  run_children(b, runs_to_start(b));
  std::vector<BatchRow> rows = gather_rows(b);
  if (comm.rank() == 0) write_table(b, rows);
  return rows;
}

}  // namespace kinetofem::app
