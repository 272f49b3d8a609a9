#pragma once
// Stage "loads and stress over the motion" for one part: the loads of every
// output time (loads::LinkLoads: joint reactions, chain pull, drive efforts,
// springs, point forces, d'Alembert inertia and weight, point masses), one
// stiffness factorization, block solves, stress recovery, the envelope over
// the motion and, when a static pose frame is given, the static study, all
// streamed into the results file under the part's body name:
//   series  displacement (m, elastic: rigid-body motion removed, body frame),
//           von_mises (Pa), one step per output time; with pins in contact
//           also contact_pressure (Pa, on the bores' nodes, 0 elsewhere)
//   static  static_displacement, static_von_mises, static_stress (Voigt)
//   envelope von_mises (max), displacement_magnitude (max), with their step;
//           contact_pressure (max) with pins in contact
//   tables  contact.<body>.<joint>: per output time the peak contact pressure
//           (Pa), its angle and the arc in contact (deg)
// The part is held by a statically determinate 3-2-1 support whose reactions
// are checked to vanish (the loads are self-equilibrated). The frame (a part
// of the ground, Part::held_face) is held on its foundation instead, which
// takes the resultant of its loads (the ground sides of the joints, drives
// and chain, and its weight; no inertia: the ground does not move).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_stress_history.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/structure/spatial_part.hpp"

namespace kinetofem::pipeline {

// A pin in contact with a bore of a part over the motion (SI; angles in rad
// about the pin axis from the part's x axis).
struct PinContactSummary {
  std::string joint, face_set;
  std::string fit;                  // the ISO 286 fit, or empty
  double clearance_m = 0.0;         // radial
  double diameter_m = 0.0;          // of the bore
  double peak_pressure_pa = 0.0, peak_time_s = 0.0, peak_angle_rad = 0.0;
  double arc_at_peak_rad = 0.0;     // the arc in contact when the peak occurs
  double max_arc_rad = 0.0, min_arc_rad = 0.0;  // over the motion
};

// What a run reports of one part (SI units; times in s).
struct PartSummary {
  std::string body;
  long nodes = 0, dofs = 0;
  double peak_von_mises_pa = 0, peak_von_mises_time_s = 0;
  long peak_von_mises_node = 0;
  Eigen::Vector3d peak_von_mises_at_m = Eigen::Vector3d::Zero();  // body frame
  double peak_displacement_m = 0, peak_displacement_time_s = 0;
  bool has_static_study = false;  // the static_* values below were computed
  double static_von_mises_pa = 0, static_displacement_m = 0;
  double factorize_seconds = 0, solve_seconds = 0;
  double assembly_seconds = 0, recovery_seconds = 0, analyze_seconds = 0;
  double factor_nonzeros = 0, factor_bytes = 0, factorization_flops = 0;
  long right_hand_sides = 0;  // solved: load patterns (superposition) or one per frame
  long output_times = 0;
  bool superposed = false;    // unit-load superposition (else step by step)
  double worst_equilibrium_residual = 0, worst_support_reaction = 0;
  double max_out_of_plane_moment_nm = 0;  // carried by the pins (loads off the mid-plane z = 0)
  bool iterative_solver = false;  // AMG-PCG instead of CHOLMOD (factor too large, or asked for)
  std::string solver_summary;
  // Pins in contact with the part's bores (loads::BoreLoad::Contact), and the
  // contact solver's record for the part.
  std::vector<PinContactSummary> contacts;
  long contact_corners = 0;
  double contact_set_up_seconds = 0, contact_solve_seconds = 0, contact_condensed_bytes = 0;
  int contact_most_active_set_steps = 0, contact_interior_point_poses = 0;
  double contact_worst_penetration_m = 0, contact_worst_resultant_error = 0;
};

// A part's stiffness with its statically determinate 3-2-1 support
// (fem::three_two_one_support over all nodes; the frame: its foundation,
// structure::foundation_support), assembled and factorized once
// for the whole motion: the per-part stress stage below and the elastic
// assembly (structure/) share it, so a part is factorized once for both.
// Neither copied nor moved (the analysis refers to the model).
class SupportedPart {
 public:
  SupportedPart(const Part& part, const fem::StaticSolverOptions& solver, const Log& log);
  SupportedPart(const SupportedPart&) = delete;
  SupportedPart& operator=(const SupportedPart&) = delete;
  const fem::FeModel& model() const { return model_; }
  fem::LinearStaticAnalysis& analysis() const { return *analysis_; }

 private:
  fem::FeModel model_;
  std::unique_ptr<fem::LinearStaticAnalysis> analysis_;
};

// `part.model` without supports (they are added here; or `factorized`, the
// part's SupportedPart made before, is used). Writes the part's body
// into `writer`; prints the peak line. Throws Error naming the part and time
// when the loads are out of equilibrium or the support carries load.
// `history` (optional): filled with the stress at every output time (the
// superposition's patterns and coefficients, else every step's stress) for
// the fatigue stage (part_fatigue.hpp).
PartSummary analyse_part_over_motion(const Part& part, const mech::MultibodyModel& model,
                                     const std::vector<mech::Frame>& motion, const std::optional<mech::Frame>& static_pose,
                                     post::ResultsWriter& writer, const loads::LinkStressOptions& options,
                                     const Log& log, const SupportedPart* factorized = nullptr,
                                     PartStressHistory* history = nullptr);

// A part of a spatial mechanism (structure/spatial_part.hpp).
using structure::SpatialPart;

// The same stage for a part of a spatial mechanism (loads::SpatialLinkLoads:
// the full 3D joint and drive reactions, the inertia of a body turning about
// any axis, point masses with rotary inertia, slides on their stations), by
// unit-load superposition on one factorization of the part held by a 3-2-1
// support (on nodes of no attachment's face set); the same series, envelopes,
// load patterns and history as above, no static study, no pins in contact.
// `history` (optional): for the fatigue stage. `factorized` (optional): a
// factorization of the part with the support of
// structure::spatial_supported_model, lent (shared with the spatial elastic
// assembly); else one is made here.
PartSummary analyse_spatial_part_over_motion(const SpatialPart& part, const mech::spatial::Model& model,
                                             const std::vector<mech::spatial::Frame>& motion,
                                             post::ResultsWriter& writer, const loads::LinkStressOptions& options,
                                             const Log& log, PartStressHistory* history = nullptr,
                                             fem::LinearStaticAnalysis* factorized = nullptr);

}  // namespace kinetofem::pipeline
