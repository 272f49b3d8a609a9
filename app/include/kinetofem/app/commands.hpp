#pragma once
// Subcommands of the `kinetofem` program. Each add_*_command registers one
// subcommand (its options and a callback that runs the job) on the CLI11 app;
// a job sets `exit_code` and throws kinetofem::Error on failure, which main()
// catches once. One file per subcommand: app/src/command_<name>.cpp.
#include <string>

namespace CLI {
class App;
}

namespace kinetofem::app {

struct CommandContext {
  std::string command_line;  // the whole command, for the results' provenance
  int exit_code = 0;
};

void add_run_command(CLI::App& app, CommandContext& context);   // kinetofem run CASE
void add_case_command(CLI::App& app, CommandContext& context);  // kinetofem case --template TYPE
void add_post_command(CLI::App& app, CommandContext& context);  // kinetofem post RESULT.h5
void add_batch_command(CLI::App& app, CommandContext& context);  // kinetofem batch CASES... --jobs N
void add_verify_command(CLI::App& app, CommandContext& context);  // kinetofem verify [-o DIR] [--quick]

}  // namespace kinetofem::app
