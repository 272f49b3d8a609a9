#include "kinetofem/driver/motion_to_stress.hpp"

#include <algorithm>
#include <memory>
#include <new>
#include <optional>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/postproc/results_size.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::driver {

using namespace kinetofem::pipeline;  // the stages

namespace {

// Runs one stage; an Error leaves it with the case and the stage named.
template <typename Stage>
auto in_stage(const MotionStressCase& c, const char* what, Stage&& stage) {
  try {
    return stage();
  } catch (const Error& e) {
    fail("{}: {}: {}", c.label, what, e.what());
  } catch (const std::bad_alloc&) {
    const MemoryBudget left = memory_available_to_process();
    fail("{}: {}: out of memory: an allocation was refused ({:.3g} GB left by {}): coarsen the mesh, give fewer "
         "output times or raise the limit",
         c.label, what, left.bytes * 1e-9, left.limited_by);
  }
}

std::vector<std::string> bodies_with_parts(const std::vector<PartSpec>& parts) {
  std::vector<std::string> out;
  for (const auto& p : parts) out.push_back(p.attachments.body);
  return out;
}

}  // namespace

MotionStressRun run_motion_to_stress(const MotionStressCase& c, const Log& log) {
  MotionStressRun run;
  run.model = c.model;
  run.results_file = c.results_file;

  in_stage(c, "the motion cannot be run", [&] {
    check_motion_before_meshing(c.model, c.times, bodies_with_parts(c.parts));
    return 0;
  });
  in_stage(c, "a tracked point does not exist", [&] {  // before the FE work, not after it
    const mech::Frame at_rest{.bodies = std::vector<mech::BodyFrame>(c.model.bodies.size(),
                                                                      mech::BodyFrame{.q = Eigen::Vector3d::Zero()})};
    for (const auto& p : c.tracked_points) point_in_world(c.model, at_rest, p);
    return 0;
  });

  Stopwatch clock;
  const std::vector<Part> parts =
      in_stage(c, "the parts cannot be built", [&] { return build_part_models(c.parts, c.material, c.mesh, log); });
  run.meshing_seconds = clock.seconds();
  in_stage(c, "a part does not fit the linkage", [&] {
    apply_mass_properties(run.model, parts, log);
    for (const auto& part : parts) check_part_against_model(part, run.model);
    return 0;
  });
  in_stage(c, "the results would not fit the disk", [&] {  // before the motion and the solves
    // Per written output time and node: each part's displacement and von Mises (4 values) and,
    // with the elastic assembly, its position, displacement, magnitude and von Mises (8).
    const auto& mask = c.stress.callback_steps;
    const std::int64_t written = std::int64_t(mask.empty() ? c.times.size() : std::count(mask.begin(), mask.end(), true)) +
                                 (c.static_pose ? 1 : 0);
    const int per_node = 4 + (c.assembly ? 8 : 0);
    std::int64_t nodes = 0;
    for (const auto& part : parts) nodes += part.model.mesh.node_count();
    post::require_free_space(c.results_file.parent_path(), post::series_bytes(nodes, per_node, written),
                             fmt::format("the results file '{}'", c.results_file.string()),
                             fmt::format("{} field output times x {} nodes x {} values x 8 bytes", written, nodes,
                                         per_node));
    return 0;
  });
  if (c.fatigue)
    in_stage(c, "a fatigue detail does not fit the parts", [&] {
      check_fatigue_details(*c.fatigue, parts);
      return 0;
    });

  const mech::MultibodySystem system = in_stage(c, "the linkage is not valid", [&] { return mech::MultibodySystem(run.model); });
  log.info("dynamics: {} output times over {:.4g} s", c.times.size(), c.times.back() - c.times.front());
  clock.restart();
  run.motion = in_stage(c, "the motion cannot be run", [&] { return run_dynamics(system, c.times, c.dynamics); });
  run.dynamics_seconds = clock.seconds();
  log.info("  dynamics: {:.3f} s", run.dynamics_seconds);
  log.info("{}", run.motion.format_checks());

  if (c.static_pose)
    run.static_pose = in_stage(c, "the static study's pose cannot be reached",
                               [&] { return solve_static_pose(run.model, *c.static_pose); });

  // A bare file name ("run.h5") is written in the working directory: there
  // is no directory to create (create_directories("") is an error).
  if (c.results_file.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(c.results_file.parent_path(), ec);
    if (ec) fail("{}: cannot create the output directory: {}", c.results_file.parent_path().string(), ec.message());
  }
  post::ResultsWriter writer(c.results_file, c.provenance);
  // One factorization per part for the whole motion, shared by the per-part
  // stress and the elastic assembly.
  std::vector<std::unique_ptr<SupportedPart>> factorized;
  in_stage(c, "the parts cannot be factorized", [&] {
    factorized = factorize_parts(parts, c.stress.solver, log, &run.factorization);
    return 0;
  });
  std::vector<fem::LinearStaticAnalysis*> shared;  // the parts' factorizations, for steps 6, 8 and after
  for (const auto& f : factorized) shared.push_back(&f->analysis());
  // The elastic assembly's topology and checks before the FE work; each
  // part's interface columns and load patterns are solved right after its
  // own stage (step 6), while its factor is in memory. Parts whose factors
  // do not fit in memory together then need one factor at a time: each is
  // freed after the assembly's solves, which superposition makes the last.
  require(!c.vibration || c.assembly, "{}: the vibration needs the elastic assembly (assembly.enabled)", c.label);
  const bool factors_fit_together = run.factorization.predicted_factor_bytes <= run.factorization.limit_bytes;
  structure::AssemblyOptions assembly_options;
  std::optional<structure::ElasticAssembly> assembly;
  if (c.assembly) {
    assembly_options = *c.assembly;
    assembly_options.solver = c.stress.solver;
    assembly_options.field_steps = c.stress.callback_steps;
    structure::AssemblyOptions run_options =
        structure::assembly_run_options(assembly_options, run.motion.frames.size() + (run.static_pose ? 1 : 0));
    run_options.defer_part_setup = true;
    run_options.release_factors = !c.vibration;  // the vibration's reductions need them after the assembly
    if (!factors_fit_together) {
      require(!c.vibration,
              "{}: the vibration needs the parts' factorizations together ({:.3g} GB predicted), more than the "
              "{:.3g} GB allowed (solver.max_factor_gb): coarsen the mesh, raise the limit, or set "
              "vibration.enabled = false",
              c.label, run.factorization.predicted_factor_bytes * 1e-9, run.factorization.limit_bytes * 1e-9);
      run_options.superpose_loads = true;  // no pose may need a factor freed before it
      log.info("elastic assembly: one part's factor in memory at a time (the factors exceed the limit together); "
               "each is freed after its interface and load-pattern solves");
    }
    assembly = in_stage(c, "the elastic assembly cannot be built", [&] {
      return std::optional<structure::ElasticAssembly>(std::in_place, parts, run.model, run_options, log, shared);
    });
  }
  // The stress at every output time, kept for the fatigue stage (when asked).
  std::vector<PartStressHistory> histories(c.fatigue ? parts.size() : 0);
  for (std::size_t k = 0; k < parts.size(); ++k) {
    in_stage(c, "the stress of the parts cannot be computed or written", [&] {
      try {
        factorized[k]->analysis().factorize();  // done already when the parts went side by side
        run.parts.push_back(analyse_part_over_motion(parts[k], run.model, run.motion.frames, run.static_pose, writer,
                                                     c.stress, log, factorized[k].get(),
                                                     c.fatigue ? &histories[k] : nullptr));
      } catch (const std::bad_alloc&) {
        // What the part needed: its factor (when direct) and a stress field per output time in blocks.
        const fem::LinearStaticAnalysis& a = factorized[k]->analysis();
        const std::string solver = a.uses_iterative_solver()
                                       ? std::string("iterative solver")
                                       : fmt::format("factor {:.3g} GB", a.solver_statistics().factor_bytes * 1e-9);
        const MemoryBudget left = memory_available_to_process();
        fail("part '{}' ({} nodes, {} output times, {}): out of memory: an allocation was refused "
             "({:.3g} GB left by {}): coarsen the mesh, give fewer output times or raise the limit",
             parts[k].body(), parts[k].model.mesh.node_count(), run.motion.frames.size(), solver, left.bytes * 1e-9,
             left.limited_by);
      }
      return 0;
    });
    if (assembly)
      in_stage(c, "the elastic assembly cannot be solved or written", [&] {
        assembly->set_up_part(parts[k].body());  // frees the factor when nothing later needs it
        return 0;
      });
    else
      factorized[k].reset();  // no second use: free the factor now
  }
  if (c.fatigue)
    in_stage(c, "the fatigue check cannot be done or written", [&] {
      log.info("fatigue: {} parts over {} output times (one work cycle)", parts.size(), run.motion.frames.size());
      for (std::size_t k = 0; k < parts.size(); ++k) {
        run.fatigue.push_back(assess_part_fatigue(parts[k], histories[k], *c.fatigue, log));
        write_part_fatigue(writer.body(parts[k].body()), run.fatigue.back());
        histories[k] = {};  // done with it: free the memory
      }
      return 0;
    });
  in_stage(c, "the histories cannot be written", [&] {
    write_mechanism_histories(writer, run.model, run.motion, c.tracked_points);
    return 0;
  });
  if (assembly) {
    log.info("elastic assembly: {} parts, {} output times{}", parts.size(), run.motion.frames.size(),
             run.static_pose ? " + the static study" : "");
    run.assembly = in_stage(c, "the elastic assembly cannot be solved or written", [&] {
      return structure::analyse_assembly_over_motion(*assembly, parts, run.model, run.motion.frames, run.static_pose,
                                                     writer, assembly_options, log);
    });
  }
  if (c.vibration) {
    log.info("vibration: the modes of the elastic assembly at {} output times{}", run.motion.frames.size(),
             run.static_pose ? " + the static pose" : "");
    run.vibration = in_stage(c, "the vibration cannot be analysed or written", [&] {
      return structure::analyse_vibration_over_motion(*assembly, parts, run.model, run.motion.frames, run.static_pose,
                                                      writer, assembly_options, *c.vibration, *run.assembly, log);
    });
  }
  writer.commit();
  return run;
}

}  // namespace kinetofem::driver
