#pragma once
// The "manipulator" case type: the whole chain for the lever-chain (SPEC §1)
// or lever (SPEC §2) manipulator — link meshes, multibody model with the
// meshes' mass properties, motion of lever 1 integrated with SUNDIALS IDAS,
// kinetostatic loads on every link at every output time, one factorization
// per link and block solves over the motion, stress envelope, a static pose
// study (gravity and payload), the comparison with the published values of
// SPEC §3, and one HDF5 + XDMF results file. The case is a preset of the
// general motion-to-stress pipeline (pipeline/manipulator_preset.hpp): this
// job reads the keys and calls the pipeline's driver.
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/pipeline/part_factorization.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"
#include "kinetofem/pipeline/vibration_over_motion.hpp"

namespace kinetofem::app {

const std::vector<KeySpec>& manipulator_schema();

// What a run reports of each link (one per part of the preset).
using LinkSummary = pipeline::PartSummary;

struct ManipulatorSummary {
  std::string mechanism;  // "lever_chain" or "lever"
  std::vector<LinkSummary> links;
  double max_von_mises_pa = 0, max_displacement_m = 0;              // over links and motion
  double static_max_von_mises_pa = 0, static_max_displacement_m = 0;  // static pose study
  double max_drive_torque_nm = 0, min_chain_tension_n = 0, max_chain_tension_n = 0;
  // The elastic assembly (assembly.enabled): total deformation, H's deflection.
  std::optional<pipeline::AssemblySummary> assembly;
  std::optional<pipeline::VibrationSummary> vibration;  // vibration.enabled
  pipeline::PartFactorizationReport factorization;       // side by side or one after the other
  std::vector<pipeline::PartFatigue> fatigue;  // fatigue.enabled: one per link
  std::filesystem::path results_file;
  double meshing_seconds = 0, dynamics_seconds = 0, total_seconds = 0;
};

ManipulatorSummary run_manipulator(const CaseFile& case_file, const RunOptions& options);

}  // namespace kinetofem::app
