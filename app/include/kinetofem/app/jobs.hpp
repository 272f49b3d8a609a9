#pragma once
// Jobs of the command-line program: each takes its options, runs, prints a
// summary and returns the process exit code. Errors are thrown as
// kinetofem::Error and caught once in main().
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "kinetofem/core/log.hpp"

namespace kinetofem::app {

struct RunOptions {
  std::filesystem::path case_path;
  std::filesystem::path output_dir = "results";
  bool quiet = false;
  bool verbose = false;  // -v: also each solve's statistics (Log::detail lines)
  std::string command_line;  // recorded in the results' provenance
  std::vector<std::string> overrides;  // --set KEY=VALUE, applied after the case file is read
  // --trust-part-files: the person running kinetofem trusts the case's .geo
  // part and geometry files to run programs, exit, write files and read
  // outside the case folder (meshes/geo_file_scan.hpp, docs/robustness.md).
  bool trust_part_files = false;
};

// The console of a job: silent but for its summary under --quiet, each
// solve's statistics too under --verbose (--quiet wins).
inline Log job_log(const RunOptions& options) {
  return Log(options.quiet ? Log::Level::Quiet : options.verbose ? Log::Level::Verbose : Log::Level::Normal);
}

// Key results of a finished run, written by each job as
// OUTPUT_DIR/<name>.summary.toml (atomically: temporary file + rename) and
// read back by the batch. SI inside; the file holds MPa and mm.
struct RunSummary {
  std::string name;  // case name: OUTPUT_DIR/<name>.h5
  std::string type;  // case type ("fe_static", "manipulator")
  std::filesystem::path results_file;
  double wall_time_s = 0.0;
  // Over the FE parts; empty for a case without parts (a mechanism only).
  std::optional<double> max_von_mises_pa;
  std::optional<double> max_displacement_m;
  // Further key results, the unit in the key's name ("max_drive_torque_nm").
  std::vector<std::pair<std::string, double>> extra;
};

std::filesystem::path run_summary_path(const std::filesystem::path& output_dir,
                                       const std::string& name);
void write_run_summary(const std::filesystem::path& output_dir, const RunSummary& summary);
// nullopt if the file is absent or unreadable (a run that did not finish).
std::optional<RunSummary> read_run_summary(const std::filesystem::path& file);

// Reads the case file and runs the analysis it describes.
int run_case(const RunOptions& options);

}  // namespace kinetofem::app
