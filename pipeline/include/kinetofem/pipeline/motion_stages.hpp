#pragma once
// Stages of the rigid-body motion, before and after the FE parts exist:
//
//   check_motion_before_meshing — the motion must be possible before anything
//       is meshed: a fully driven linkage (DoF 0) is run kinematically over all
//       output times with nominal mass properties for the bodies whose mass
//       comes from a mesh (the kinematics do not depend on masses, only the
//       loads scale with them), so a limit of assembly, a dead centre or a
//       drive past its range stops the run here with its time; a linkage
//       with free DoFs is assembled at t = 0 (its motion needs the masses).
//   run_dynamics — the motion with the real mass properties: IDAS (any DoF),
//       CVODES (1 DoF, minimal coordinate) or kinematic (DoF 0); its result
//       is used only if its own checks hold (require_accurate_motion).
//   solve_static_pose — the linkage at rest in a pose: each motion drive's
//       law value ramped from law(0) to the target by a 3-4-5 rise over 1 s
//       (continuation: Newton from the initial pose alone diverges far from
//       it); the last frame has zero speed and acceleration, so its reactions
//       and drive efforts are the static ones (gravity, point masses, forces).
//
// SI units throughout (s, m, rad, N, N m).
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"

namespace kinetofem::pipeline {

enum class DynamicsMethod { Idas, Cvodes, Kinematic };

struct DynamicsSettings {
  DynamicsMethod method = DynamicsMethod::Idas;
  mech::DynamicsOptions options;
  // CVODES: the independent coordinate (default: the first force drive's).
  std::optional<mech::RelativeCoordinate> cvodes_coordinate;
};

// Throws Error naming the time and what fails. `bodies_from_meshes`: bodies
// whose (still unknown) mass properties come from their parts.
void check_motion_before_meshing(const mech::MultibodyModel& model, const std::vector<double>& times,
                                 const std::vector<std::string>& bodies_from_meshes);

// Degrees of freedom of the model at its initial pose (assembled).
int degrees_of_freedom(const mech::MultibodySystem& system);

mech::Results run_dynamics(const mech::MultibodySystem& system, const std::vector<double>& times,
                           const DynamicsSettings& settings);

// The largest errors of a motion whose loads are still used: the position
// constraint drift relative to the model's characteristic length, and the
// energy balance |dT + dV - W| relative to the energy scale (docs/multibody.md,
// "Checks of a run"). At the default tolerances both are below 1e-8; at the
// loosest allowed (relative 1e-2, absolute 1) the bundled slider-crank drifts
// 3.5e-2 and its energy balance is off by 97 %: poses and loads would be wrong.
inline constexpr double kMaxRelativeConstraintDrift = 1e-4;
inline constexpr double kMaxEnergyBalanceError = 1e-2;

// Throws Error, naming the check, its value, the limit and the tolerances to
// tighten, when the run's constraint drift or energy balance (where the method
// computes it) is above those limits or not finite. run_dynamics calls it.
void require_accurate_motion(const mech::Results& results, const mech::DynamicsOptions& options);

// law_values[d]: the target value of motion drive d's law (rad or m; the
// drive holds s_0 + law_value). Needs a fully driven linkage. Throws Error if
// the pose cannot be reached or a chain is slack at rest.
mech::Frame solve_static_pose(const mech::MultibodyModel& model, const std::vector<double>& law_values);

}  // namespace kinetofem::pipeline
