#pragma once
// Case-file keys of the fatigue check (pipeline/part_fatigue.hpp),
// declared once for the manipulator and linkage case types, and their reader.
// Every key, unit and default: docs/cases.md; the method: docs/fatigue.md.
//
//   [fatigue]          enabled, stress_measure, detail_category_mpa,
//                      mean_stress, gamma_ff, gamma_mf, cycles_per_hour,
//                      service_life_h | cycles
//   [[fatigue.detail]] part, set, category_mpa, mean_stress
//
// Defaults, each with its reason (docs/fatigue.md):
//   detail category 71 MPa  a welded detail (EN 1993-1-9 table 8.4, an
//                           attachment 50 < L <= 80 mm): a fabricated
//                           steel link is welded unless the case says not
//   gamma_Ff = 1.0          EN 1993-1-9 3(7)
//   gamma_Mf = 1.35         EN 1993-1-9 table 3.1, safe life, high consequence
//   60 cycles/h             one extraction a minute (die casting: 30-120 per h)
//   80 000 h                20 years of two shifts (4000 h a year)
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"

namespace kinetofem::app {

void add_fatigue_keys(std::vector<KeySpec>& schema);

// Empty when fatigue.enabled is false. Throws Error naming file, key and
// value for: a detail category not of EN 1993-1-9 (the message lists them),
// both service_life_h and cycles, a service life shorter than one work cycle,
// fatigue.detail on a body without a part, fatigue keys in a file
// without fatigue.enabled (with `enabled = false` written they are unused). (Rates <= 0 and partial factors below 1 are range errors
// of the schema.) The sets of fatigue.detail are checked against the meshes
// by the driver (pipeline::check_fatigue_details).
std::optional<pipeline::FatigueSettings> read_fatigue(const CaseFile& case_file,
                                                      const std::vector<std::string>& bodies_with_parts);

// After the run: prints the fatigue table (pipeline::format_fatigue_table)
// and writes the critical nodes' counted ranges to <results stem>.fatigue.csv
// beside the results file; nothing without results. Returns the CSV's path
// (empty: none written).
std::filesystem::path report_fatigue(const std::vector<pipeline::PartFatigue>& fatigue,
                                     const std::filesystem::path& results_file);

}  // namespace kinetofem::app
