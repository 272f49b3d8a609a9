#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/fe_static_job.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

namespace {

// The case's [case] type, read before the case is checked against the
// schema of that type. Syntax errors are reported by CaseFile::load.
std::string case_type(const std::filesystem::path& path) {
  const CaseFile any = CaseFile::load(path, {{.path = "case.type", .type = KeySpec::Type::String,
                                              .required = true}}, /*allow_unknown=*/true);
  return any.text_value("case.type");
}

}  // namespace

int run_case(const RunOptions& options) {
  const std::string type = case_type(options.case_path);
  if (type == "fe_static") {
    const CaseFile c = CaseFile::load(options.case_path, fe_static_schema());
    run_fe_static(c, options);
    return 0;
  }
  fail("{}: case.type = \"{}\" is not a known case type (known: \"fe_static\")",
       options.case_path.string(), type);
}

}  // namespace kinetofem::app
