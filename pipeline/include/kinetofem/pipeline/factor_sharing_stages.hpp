#pragma once
// The stages of a motion-to-stress run that borrow the parts' factorizations
// from their one owner (part_factors.hpp), and the results-size check before
// them. Each is a named step of driver::run_motion_to_stress:
//   check_results_fit_disk     before the motion and the solves
//   begin_elastic_assembly     the assembly's topology and checks (before the parts' stress)
//   analyse_part_with_factors  one part's stress over the motion with its lent factor
//   set_up_assembly_part       that part's interface and load-pattern solves on the same factor
//   analyse_assembly_with_factors   the assembly over the motion, then its factors given back
//   analyse_vibration_with_factors  the vibration over the motion, then its factors given back
// (the stages themselves: assembly_over_motion.hpp, vibration_over_motion.hpp).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/pipeline/assembly_over_motion.hpp"
#include "kinetofem/pipeline/part_factors.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/pipeline/part_stress.hpp"
#include "kinetofem/pipeline/part_stress_history.hpp"
#include "kinetofem/pipeline/vibration_over_motion.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::pipeline {

// Error when the results file would not fit the free space of its folder:
// per written output time (`field_steps` true, all when empty; plus the
// static study) and node, each part's displacement and von Mises (4 values)
// and, with the elastic assembly, its position, displacement, magnitude and
// von Mises (8), 8 bytes each.
void check_results_fit_disk(const std::filesystem::path& results_file, const std::vector<Part>& parts,
                            std::size_t output_times, const std::vector<bool>& field_steps, bool static_study,
                            bool with_assembly);

// The elastic assembly's topology and checks, its parts to be set up one by
// one (set_up_assembly_part) while each factor is in memory. `options` with
// the run's solver and field steps; whether it superposes its loads over
// `poses` (output times + the static study) is the factors' owner's choice.
structure::ElasticAssembly begin_elastic_assembly(const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                                  const structure::AssemblyOptions& options, std::size_t poses,
                                                  const PartFactors& factors, const Log& log);

// analyse_part_over_motion for part k with its factor lent by `factors`
// (factorized here when the factors live one at a time), then given back
// (FactorUser::Stress). Out of memory: an Error naming the part, its nodes,
// output times and factor size.
PartSummary analyse_part_with_factors(std::size_t k, const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                      const std::vector<mech::Frame>& motion,
                                      const std::optional<mech::Frame>& static_pose, post::ResultsWriter& writer,
                                      const loads::LinkStressOptions& options, const Log& log, PartFactors& factors,
                                      PartStressHistory* history = nullptr);

// Part k's set-up in the elastic assembly with its factor lent by
// `factors`, then given back (FactorUser::AssemblySetUp: freed unless the
// assembly's poses or the vibration still need it).
void set_up_assembly_part(structure::ElasticAssembly& assembly, std::size_t k, const std::vector<Part>& parts,
                          PartFactors& factors);

// analyse_assembly_over_motion on the set-up assembly, then every factor
// given back (FactorUser::Assembly: freed unless the vibration follows).
AssemblySummary analyse_assembly_with_factors(structure::ElasticAssembly& assembly, const std::vector<Part>& parts,
                                              const mech::MultibodyModel& model, const std::vector<mech::Frame>& motion,
                                              const std::optional<mech::Frame>& static_pose,
                                              post::ResultsWriter& writer, const structure::AssemblyOptions& options,
                                              const Log& log, PartFactors& factors,
                                              std::vector<PartStressHistory>* stress_histories = nullptr);

// analyse_vibration_over_motion on the same assembly, `factors` lending each
// part's factor to its reductions part by part (PartFactors::
// vibration_lender), then every factor given back (FactorUser::Vibration).
VibrationSummary analyse_vibration_with_factors(const structure::ElasticAssembly& assembly,
                                                const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                                const std::vector<mech::Frame>& motion,
                                                const std::optional<mech::Frame>& static_pose,
                                                post::ResultsWriter& writer,
                                                const structure::AssemblyOptions& assembly_options,
                                                const VibrationOptions& options, const AssemblySummary& quasi_static,
                                                const Log& log, PartFactors& factors);

}  // namespace kinetofem::pipeline
