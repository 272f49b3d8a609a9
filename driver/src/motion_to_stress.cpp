#include "kinetofem/driver/motion_to_stress.hpp"

#include <new>
#include <optional>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/pipeline/factor_sharing_stages.hpp"
#include "kinetofem/pipeline/part_factors.hpp"
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
    apply_mass_properties(run.model, parts, log, c.parts);
    for (const auto& part : parts) check_part_against_model(part, run.model);
    return 0;
  });
  in_stage(c, "the results would not fit the disk", [&] {  // before the motion and the solves
    check_results_fit_disk(c.results_file, parts, c.times.size(), c.stress.callback_steps, c.static_pose.has_value(),
                           c.assembly.has_value());
    return 0;
  });
  // Parts in several planes: the moments between the planes are in the
  // elastic assembly's 3D joint loads, not in the per-part stage's planar
  // reactions, so the fatigue takes each part's stress from the assembly.
  const bool fatigue_from_assembly = c.fatigue && parts_in_several_planes(c.parts);
  if (c.fatigue)
    in_stage(c, "a fatigue detail does not fit the parts", [&] {
      check_fatigue_details(*c.fatigue, parts);
      require(!fatigue_from_assembly || c.assembly,
              "the parts sit in several planes (their offset_mm z differs): their fatigue needs the elastic "
              "assembly's 3D joint loads (the moments between the planes); set assembly.enabled = true");
      return 0;
    });

  const mech::MultibodySystem system = in_stage(c, "the linkage is not valid", [&] { return mech::MultibodySystem(run.model); });
  log.info("dynamics: {} output times over {:.4g} s", c.times.size(), c.times.back() - c.times.front());
  clock.restart();
  run.motion = in_stage(c, "the motion cannot be run", [&] { return run_dynamics(system, c.times, c.dynamics); });
  run.dynamics_seconds = clock.seconds();
  log.info("  dynamics: {:.3f} s", run.dynamics_seconds);
  log.info("{}", run.motion.format_checks());
  log.detail("{}", run.motion.format_final_reactions());

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
  require(!c.vibration || c.assembly, "{}: the vibration needs the elastic assembly (assembly.enabled)", c.label);
  // One owner of every part's factorization: made once, lent to the per-part
  // stress, the elastic assembly and the vibration, freed after its last user.
  std::optional<PartFactors> factors;
  in_stage(c, "the parts cannot be factorized", [&] {
    factors.emplace(parts, c.stress.solver,
                    FactorStages{.stress = true, .assembly = c.assembly.has_value(), .vibration = c.vibration.has_value()},
                    c.label, log);
    return 0;
  });
  run.factorization = factors->report();
  structure::AssemblyOptions assembly_options;
  std::optional<structure::ElasticAssembly> assembly;
  if (c.assembly) {
    assembly_options = *c.assembly;
    assembly_options.solver = c.stress.solver;
    assembly_options.field_steps = c.stress.callback_steps;
    assembly_options.keep_part_stress = fatigue_from_assembly;
    assembly = in_stage(c, "the elastic assembly cannot be built", [&] {
      return std::optional<structure::ElasticAssembly>(
          begin_elastic_assembly(parts, run.model, assembly_options,
                                 run.motion.frames.size() + (run.static_pose ? 1 : 0), *factors, log));
    });
  }
  // The stress at every output time, kept for the fatigue stage (when asked),
  // from the per-part stage or the elastic assembly.
  std::vector<PartStressHistory> histories(c.fatigue ? parts.size() : 0);
  const auto assess_fatigue = [&] {
    in_stage(c, "the fatigue check cannot be done or written", [&] {
      log.info("fatigue: {} parts over {} output times (one work cycle); stress: {}", parts.size(),
               run.motion.frames.size(), describe(histories.front().source));
      for (std::size_t k = 0; k < parts.size(); ++k) {
        run.fatigue.push_back(assess_part_fatigue(parts[k], histories[k], *c.fatigue, log));
        write_part_fatigue(writer.body(parts[k].body()), run.fatigue.back());
        histories[k] = {};  // done with it: free the memory
      }
      return 0;
    });
  };
  for (std::size_t k = 0; k < parts.size(); ++k) {
    run.parts.push_back(in_stage(c, "the stress of the parts cannot be computed or written", [&] {
      return analyse_part_with_factors(k, parts, run.model, run.motion.frames, run.static_pose, writer, c.stress, log,
                                       *factors, c.fatigue && !fatigue_from_assembly ? &histories[k] : nullptr);
    }));
    if (assembly)
      in_stage(c, "the elastic assembly cannot be solved or written", [&] {
        set_up_assembly_part(*assembly, k, parts, *factors);
        return 0;
      });
  }
  if (c.fatigue && !fatigue_from_assembly) assess_fatigue();
  in_stage(c, "the histories cannot be written", [&] {
    write_mechanism_histories(writer, run.model, run.motion, c.tracked_points);
    return 0;
  });
  if (assembly) {
    log.info("elastic assembly: {} parts, {} output times{}", parts.size(), run.motion.frames.size(),
             run.static_pose ? " + the static study" : "");
    run.assembly = in_stage(c, "the elastic assembly cannot be solved or written", [&] {
      return analyse_assembly_with_factors(*assembly, parts, run.model, run.motion.frames, run.static_pose, writer,
                                           assembly_options, log, *factors,
                                           fatigue_from_assembly ? &histories : nullptr);
    });
  }
  if (fatigue_from_assembly) assess_fatigue();
  if (c.vibration) {
    log.info("vibration: the modes of the elastic assembly at {} output times{}", run.motion.frames.size(),
             run.static_pose ? " + the static pose" : "");
    run.vibration = in_stage(c, "the vibration cannot be analysed or written", [&] {
      return analyse_vibration_with_factors(*assembly, parts, run.model, run.motion.frames, run.static_pose, writer,
                                            assembly_options, *c.vibration, *run.assembly, log, *factors);
    });
  }
  writer.commit();
  return run;
}

}  // namespace kinetofem::driver
