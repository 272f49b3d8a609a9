#pragma once
// The registry of case types: each type's name, schema and job. `case.type`
// in a case file selects one.
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"

namespace kinetofem::app {

struct CaseType {
  std::string name;
  std::string summary;
  const std::vector<KeySpec>& (*schema)();
  // Runs the case and returns its key results; run_case writes them as
  // OUTPUT_DIR/<name>.summary.toml (name and wall time filled in there).
  RunSummary (*run)(const CaseFile&, const RunOptions&);
};

const std::vector<CaseType>& case_types();
const CaseType& case_type_named(const std::string& name, const std::string& context);
// A commented TOML template of a case type (kinetofem case --template TYPE).
std::string case_template(const std::string& type);

}  // namespace kinetofem::app
