#pragma once
// Stage "the spatial elastic assembly over the motion": a spatial mechanism
// as ONE linear-elastic structure held by the ground
// (structure/spatial_elastic_assembly.hpp) at every output time of its
// motion, with one factorization per part, its loads superposed from fixed
// patterns. Quasi-static: the deflection does not feed back into the motion
// (the frames come from the rigid-body run). docs/elastic_assembly.md,
// "Spatial mechanisms".
//
// Written into the results file (the planar stage's names, docs/results.md):
//   body assembly.<b> per elastic part, series at the written output times:
//     position, displacement (m, world axes, from the rigid configuration),
//     displacement_magnitude (m), von_mises (Pa); envelopes
//     displacement_magnitude and von_mises (max over the motion);
//   histories assembly.max_displacement (m), and per tracked point P
//     assembly.point.<P>.displacement, .displacement_magnitude, .rotation,
//     .compliance (m/N, xx ... zz), .from.part.<b> and .from.chain.<c> (m:
//     the shares, they add up to the displacement);
//   with the vibration (vibration/spatial_assembly_modes.hpp: one
//   Craig-Bampton reduction per part, one small eigenproblem per pose):
//     history vibration.frequency (T x m, Hz, mode_1..mode_m), the natural
//     frequencies of the structure frozen in each pose.
// The writer's mechanism time must be the output times of `motion`.
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"  // PointSummary
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/structure/spatial_elastic_assembly.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"

namespace kinetofem::pipeline {

struct SpatialAssemblySummary {
  double max_displacement_m = 0.0, max_displacement_time_s = 0.0;
  std::string max_displacement_body;
  // Per tracked point; its compliance extremes are the eigenvalues of the
  // full 3 x 3 compliance (m/N).
  std::vector<PointSummary> points;
  struct PartPeak {
    std::string body;
    double max_von_mises_pa = 0.0, max_von_mises_time_s = 0.0;
  };
  std::vector<PartPeak> parts;
  double setup_seconds = 0.0, poses_seconds = 0.0;
  double worst_relative_residual = 0.0;  // of the poses' dense systems
  // The natural frequencies per pose (with the vibration).
  struct Vibration {
    int modes = 0;
    Eigen::MatrixXd frequency_hz;  // T x modes
    double lowest_first_hz = 0.0, lowest_first_time_s = 0.0;
    double highest_first_hz = 0.0, highest_first_time_s = 0.0;
    std::vector<vibration::PartReduction> reductions;
    std::string rule;  // the part-mode rule's check (SpatialAssemblyModes::check_rule)
    double seconds = 0.0;
  };
  std::optional<Vibration> vibration;
};

// `field_steps`: the output times whose fields are written (empty: all).
// `factorized`: the parts' factorizations lent (SpatialPartFactors), or empty.
// `vibration` (optional): the natural frequencies per pose too.
// Throws Error naming the part, joint, drive or time
// (spatial_elastic_assembly.hpp), or a result that is not finite.
SpatialAssemblySummary analyse_spatial_assembly_over_motion(
    const std::vector<structure::SpatialPart>& parts, const mech::spatial::Model& model,
    const std::vector<mech::spatial::Frame>& motion, post::ResultsWriter& writer,
    const structure::SpatialAssemblyOptions& options, const std::vector<bool>& field_steps, const Log& log,
    const std::vector<fem::LinearStaticAnalysis*>& factorized = {},
    const vibration::AssemblyModesOptions* vibration = nullptr);

}  // namespace kinetofem::pipeline
