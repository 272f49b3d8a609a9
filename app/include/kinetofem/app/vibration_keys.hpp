#pragma once
// Case-file keys of the vibration over the motion (pipeline/
// vibration_over_motion.hpp), declared once for the manipulator and
// linkage case types, and their reader. Keys, units and defaults:
// docs/cases.md; the method: docs/vibration.md.
//
//   [vibration]  enabled, modes, part_mode_cutoff_hz, cutoff_factor,
//                damping_ratio, settling_tolerance_mm
//
// Defaults, each declared once where it lives:
//   modes 6, cutoff factor 2   structure::AssemblyModesOptions (the part-mode rule)
//   damping ratio 0.02         structure::kDefaultModalDampingRatio (Newmark & Hall 1982)
//   settling tolerance 0.1 mm  structure::kDefaultSettlingToleranceM
#include <optional>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/pipeline/vibration_over_motion.hpp"

namespace kinetofem::app {

void add_vibration_keys(std::vector<KeySpec>& schema);

// Empty when vibration.enabled is false. Throws Error naming file, key and
// value for: vibration keys in a file without vibration.enabled (with
// `enabled = false` written they are unused), vibration without the
// elastic assembly (assembly.enabled = false) or with rigid-bore couplings,
// a damping ratio of 1 or more. (modes < 1, a negative ratio, a tolerance
// <= 0 are range errors of the schema.)
std::optional<pipeline::VibrationOptions> read_vibration(const CaseFile& case_file,
                                                          const std::optional<structure::AssemblyOptions>& assembly);

}  // namespace kinetofem::app
