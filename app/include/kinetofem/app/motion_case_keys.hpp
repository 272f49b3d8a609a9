#pragma once
// The half of a motion case (driver::MotionStressCase) that every motion case
// type (manipulator, linkage) reads alike, read in one place. A case type
// reads its own keys first (model, parts, output times, dynamics, static pose,
// tracked points), then calls read_shared_motion_keys with its reader of the
// [assembly] keys, which differ per type. The order of the readers is the
// order in which a case's errors are reported.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/driver/motion_to_stress.hpp"

namespace kinetofem::app {

// The bodies that carry an FE part, in the parts' order.
std::vector<std::string> bodies_with_parts(const std::vector<pipeline::PartSpec>& parts);

// The case type's [assembly] reader, given the bodies with parts; nullopt: no assembly.
using AssemblyReader =
    std::function<std::optional<structure::AssemblyOptions>(const std::vector<std::string>& bodies_with_parts)>;

// Fills, after the case type's own keys (run_case.parts and run_case.times set):
// label, the assembly (read_assembly), [vibration] on it, [fatigue] of the bodies
// with parts, [material], the part mesh, stress and field-output keys (which
// may add output times), the results file <output_dir>/<name>.h5 and the
// provenance. Error naming file, key and line for a bad value.
void read_shared_motion_keys(const CaseFile& case_file, const RunOptions& options, const std::string& name,
                             const AssemblyReader& read_assembly, driver::MotionStressCase& run_case);

// The stage summaries of a finished run that every motion case type prints
// after its own tables: the assembly, the vibration, the fatigue check.
void print_stage_summaries(const driver::MotionStressRun& run);

}  // namespace kinetofem::app
