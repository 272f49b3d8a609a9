#pragma once
// Stage "the vibration of the manipulator over the motion"
// (docs/vibration.md): the natural frequencies of the elastic assembly in
// every pose (vibration/assembly_modes.hpp: one Craig-Bampton reduction per
// part, one small eigenproblem per pose) and the elastic vibration of the
// tracked points (the gripper point H) that the motion's inertia and weight
// loads excite, during the stroke and for a settling window after the stop.
//
// Response. In the interval [t_k, t_k+1] between output times the pose and
// its modes (omega_i, phi_i) are frozen and the modal load f_i = phi_i^T F(t)
// goes linearly (F: AssemblyModes::load); each mode is advanced EXACTLY for
// it (vibration::ModalStepper), on substeps of at most 1/8 of the period of
// the highest mode kept (the history is then drawn finely enough). At t_k+1
// the modal state passes to the next pose's modes: its quasi-static part
// becomes the new pose's f / w^2, its dynamic part q - f / w^2 and its
// velocity pass by the mass-orthogonal projection Phi_k+1^T M Phi_k (M is
// constant in the body axes), so a motion slow against the modes stays
// quasi-static however the mode shapes turn. Start: at rest in the
// quasi-static state of the first pose. Modal damping: one ratio zeta.
// Output by mode acceleration:
//   y(t) = y_qs(t) + C Phi (q - f / omega^2),
// y_qs the elastic assembly's own (exact) quasi-static deflection of the point
// (AssemblySummary::points[].displacement_history_m, linear in between), so
// the modes truncated only miss their dynamic part, not their static one.
// After the stop the last pose and load stay; the settling time is the
// guaranteed bound of vibration::settling_after_stop (|y - y_end| <=
// tolerance from then on; +inf with zeta = 0).
// Dynamic amplification = peak |y| / peak |y_qs| over the stroke (the
// weight's sag included in both); the vibration itself is peak |y - y_qs|.
// Neglected (docs/vibration.md): the elastic motion's effect on the rigid
// motion, geometric stiffness, gyroscopic and centrifugal terms.
//
// Written (docs/results.md):
//   mechanism history vibration.frequency                (T x m) Hz, mode_1..mode_m
//   mechanism history vibration.point.<P>.displacement   (T x 3) m, y at the output times
//   tables vibration.static_frequency (m x 1) Hz (static study),
//     vibration.response.time (n x 1) s, vibration.response.stop_time (1 x 1) s,
//     vibration.response.point.<P>.displacement, .quasi_static (n x 3) m,
//     vibration.point.<P>.settling_time (s after the stop), .settling_tolerance (m),
//     .amplitude_at_stop (m), .dynamic_amplification (1)
//   bodies vibration.static.<b> (static study) and vibration.lowest.<b> (the
//     pose of the lowest first frequency), their meshes placed in world
//     coordinates at that pose: static fields mode_<i> (N x 3, max |u| over
//     the parts = 1) and mode_<i>_magnitude, i = 1..m (ParaView: Warp By
//     Vector, and animate its scale factor).
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/part.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"

namespace kinetofem::pipeline {

// Modal damping ratio of a welded steel structure at working stress:
// 2 to 3 % (N. M. Newmark, W. J. Hall, "Earthquake Spectra and Design",
// EERI 1982, table 3); the lower end, which rings longest.
inline constexpr double kDefaultModalDampingRatio = 0.02;
// The gripper point's settling tolerance, m: 0.1 mm, a tenth of a typical
// +-1 mm gripping tolerance of a die-cast part.
inline constexpr double kDefaultSettlingToleranceM = 0.1e-3;

struct VibrationOptions {
  vibration::AssemblyModesOptions modes;
  double damping_ratio = kDefaultModalDampingRatio;     // 0 <= zeta < 1
  double settling_tolerance_m = kDefaultSettlingToleranceM;  // > 0
};

struct PointVibration {
  std::string name;
  double peak_dynamic_m = 0.0, peak_dynamic_time_s = 0.0;
  double peak_quasi_static_m = 0.0, peak_quasi_static_time_s = 0.0;
  double dynamic_amplification = 0.0;
  double peak_vibration_m = 0.0, peak_vibration_time_s = 0.0;  // max |y - y_qs| over the stroke
  // Largest |y - y_end| from the stop on (sampled over the settling window at
  // 8 points per period of the highest mode kept): the ringing left behind.
  double amplitude_at_stop_m = 0.0;
  double settling_time_s = 0.0;      // after the stop; +inf: never (zeta = 0)
  // max over the output times of |C x_static(reduced) - y_qs| / max |y_qs|:
  // the reduced model's static deflection against the elastic assembly's.
  double reduced_static_mismatch = 0.0;
};

struct VibrationSummary {
  int modes = 0;
  std::vector<double> time_s;    // output times
  Eigen::MatrixXd frequency_hz;  // T x m
  double lowest_first_hz = 0.0, lowest_first_time_s = 0.0;
  double highest_first_hz = 0.0, highest_first_time_s = 0.0;
  bool has_static_study = false;
  Eigen::VectorXd static_frequency_hz;
  std::vector<PointVibration> points;
  double damping_ratio = 0.0, settling_tolerance_m = 0.0;
  double stop_time_s = 0.0, window_after_stop_s = 0.0;
  std::vector<vibration::PartReduction> reductions;
  double cutoff_hz = 0.0;
  std::string rule_check;
  Eigen::Index reduced_size = 0;
  double reduction_seconds = 0.0, modes_seconds = 0.0, response_seconds = 0.0;
};

// `assembly_options`: those of the elastic assembly stage (its points are
// the points reported); `quasi_static`: that stage's summary (the points'
// deflection histories). `factorized`: the parts' shared factorizations.
// Throws Error for bad options (modes < 1, zeta outside [0, 1), tolerance
// <= 0), a zero-density part, an eigen solve that does not converge (naming
// the part and the modes converged), rigid-bore couplings.
VibrationSummary analyse_vibration_over_motion(const std::vector<structure::Part>& parts,
                                               const mech::MultibodyModel& model,
                                               const std::vector<mech::Frame>& motion,
                                               const std::optional<mech::Frame>& static_pose,
                                               post::ResultsWriter& writer, const structure::AssemblyOptions& assembly_options,
                                               const VibrationOptions& options, const AssemblySummary& quasi_static,
                                               const Log& log,
                                               const std::vector<fem::LinearStaticAnalysis*>& factorized = {});

// The same on the caller's (set-up) assembly, e.g. the one the quasi-static
// stage ran (driver): its parts' interface columns are not solved again.
// `lender`: lends each part's factorization to the reductions, part by part
// (PartFactors::vibration_lender: one factor in memory at a time when they do
// not fit together); null: the assembly's parts' factorizations must still
// be lent to it.
VibrationSummary analyse_vibration_over_motion(const structure::ElasticAssembly& assembly,
                                               const std::vector<structure::Part>& parts,
                                               const mech::MultibodyModel& model,
                                               const std::vector<mech::Frame>& motion,
                                               const std::optional<mech::Frame>& static_pose,
                                               post::ResultsWriter& writer, const structure::AssemblyOptions& assembly_options,
                                               const VibrationOptions& options, const AssemblySummary& quasi_static,
                                               const Log& log, vibration::PartFactorLender* lender = nullptr);

// The frequencies, amplification and settling in a few lines (Hz, mm, s).
std::string format_vibration_summary(const VibrationSummary& summary);

}  // namespace kinetofem::pipeline
