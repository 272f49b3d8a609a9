#pragma once
// A `linkage` case file run quietly as the program runs it (the case file,
// then the --set overrides), its results in a fresh folder of the temp
// directory; the test removes the folder (output_dir) when done.
#include <filesystem>
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/linkage_job.hpp"

namespace kinetofem::testing {

struct QuietLinkageRun {
  std::filesystem::path output_dir;
  app::LinkageRun run;
};

inline QuietLinkageRun run_linkage_quietly(const std::filesystem::path& case_path, const std::string& folder,
                                           const std::vector<std::string>& overrides = {}) {
  app::RunOptions options;
  options.output_dir = std::filesystem::temp_directory_path() / folder;
  std::filesystem::remove_all(options.output_dir);
  options.quiet = true;
  options.case_path = case_path;
  const app::CaseFile c = app::CaseFile::load(case_path, app::linkage_schema(), false, overrides);
  return {options.output_dir, app::run_linkage(c, options)};
}

}  // namespace kinetofem::testing
