#include <cstdio>
#include <memory>

#include <CLI/CLI.hpp>

#include "kinetofem/app/case_types.hpp"
#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

void add_case_command(CLI::App& app, CommandContext& context) {
  auto type = std::make_shared<std::string>();
  auto* command = app.add_subcommand("case", "Case files: print a commented template of a case type");
  command->add_option("--template", *type, "Case type whose template to print")->required();
  command->callback([type, &context] {
    std::fputs(case_template(*type).c_str(), stdout);
    context.exit_code = 0;
  });
}

}  // namespace kinetofem::app
