#pragma once
// Jobs of the command-line program: each takes its options, runs, prints a
// summary and returns the process exit code. Errors are thrown as
// kinetofem::Error and caught once in main().
#include <filesystem>
#include <string>

namespace kinetofem::app {

struct RunOptions {
  std::filesystem::path case_path;
  std::filesystem::path output_dir = "results";
  bool quiet = false;
  std::string command_line;  // recorded in the results' provenance
};

// Reads the case file and runs the analysis it describes.
int run_case(const RunOptions& options);

}  // namespace kinetofem::app
