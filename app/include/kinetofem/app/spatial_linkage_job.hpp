#pragma once
// The "spatial_linkage" case type: any spatial linkage of rigid bodies (joint
// axes in any direction), written out in TOML, mapped one to one onto
// mech::spatial::Model (mechanisms/.../spatial/model.hpp) and run through the
// spatial multibody core: as a prescribed motion (kinematic, DoF 0: poses,
// velocities, and from the index-1 system the accelerations, every joint's
// reaction and the drive efforts) or integrated with SUNDIALS IDAS (any DoF).
//
// Case-file tables (every key, unit and default: spatial_linkage_schema() and
// docs/cases.md): [[body]] (mass, centre of mass, inertia tensor or principal
// moments, initial pose as position + roll-pitch-yaw), [[point]],
// [[point_mass]] (with rotary inertia), [[joint]] (spherical, revolute,
// prismatic, cylindrical, universal, fixed, with their axes), [[motion_drive]]
// on a joint's rotation or translation with the motion-law keys of
// motion_keys.hpp, [[spring]] (with damping), [[point_force]], [gravity],
// [simulation]. Lengths in the file are mm, angles deg; inside SI (m, rad).
// Frames: world right-handed x, y, z; a body's points, centre of mass, axes
// and inertia are in its body frame, whose origin and rotation (body axes ->
// world, R = Rz(yaw) Ry(pitch) Rx(roll)) the pose gives.
//
// Output: results/<name>.h5 (+ .xdmf) with the spatial histories and moving
// skeleton of pipeline/spatial_histories.hpp, plus the energy checks'
// histories; a console summary: peak drive efforts, peak joint reactions,
// drift, redundant rows, and the work-energy and power balances. A run whose
// drift or work-energy balance exceeds the planar runs' limits
// (pipeline/motion_stages.hpp) is refused before any results are written.
#include <string>
#include <vector>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/jobs.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"

namespace kinetofem::app {

const std::vector<KeySpec>& spatial_linkage_schema();

// The model a spatial_linkage case describes, checked name by name: an
// unknown body, point or joint, a zero-length axis, a moving body without
// mass or with an inertia that is not positive definite, a drive on a joint
// that has no such coordinate, is an Error naming file, line, key and value.
// The core's own checks (spatial/system.hpp) run when it is compiled.
mech::spatial::Model read_spatial_linkage_model(const CaseFile& case_file);

// The work-energy and power balances of a spatial run (SI):
//   power balance at every frame: dT/dt = v^T M v' equals the power of the
//     applied forces v^T (Q - h) (gravity, springs, dampers, point forces; the
//     gyroscopic term does no work) plus the drives' sum of effort * s'; its
//     largest residual over the peak power. Holds to round-off whenever the
//     frames' velocities satisfy the constraints (ideal joints do no work).
//   work-energy over the run: drive work W_d = integral of sum effort * s',
//     applied work W_a = integral of v^T (Q - h), by composite Simpson over
//     equally spaced frames (an even number of intervals; else trapezoidal);
//     W_d + W_a = T_end - T_0, its residual over (peak |power| * duration).
//     W_a = -(V_end - V_0) + W_nc, with W_nc the dampers' and point forces' work.
struct EnergyBalance {
  double drive_work_J = 0.0, applied_work_J = 0.0;
  double kinetic_gain_J = 0.0, potential_gain_J = 0.0;  // V: gravity and springs
  double nonconservative_work_J = 0.0;                  // dampers and point forces: W_a + dV
  double work_energy_error = 0.0;                       // |W_d + W_a - dT| / scale
  double power_balance_error = 0.0;                     // max over frames, / peak power
  std::vector<double> power_residual_W;                 // per frame
};
EnergyBalance energy_balance(const mech::spatial::System& system, const mech::spatial::Results& results);

// The energy checks' tolerances: the power balance is round-off; the
// work-energy balance holds to the quadrature's error, which for a smooth
// law over a few thousand intervals is far below this.
inline constexpr double kPowerBalanceTolerance = 1e-8;
inline constexpr double kWorkEnergyTolerance = 1e-6;
// The energy checks integrate over at least this many intervals (the output
// intervals split evenly; the extra frames are not written).
inline constexpr long kEnergyCheckIntervals = 2000;

MechanismCaseSummary run_spatial_linkage(const CaseFile& case_file, const RunOptions& options);

}  // namespace kinetofem::app
