#include "kinetofem/pipeline/factor_sharing_stages.hpp"

#include <algorithm>
#include <cstdint>
#include <new>
#include <string>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/postproc/results_size.hpp"

namespace kinetofem::pipeline {

void check_results_fit_disk(const std::filesystem::path& results_file, const std::vector<Part>& parts,
                            std::size_t output_times, const std::vector<bool>& field_steps, bool static_study,
                            bool with_assembly) {
  const std::int64_t written =
      std::int64_t(field_steps.empty() ? output_times : std::count(field_steps.begin(), field_steps.end(), true)) +
      (static_study ? 1 : 0);
  const int per_node = 4 + (with_assembly ? 8 : 0);
  std::int64_t nodes = 0;
  for (const auto& part : parts) nodes += part.model.mesh.node_count();
  post::require_free_space(results_file.parent_path(), post::series_bytes(nodes, per_node, written),
                           fmt::format("the results file '{}'", results_file.string()),
                           fmt::format("{} field output times x {} nodes x {} values x 8 bytes", written, nodes,
                                       per_node));
}

structure::ElasticAssembly begin_elastic_assembly(const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                                  const structure::AssemblyOptions& options, std::size_t poses,
                                                  const PartFactors& factors, const Log& log) {
  structure::AssemblyOptions run_options = options;
  // One factor at a time: superposed, so no pose needs a factor freed before it.
  run_options.superpose_loads =
      factors.factors_fit_together() ? options.superpose_loads && factors.superpose_assembly_loads(poses) : true;
  return structure::ElasticAssembly(parts, model, run_options, log, structure::PartsLentOneByOne{});
}

PartSummary analyse_part_with_factors(std::size_t k, const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                      const std::vector<mech::Frame>& motion,
                                      const std::optional<mech::Frame>& static_pose, post::ResultsWriter& writer,
                                      const loads::LinkStressOptions& options, const Log& log, PartFactors& factors,
                                      PartStressHistory* history) {
  PartSummary summary;
  try {
    const SupportedPart& supported = factors.lend(k);  // factorized already when the parts went side by side
    summary = analyse_part_over_motion(parts[k], model, motion, static_pose, writer, options, log, &supported, history);
  } catch (const std::bad_alloc&) {
    // What the part needed: its factor (when direct) and a stress field per output time in blocks.
    const fem::LinearStaticAnalysis* a = factors.held(k);
    const std::string solver = !a                          ? std::string("no factor")
                               : a->uses_iterative_solver() ? std::string("iterative solver")
                                   : fmt::format("factor {:.3g} GB", a->solver_statistics().factor_bytes * 1e-9);
    const MemoryBudget left = memory_available_to_process();
    fail("part '{}' ({} nodes, {} output times, {}): out of memory: an allocation was refused "
         "({:.3g} GB left by {}): coarsen the mesh, give fewer output times or raise the limit",
         parts[k].body(), parts[k].model.mesh.node_count(), motion.size(), solver, left.bytes * 1e-9, left.limited_by);
  }
  factors.done(k, FactorUser::Stress);
  return summary;
}

void set_up_assembly_part(structure::ElasticAssembly& assembly, std::size_t k, const std::vector<Part>& parts,
                          PartFactors& factors) {
  assembly.set_up_part(parts[k].body(), factors.lend_analysis(k));
  factors.done(k, FactorUser::AssemblySetUp, assembly.solves_with_factor(parts[k].body()));
}

AssemblySummary analyse_assembly_with_factors(structure::ElasticAssembly& assembly, const std::vector<Part>& parts,
                                              const mech::MultibodyModel& model, const std::vector<mech::Frame>& motion,
                                              const std::optional<mech::Frame>& static_pose,
                                              post::ResultsWriter& writer, const structure::AssemblyOptions& options,
                                              const Log& log, PartFactors& factors,
                                              std::vector<PartStressHistory>* stress_histories) {
  AssemblySummary summary =
      analyse_assembly_over_motion(assembly, parts, model, motion, static_pose, writer, options, log, stress_histories);
  factors.done_all(FactorUser::Assembly);
  return summary;
}

VibrationSummary analyse_vibration_with_factors(const structure::ElasticAssembly& assembly,
                                                const std::vector<Part>& parts, const mech::MultibodyModel& model,
                                                const std::vector<mech::Frame>& motion,
                                                const std::optional<mech::Frame>& static_pose,
                                                post::ResultsWriter& writer,
                                                const structure::AssemblyOptions& assembly_options,
                                                const VibrationOptions& options, const AssemblySummary& quasi_static,
                                                const Log& log, PartFactors& factors) {
  VibrationSummary summary = analyse_vibration_over_motion(assembly, parts, model, motion, static_pose, writer,
                                                           assembly_options, options, quasi_static, log,
                                                           &factors.vibration_lender());
  factors.done_all(FactorUser::Vibration);
  return summary;
}

}  // namespace kinetofem::pipeline
