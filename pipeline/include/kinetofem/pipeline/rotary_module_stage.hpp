#pragma once
// Stage "the rotary gripper module" of a planar manipulator with FE parts:
// after the planar motion, the gripper turns the casting about the arm
// (mech::spatial::RotaryModule, seed 002's extractor), a motion out of the
// mechanism's plane that the planar core cannot carry. The mechanism as run
// (its bodies with the parts' mass properties) is lifted into the spatial core
// (spatial::from_planar), the gripper and the casting leave the arm's point
// masses for the module's body (the gripper turning on its bearing at H about
// the arm's axis A -> C, the casting held off the axis), the lever's motion is
// run and then the turn, and every moving part is analysed over the whole
// motion under the spatial loads (analyse_spatial_part_over_motion): the arm
// takes the turn's torque about its axis (torsion) and the casting's weight
// across its plane.
//
// Where the loads enter: each planar joint and drive through its face set as
// in the planar stage (distributing couplings), the module's bearing and its
// drive on the arm's face set that carried the gripper in the planar case
// (the gripper mount). Units SI; angles in rad.
#include <filesystem>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/pipeline/spatial_assembly_over_motion.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/postproc/provenance.hpp"

namespace kinetofem::pipeline {

struct RotaryModuleSettings {
  double angle_rad = 0.0;     // the turn about the arm's axis (cycloidal law)
  double start_s = 0.0;       // when the turn starts
  double duration_s = 0.0;    // how long it takes
  Eigen::Matrix3d gripper_inertia_kgm2 = Eigen::Matrix3d::Zero();  // the turning gripper about H, arm axes
  Eigen::Vector3d casting_offset_m = Eigen::Vector3d::Zero();       // casting's centre from H, arm axes at the start
  Eigen::Matrix3d casting_inertia_kgm2 = Eigen::Matrix3d::Zero();  // about its centre, arm axes at the start
};

struct RotaryModuleSummary {
  std::vector<double> times;  // the motion and then the turn
  double peak_torque_nm = 0.0, peak_torque_time_s = 0.0;  // the module drive's torque about the arm's axis
  std::vector<PartSummary> parts;
  // With the elastic assembly: the mechanism and the module as one structure
  // (spatial_assembly_over_motion.hpp) over the motion and the turn; its
  // tracked points are the planar assembly's and "casting" (the casting's
  // centre on the turning module: the gripper's deflection).
  std::optional<SpatialAssemblySummary> assembly;
  std::vector<PartFatigue> fatigue;  // per part, with the fatigue settings
  std::filesystem::path results_file;
};

// `model`: the planar mechanism as run (the parts' mass properties on its
// bodies) with its gripper and casting point masses on the arm at H; `parts`:
// the parts as meshed for it; `times`: the planar output times (the turn's
// are added at the same spacing). Writes `results_file` (the spatial
// histories, the moving skeletons, each part's fields). Throws Error naming
// the part for an attachment the spatial loads cannot take (a bearing
// pressure, a pin in contact, a transmission, a spring, a part of the
// ground). `assembly` (optional): the planar case's elastic assembly options;
// its chains' EA and tracked points carry over to the spatial assembly (its
// compliant drives, pins and contact do not: an Error says so). One
// factorization per part serves the assembly and the per-part stage.
// `modes` (optional, with `assembly`): the natural frequencies of the
// mechanism with its module frozen in each pose (the history
// vibration.frequency of results_file). `fatigue` (optional): each part's
// fatigue over the work cycle of the stroke and the turn (part_fatigue.hpp,
// its fields in results_file).
RotaryModuleSummary analyse_rotary_module(const mech::MultibodyModel& model, const std::vector<Part>& parts,
                                          const std::vector<double>& times, const RotaryModuleSettings& settings,
                                          const std::filesystem::path& results_file,
                                          const post::Provenance& provenance,
                                          const loads::LinkStressOptions& options, const Log& log,
                                          const structure::AssemblyOptions* assembly = nullptr,
                                          const vibration::AssemblyModesOptions* modes = nullptr,
                                          const FatigueSettings* fatigue = nullptr);

}  // namespace kinetofem::pipeline
