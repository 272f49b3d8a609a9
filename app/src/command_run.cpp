#include <memory>

#include <CLI/CLI.hpp>

#include "kinetofem/app/commands.hpp"
#include "kinetofem/app/jobs.hpp"

namespace kinetofem::app {

void add_run_command(CLI::App& app, CommandContext& context) {
  auto options = std::make_shared<RunOptions>();
  auto* run = app.add_subcommand("run", "Run an analysis case (case.toml)");
  run->add_option("case", options->case_path, "Case file (TOML)")->required();
  run->add_option("-o,--output-dir", options->output_dir, "Directory for results")
      ->capture_default_str();
  run->add_flag("-q,--quiet", options->quiet, "Print only errors and the summary");
  run->add_flag("-v,--verbose", options->verbose,
                "Also print each solve's statistics (CHOLMOD solves and factorizations, orderings, sub-step times)");
  run->add_flag("--trust-part-files", options->trust_part_files,
                "Let the case's .geo part and geometry files run programs, exit, write files and read outside the "
                "case folder (a trust decision: only for files you trust; docs/robustness.md)");
  run->add_option("--set", options->overrides,
                  "Override a case key: KEY=VALUE, the value in TOML (20, \"hex\", [0, 1, 0]); repeatable")
      ->allow_extra_args(false);
  run->callback([options, &context] {
    options->command_line = context.command_line;
    context.exit_code = run_case(*options);
  });
}

}  // namespace kinetofem::app
