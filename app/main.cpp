// kinetofem — command-line entry point. Registers the subcommands (one file
// each, app/src/command_*.cpp), parses the arguments, and is the one place
// that catches errors: it prints the one-line message and exits non-zero.
#include <csignal>
#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/core/termination_cleanup.hpp"
#include "kinetofem/core/version.hpp"
#include "kinetofem/postproc/provenance.hpp"

int main(int argc, char** argv) {
  // Ctrl-C, SIGTERM or SIGHUP remove the registered temporary files and stop
  // the registered child processes before the program dies of the signal.
  kinetofem::core::install_termination_cleanup();
  // A file-size limit (a full disk, simulated or real) must end in a clear
  // error from the writer, not in a kill by SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  // Memory freed during a run (a part's factor) goes back to the system.
  kinetofem::return_freed_memory_to_the_system();
  CLI::App app{"kinetofem: kinematic, kinetostatic and finite-element analysis of robot "
               "manipulator mechanisms"};
  app.set_version_flag("--version", std::string("kinetofem ") + kinetofem::kVersion + " (" +
                                        kinetofem::kGitCommit + ")");
  app.require_subcommand(1);
  kinetofem::app::CommandContext context;
  context.command_line = kinetofem::post::command_line_of(argc, argv);
  kinetofem::app::add_run_command(app, context);
  kinetofem::app::add_case_command(app, context);
  kinetofem::app::add_post_command(app, context);
  kinetofem::app::add_batch_command(app, context);
  kinetofem::app::add_verify_command(app, context);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    return app.exit(error);
  } catch (const kinetofem::Error& error) {
    std::fprintf(stderr, "kinetofem: error: %s\n", error.what());
    return 1;
  } catch (const std::bad_alloc&) {
    // A stage that knows its part names it (driver/motion_to_stress.cpp); this is the rest.
    const kinetofem::MemoryBudget left = kinetofem::memory_available_to_process();
    std::fprintf(stderr,
                 "kinetofem: error: out of memory: an allocation was refused (%.3g GB left by %s): coarsen the "
                 "mesh, give fewer output times or raise the limit\n",
                 left.bytes * 1e-9, left.limited_by.c_str());
    return 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "kinetofem: internal error: %s\n", error.what());
    return 2;
  }
  return context.exit_code;
}
