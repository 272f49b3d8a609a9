#pragma once
// The motion-to-stress pipeline for any planar linkage whose bodies may carry
// FE parts: the driver that runs the stages of pipeline/ in order (it holds
// no factor or memory logic: PartFactors owns every part's factorization).
// The SPEC §1/§2 manipulators are presets of it
// (app/src/manipulator_job.cpp builds their MotionStressCase from their
// keys), the `linkage` case type another.
//
//   run_motion_to_stress(case):
//     1. check_motion_before_meshing   the motion is possible (nominal masses)
//     2. build_part_models             mesh and place every part
//     3. apply_mass_properties         bodies get their parts' mass properties
//        check_part_against_model      face sets, size, joint points in bores
//        check_results_fit_disk        the results file fits the free space
//     4. run_dynamics                  the motion with the real masses
//     5. solve_static_pose             the pose study at rest (when asked)
//     6. PartFactors                   every part analysed; factorized side by
//                                      side when the factors fit together
//        begin_elastic_assembly        the assembly's topology and checks (when asked)
//        analyse_part_with_factors     per part: loads, block solves with its
//                                      lent factor, stress, envelopes;
//        set_up_assembly_part          then (assembly asked) the part's
//                                      interface and load-pattern solves on
//                                      the same factor, freed after its last user
//        assess_part_fatigue           per part (when asked): rainflow, Miner,
//                                      life per node over the work cycle, on
//                                      the per-part stage's stress
//     7. write_mechanism_histories     bodies, joints, drives, chains, points
//     8. analyse_assembly_with_factors the linkage as one elastic structure
//                                      (when asked): total deformation, the
//                                      tracked points' deflection and split
//        assess_part_fatigue           instead of in step 6 when the parts sit
//                                      in several planes: on the assembly's
//                                      stress (its 3D joint loads; the
//                                      assembly is then required)
//        analyse_vibration_with_factors the assembly's modes in every pose and
//                                      the tracked points' vibration (when
//                                      asked; needs step 8); each gives its
//                                      factors back when done
//     9. commit the results file       atomically (.h5 + .xdmf)
// A linkage without parts runs steps 1, 4, 5, 7 and 9.
//
// Every Error of a stage is rethrown once with the case and the stage named
// ("case.toml: the motion cannot be run: singular position at t = ...").
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/pipeline/histories.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/pipeline/part_factorization.hpp"
#include "kinetofem/pipeline/part_fatigue.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/postproc/provenance.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"
#include "kinetofem/pipeline/vibration_over_motion.hpp"

namespace kinetofem::driver {

using pipeline::DynamicsSettings;
using pipeline::PartSpec;
using pipeline::PartSummary;
using pipeline::PathPoint;

struct MotionStressCase {
  std::string label;                 // for messages: the case file
  mech::MultibodyModel model;        // bodies with parts get the parts' mass properties
  std::vector<PartSpec> parts;       // may be empty: rigid-body dynamics only
  std::vector<double> times;         // output times, s (first = start)
  DynamicsSettings dynamics;
  // Target law value of each motion drive for the static pose study (rad or
  // m); empty: no static study.
  std::optional<std::vector<double>> static_pose;
  fem::IsotropicMaterial material;   // of every part
  meshes::MeshOptions mesh;
  loads::LinkStressOptions stress;
  std::vector<PathPoint> tracked_points;  // written as point.<body>.<point> paths
  // The elastic assembly (step 8); empty: not run. Its chains' EA, drives'
  // stiffness and points (e.g. the gripper point H with its face set).
  std::optional<structure::AssemblyOptions> assembly;
  // The vibration over the motion (after step 8, which it needs); empty: not run.
  std::optional<pipeline::VibrationOptions> vibration;
  // The fatigue check of every part over the work cycle (after step 6);
  // empty: not run.
  std::optional<pipeline::FatigueSettings> fatigue;
  std::filesystem::path results_file;        // <dir>/<name>.h5 (+ .xdmf)
  post::Provenance provenance;
};

struct MotionStressRun {
  mech::MultibodyModel model;  // as run: with the parts' mass properties
  mech::Results motion;
  std::optional<mech::Frame> static_pose;
  std::vector<PartSummary> parts;
  std::optional<pipeline::AssemblySummary> assembly;
  std::optional<pipeline::VibrationSummary> vibration;  // when c.vibration
  std::vector<pipeline::PartFatigue> fatigue;  // per part, when c.fatigue
  pipeline::PartFactorizationReport factorization;  // side by side or one after the other, and why
  std::filesystem::path results_file;
  double meshing_seconds = 0.0, dynamics_seconds = 0.0;
};

MotionStressRun run_motion_to_stress(const MotionStressCase& c, const Log& log);

}  // namespace kinetofem::driver
