// kinetofem — command-line entry point. Parses arguments, runs the chosen
// job, and is the one place that catches errors: it prints the one-line
// message and exits non-zero.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "kinetofem/app/jobs.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/version.hpp"
#include "kinetofem/postproc/provenance.hpp"

int main(int argc, char** argv) {
  CLI::App app{"kinetofem: kinematic, kinetostatic and finite-element analysis of robot "
               "manipulator mechanisms"};
  app.set_version_flag("--version", std::string("kinetofem ") + kinetofem::kVersion + " (" +
                                        kinetofem::kGitCommit + ")");
  app.require_subcommand(1);

  kinetofem::app::RunOptions run_options;
  auto* run = app.add_subcommand("run", "Run an analysis case (case.toml)");
  run->add_option("case", run_options.case_path, "Case file (TOML)")->required();
  run->add_option("-o,--output-dir", run_options.output_dir,
                  "Directory for results (default: results/)");
  run->add_flag("-q,--quiet", run_options.quiet, "Print only errors and the summary");

  CLI11_PARSE(app, argc, argv);
  run_options.command_line = kinetofem::post::command_line_of(argc, argv);
  try {
    if (run->parsed()) return kinetofem::app::run_case(run_options);
  } catch (const kinetofem::Error& error) {
    std::fprintf(stderr, "kinetofem: error: %s\n", error.what());
    return 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "kinetofem: internal error: %s\n", error.what());
    return 2;
  }
  return 0;
}
