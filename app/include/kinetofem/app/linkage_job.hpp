#pragma once
// The "linkage" case type: any planar linkage of rigid bodies, written out in
// TOML, mapped one to one onto mech::MultibodyModel (mechanisms/.../multibody/
// model.hpp) and run with SUNDIALS IDAS (any number of DoF), CVODES (1 DoF,
// minimal coordinate) or as a prescribed motion (kinematic, DoF 0).
//
// Case-file tables (every key, unit and default: linkage_schema() and
// docs/cases.md): [[body]], [[point]], [[point_mass]], [[joint]] (revolute,
// prismatic, fixed, chain), [[spring]], [[point_force]], [[motion_drive]]
// (laws polynomial345, cycloidal, trapezoidal, constant_velocity, csv),
// [[transmission]] (belts, chains, gear trains between two joint angles),
// [[force_drive]] (constant, dc_motor, pd_servo), [gravity], [simulation].
// Lengths in the file are mm, angles deg; inside SI (m, rad).
//
// FE parts ([[part]], [[face_set]] and the face keys of the tables that act
// on a part; app/part_keys.hpp): every moving body may carry a parametric link
// or a CAD part; the run then computes its stress over the motion through the
// motion-to-stress pipeline (driver/motion_to_stress.hpp), the same as the
// manipulator cases.
//
// Output: results/<name>.h5 (+ .xdmf) with the histories of every body, joint,
// drive and chain under /mechanism (names in docs/results.md), each part's
// fields over the motion, and a summary: extremes of drive efforts, reactions
// and chain tension, the parts' peak stresses, and the run's checks
// (mech::Results::format_checks()).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"
#include "kinetofem/pipeline/vibration_over_motion.hpp"

namespace kinetofem::app {

const std::vector<KeySpec>& linkage_schema();

// The model a linkage case describes, checked name by name: an unknown body,
// point, joint or law, a missing csv file or a key that does not fit the
// coordinate (stroke_mm on an angle drive) is an Error naming file, line, key
// and value. The system's own checks (system.hpp) run when it is compiled.
mech::MultibodyModel read_linkage_model(const CaseFile& case_file);

struct LinkageRun {
  mech::MultibodyModel model;
  mech::Results results;
  std::filesystem::path results_file;
  double min_chain_tension_n = 0.0, max_chain_tension_n = 0.0;  // 0 when the model has no chain
  double max_abs_drive_effort = 0.0;                           // over all drives (N m or N)
  std::vector<pipeline::PartSummary> parts;                    // one per [[part]]: stress over the motion
  std::optional<pipeline::AssemblySummary> assembly;          // assembly.enabled
  std::optional<pipeline::VibrationSummary> vibration;  // vibration.enabled
  std::vector<pipeline::PartFatigue> fatigue;                  // fatigue.enabled: one per [[part]]
};

LinkageRun run_linkage(const CaseFile& case_file, const RunOptions& options);

}  // namespace kinetofem::app
