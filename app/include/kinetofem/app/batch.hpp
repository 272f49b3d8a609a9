#pragma once
// Batch runs: `kinetofem batch CASES... --jobs N [-o DIR] [--set KEY=VALUE]`.
//
// A batch is a list of runs: one per case file, or, for a case file with a
// [sweep] table, one per point of the sweep (the cartesian product of its
// parameters' values), named <case>__<key>=<value>... and run with the
// point's values as --set overrides:
//
//   [sweep]
//   parameters = ["payload.casting_mass_kg", "mesh.order"]
//   values     = [[], [1, 2]]              # one array of values per parameter, or
//   linspace   = [[5.0, 40.0, 20], []]     # [start, stop, count] per parameter
//
// Each run is `kinetofem run CASE -o DIR --set ...` in a child process of the
// same executable (Gmsh is not thread-safe, and a crashing run must not take
// the batch down), its output in DIR/<name>.log; up to N run at once. A run
// that exits 0 and leaves DIR/<name>.summary.toml is done; its content hash
// (case text, the files it references — geometry.file —, the overrides, the
// kinetofem version and commit; see run_hash) is then written atomically to
// DIR/<name>.h5.hash. A later batch skips a run whose results, summary and
// hash are on disk and whose hash matches, so a batch killed half-way and
// started again finishes only what is missing. One failing run does not stop
// the others; the batch exits 1 if any failed.
//
// The summary table (DIR/batch_summary.csv and .md: case, status
// done/skipped/failed, wall time, max von Mises, max displacement, results
// file, the error line of a failure) is rebuilt from the run summaries on disk.
//
// MPI: started under mpirun, rank r of N takes the runs with index % N == r
// and rank 0 gathers the rows and writes the table; the communication is
// behind BatchComm so that this library does not depend on MPI (the MPI
// implementation lives with the `batch` subcommand in the executable).
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinetofem/app/jobs.hpp"  // RunSummary

namespace kinetofem::app {

// ---- the plan ------------------------------------------------------------------

struct BatchRun {
  std::string name;  // results: DIR/<name>.h5
  std::filesystem::path case_path;
  // The batch's --set overrides, then the sweep point's, then case.name.
  std::vector<std::string> overrides;
  std::string hash;        // run_hash(), hex
  std::string plan_error;  // the case file could not be planned: the run fails with this
};

// The most runs a batch may plan: a sweep's size is the product of its
// parameters' counts, and a batch beyond this is refused before any run is
// planned (three parameters of 100 000 values would be 1e15 runs).
inline constexpr std::size_t kMaxBatchRuns = 100000;

// Reads each case (case.name, geometry.file, [sweep]) and expands sweeps into
// runs, in the order given. A case that cannot be read becomes one run with
// plan_error set. Throws Error if two runs share a name, or if the runs of
// all cases together would be more than kMaxBatchRuns (the message gives the count).
std::vector<BatchRun> plan_batch(const std::vector<std::filesystem::path>& cases,
                                 const std::vector<std::string>& overrides);

// 64-bit FNV-1a (hex) of the case text, the bytes of each referenced file, the
// overrides, the run name and the kinetofem version and commit: equal hashes
// mean the run would compute the same results (not a cryptographic hash).
std::string run_hash(const std::string& name, const std::string& case_text,
                     const std::vector<std::filesystem::path>& referenced_files,
                     const std::vector<std::string>& overrides);

// ---- running -------------------------------------------------------------------

enum class RunStatus { Done, Skipped, Failed };
const char* status_name(RunStatus status);

struct BatchRow {
  std::string name;
  RunStatus status = RunStatus::Failed;
  double wall_time_s = 0.0;  // this batch's run; for a skipped run, the run that made the results
  std::optional<double> max_von_mises_pa, max_displacement_m;
  // The shortest fatigue life over the parts (run summary key
  // fatigue_min_life_h; s, may be infinite), when the case ran the fatigue check.
  std::optional<double> min_fatigue_life_s;
  std::string results_file;
  std::string error;  // the run's error line (failed)
};

// The processes of a batch: one (serial) or the ranks of an MPI job.
class BatchComm {
 public:
  virtual ~BatchComm() = default;
  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  // Every rank passes one string; rank 0 gets them all in rank order, the
  // others an empty vector.
  virtual std::vector<std::string> gather(const std::string& mine) const { return {mine}; }
};

// Runs at once are capped at this many per hardware thread (each run is a
// process with its own mesh and factor): more only add memory and switching.
inline constexpr int kJobsPerThread = 4;

struct BatchOptions {
  std::vector<std::filesystem::path> cases;
  std::filesystem::path output_dir = "results";
  std::vector<std::string> overrides;  // applied to every run
  int jobs = 1;                        // runs at once (per MPI rank), capped by kJobsPerThread
  bool force = false;                  // rerun up-to-date runs too
  bool quiet = false;                  // no progress lines
  bool verbose = false;                // every run started with --verbose (its log gets each solve's statistics)
  bool trust_part_files = false;       // every run started with --trust-part-files (docs/robustness.md, Trust)
  std::filesystem::path executable;    // the kinetofem to start; empty: /proc/self/exe
};

// Runs the batch (this rank's share of it) and, on rank 0, writes and prints
// the summary table. Returns the rows on rank 0 (every run, in plan order),
// this rank's rows elsewhere.
std::vector<BatchRow> run_batch(const BatchOptions& options, const BatchComm& comm);

// The table from the rows and the run summaries on disk.
std::string summary_csv(const std::vector<BatchRow>& rows);
std::string summary_markdown(const std::vector<BatchRow>& rows);

// Writes `text` to `file` atomically (temporary file in the same folder, then rename).
void write_file_atomically(const std::filesystem::path& file, const std::string& text);

}  // namespace kinetofem::app
