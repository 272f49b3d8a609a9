#pragma once
// Case files of cases/ compiled into the program (cmake/KinetofemEmbed.cmake,
// regenerated when a file changes) for the runs the program makes by itself:
// `kinetofem verify` runs the SPEC §3 cases from these texts
// (verify_checks_published.cpp), so it needs neither the source tree nor a
// cases/ folder at run time.
#include <string_view>

namespace kinetofem::app {

// The text of cases/lever_chain_manipulator/case.toml and of
// cases/lever_manipulator/case.toml, byte for byte.
std::string_view lever_chain_manipulator_case_text();
std::string_view lever_manipulator_case_text();

}  // namespace kinetofem::app
