#pragma once
// The printed summary of a motion-to-stress run, shared by every case type:
// the extremes of the mechanism's drive efforts, joint reactions and chain
// tensions, and the per-part table (DoFs, peak von Mises with its time,
// deformation, static study, solver). Text in the units users read (MPa, mm,
// N, N m); the values returned stay SI.
#include <string>
#include <vector>

#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/pipeline/part_stress.hpp"

namespace kinetofem::pipeline {

struct MechanismExtremes {
  double max_abs_drive_effort = 0.0;                       // over all drives (N m or N)
  double min_chain_tension_n = 0.0, max_chain_tension_n = 0.0;  // 0 without a chain
  std::string text;                                        // one line per drive, joint and chain
};
MechanismExtremes mechanism_extremes(const mech::MultibodyModel& model, const mech::Results& results);

struct PartExtremes {
  double max_von_mises_pa = 0, max_displacement_m = 0;                 // over parts and the motion
  double static_max_von_mises_pa = 0, static_max_displacement_m = 0;  // static pose study
};
PartExtremes part_extremes(const std::vector<PartSummary>& parts);

// The per-part table and one solver line per part. `several_planes`: the
// parts sit in several planes (parts_in_several_planes), so a line says that
// this stress is each part alone under the planar reactions and that the
// elastic assembly's has the moments between the planes.
std::string format_part_table(const std::vector<PartSummary>& parts, bool several_planes = false);

}  // namespace kinetofem::pipeline
