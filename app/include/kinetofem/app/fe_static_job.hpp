#pragma once
// The "fe_static" case type: one linear-elastic part, meshed from a
// parametric geometry (the lever of SPEC §1) or a geometry/.msh file,
// supported on node sets and loaded by forces on face sets, gravity and
// pressure. Solves, recovers stresses, prints a summary (max von Mises, max
// displacement, equilibrium of reactions and loads) and writes HDF5 + XDMF.
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"

namespace kinetofem::app {

// Every key of an fe_static case (declared once: unit, default, range, doc).
const std::vector<KeySpec>& fe_static_schema();

struct FeStaticSummary {
  double max_von_mises_pa = 0.0;
  double max_displacement_m = 0.0;
  long node_count = 0, element_count = 0, dof_count = 0;
  double reaction_balance = 0.0;  // |sum reactions + sum loads| / |sum loads|
  std::filesystem::path results_file;
};

FeStaticSummary run_fe_static(const CaseFile& case_file, const RunOptions& options);

}  // namespace kinetofem::app
