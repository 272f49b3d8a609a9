#include "kinetofem/app/jobs.hpp"

#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

int run_case(const RunOptions& options) {
  fail("{}: running cases is not implemented yet", options.case_path.string());
}

}  // namespace kinetofem::app
