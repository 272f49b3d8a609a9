#pragma once
// Stage "the elastic assembly over the motion": the linkage as ONE
// linear-elastic structure held by the ground (structure/elastic_assembly.hpp)
// at every output time and, when given, in the static pose study, with one
// factorization per part for all of them. Quasi-static: the elastic
// deflection does not feed back into the motion (the frames come from the
// rigid-body dynamics). Parts' loads by unit-load superposition
// (structure::AssemblyOptions::superpose_loads) from 64 poses on; fewer poses are solved
// one by one (cheaper there; exact either way). docs/elastic_assembly.md.
//
// Written into the results file (names: docs/results.md):
//   body assembly.<b> per elastic part, series (one step per output time):
//     position               m, N x 3  world coordinates of the rigid configuration
//                                      (the XDMF geometry of the step: the mechanism moves)
//     displacement           m, N x 3  world axes, from the rigid configuration
//     displacement_magnitude m, N x 1
//     von_mises              Pa, N x 1
//     contact_pressure       Pa, N x 1 a part with pins in contact: on their bores (0 elsewhere)
//   cell field solid (a welded part: each element's solid, part_model.hpp);
//   envelopes displacement_magnitude, von_mises (max over the motion);
//   static study: static_position, static_displacement,
//     static_displacement_magnitude, static_von_mises;
//   mechanism histories:
//     assembly.max_displacement                         m     max |u| over the parts' nodes
//     assembly.point.<P>.displacement                   m     x, y, z (world)
//     assembly.point.<P>.displacement_magnitude         m
//     assembly.point.<P>.rotation                       rad   x, y, z
//     assembly.point.<P>.from.<contributor>             m     x, y, z; contributor part.<b>,
//                                                             chain.<c>, drive.<d>, pin.<j>,
//                                                             play.<j> (a pin in contact); they add up
//     assembly.point.<P>.coupling_displacement          m     x, y, z: with couplings at the pins
//                                                             in contact (pins in contact only)
//     assembly.point.<P>.compliance                     m/N   xx xy xz yx yy yz zx zy zz
//     assembly.chain.<c>.tension, .elongation           N, m
//     assembly.drive.<d>.moment, .twist                 N*m, rad
//   tables assembly.contact.<b>.<j> per pin in contact with a bore of part b:
//     time (s), peak pressure (Pa), its angle from the part's x axis (deg), arc
//     in contact (deg), the pin's motion in the bore (x, y, m; body axes)
// The writer must have its mechanism time set (write_mechanism_histories) to
// the output times of `motion`.
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/pipeline/part_stress.hpp"  // PinContactSummary
#include "kinetofem/pipeline/part_stress_history.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/part.hpp"

namespace kinetofem::pipeline {

// A tracked point's extremes (SI; times in s).
struct PointSummary {
  std::string name, body;
  double max_displacement_m = 0.0, max_displacement_time_s = 0.0;
  Eigen::Vector3d displacement_at_max_m = Eigen::Vector3d::Zero();
  std::vector<structure::PointContribution> contributions_at_max;  // at that time
  // Largest and smallest eigenvalue of the in-plane (x, y) compliance over
  // the motion, m/N, with their times.
  double max_compliance_m_per_n = 0.0, max_compliance_time_s = 0.0;
  double min_compliance_m_per_n = 0.0, min_compliance_time_s = 0.0;
  bool has_static_study = false;
  Eigen::Vector3d static_displacement_m = Eigen::Vector3d::Zero();
  std::vector<structure::PointContribution> static_contributions;
  Eigen::Matrix3d static_compliance_m_per_n = Eigen::Matrix3d::Zero();
  // The displacement at every output time (T x 3, world axes, m): the
  // quasi-static deflection the vibration stage adds its ringing to.
  Eigen::MatrixXd displacement_history_m;
  // Pins in contact: the pins' share of the displacement (clearance and
  // contact against couplings), |u - u_coupling|, its largest over the motion.
  bool has_pins_in_contact = false;
  double max_pin_share_m = 0.0, max_pin_share_time_s = 0.0;
  Eigen::Vector3d pin_share_at_max_m = Eigen::Vector3d::Zero();
};

struct AssemblySummary {
  // Total deformation: max |u| over every part's nodes (world, from the rigid
  // configuration) over the motion, and in the static study.
  double max_displacement_m = 0.0, max_displacement_time_s = 0.0;
  std::string max_displacement_body;
  bool has_static_study = false;
  double static_max_displacement_m = 0.0;
  std::string static_max_displacement_body;
  std::vector<PointSummary> points;
  struct PartPeak {
    std::string body;
    double max_von_mises_pa = 0.0, static_von_mises_pa = 0.0;
  };
  std::vector<PartPeak> parts;
  // Per elastic pin (a joint whose bores sit at different z): its peaks over
  // the motion.
  struct PinPeak {
    std::string joint;
    double diameter_m = 0.0, length_m = 0.0;
    double max_bending_stress_pa = 0.0, max_bending_time_s = 0.0;
    double max_shear_stress_pa = 0.0, max_shear_time_s = 0.0;
    double max_deflection_m = 0.0;
  };
  std::vector<PinPeak> pins;
  // Per pin in contact with a bore of a part: its peaks over the motion.
  struct ContactPeak {
    std::string body;
    PinContactSummary pin;
    double max_pin_motion_m = 0.0;  // largest |(x, y)| of the pin's motion in the bore
  };
  std::vector<ContactPeak> contacts;
  double worst_contact_penetration_m = 0.0, worst_contact_resultant_error = 0.0, worst_contact_reciprocity = 0.0;
  structure::Indeterminacy indeterminacy;  // of the first pose (the same at every regular pose)
  // Per transmission: its largest moment on the output's body_j, twist and,
  // for a belt, the least span tension over the motion.
  struct TransmissionPeak {
    std::string name;
    double max_moment_nm = 0.0, max_moment_time_s = 0.0;  // |moment|
    double max_twist_rad = 0.0;                           // |twist|
    bool has_spans = false;
    double min_span_tension_n = 0.0, min_span_tension_time_s = 0.0;
  };
  std::vector<TransmissionPeak> transmissions;
  // |assembly chain tension - the dynamics'| / the dynamics', worst over the
  // poses (0 for determinate linkages up to round-off); likewise a
  // transmission's moment, relative to its largest.
  double worst_chain_mismatch = 0.0;
  double worst_transmission_mismatch = 0.0;
  structure::AssemblyStatistics statistics;
};

// `factorized`: the parts' factorizations shared with the per-part stage
// (structure::ElasticAssembly). Throws Error naming the part, joint, drive or time (elastic_assembly.hpp),
// and when a statically determinate linkage's chain force differs from the
// dynamics' tension by more than 1e-6 of it.
AssemblySummary analyse_assembly_over_motion(const std::vector<structure::Part>& parts,
                                             const mech::MultibodyModel& model,
                                             const std::vector<mech::Frame>& motion,
                                             const std::optional<mech::Frame>& static_pose,
                                             post::ResultsWriter& writer, const structure::AssemblyOptions& options,
                                             const Log& log,
                                             const std::vector<fem::LinearStaticAnalysis*>& factorized = {});

// The same on an assembly made (and set up) by the caller, e.g. one whose
// parts were set up one at a time with the factors lent by PartFactors
// (begin_elastic_assembly, set_up_assembly_part). `options` as given to it
// (points, field steps). `stress_histories` (optional; the assembly made
// with options.keep_part_stress): per part (in order) its stress at every
// output time in the assembly, the 3D joint loads included, for the fatigue
// stage (part_fatigue.hpp) where the parts sit in several planes.
AssemblySummary analyse_assembly_over_motion(structure::ElasticAssembly& assembly, const std::vector<structure::Part>& parts,
                                             const mech::MultibodyModel& model,
                                             const std::vector<mech::Frame>& motion,
                                             const std::optional<mech::Frame>& static_pose,
                                             post::ResultsWriter& writer, const structure::AssemblyOptions& options,
                                             const Log& log,
                                             std::vector<PartStressHistory>* stress_histories = nullptr);

// The options analyse_assembly_over_motion runs its assembly with for this
// many poses (output times + the static study): unit-load superposition only
// from kMinSuperposedPoses up (part_factors.hpp; below, one solve per pose is
// cheaper; exact either way).
structure::AssemblyOptions assembly_run_options(const structure::AssemblyOptions& options, size_t poses);

// One line per tracked point, the total deformation and the indeterminacy,
// in mm, um/N and %, for the run's summary.
std::string format_assembly_summary(const AssemblySummary& summary);

}  // namespace kinetofem::pipeline
