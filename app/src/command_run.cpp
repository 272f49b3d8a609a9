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
  run->callback([options, &context] {
    options->command_line = context.command_line;
    context.exit_code = run_case(*options);
  });
}

}  // namespace kinetofem::app
