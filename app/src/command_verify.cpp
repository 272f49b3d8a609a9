#include <memory>

#include <CLI/CLI.hpp>

#include "kinetofem/app/commands.hpp"
#include "kinetofem/app/verify.hpp"

namespace kinetofem::app {

void add_verify_command(CLI::App& app, CommandContext& context) {
  auto options = std::make_shared<VerifyOptions>();
  auto* verify = app.add_subcommand(
      "verify", "Run the verification suite (SPEC numbers, analytic solutions) and write a report");
  verify->add_option("-o,--output-dir", options->output_dir,
                     "Directory for verification_report.md and .html (and the SPEC §3 runs)")
      ->capture_default_str();
  verify->add_flag("--quick", options->quick, "Leave out the SPEC §3 manipulator runs (informational rows)");
  verify->add_flag("-q,--quiet", options->quiet, "Print only the final line");
  verify->callback([options, &context] {
    options->command_line = context.command_line;
    context.exit_code = run_verify(*options);
  });
}

}  // namespace kinetofem::app
