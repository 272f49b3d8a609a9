#include "kinetofem/pipeline/part_stress.hpp"

#include <limits>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::pipeline {

namespace {

// A moving part: its 3-2-1 support; the frame (a part of the ground): its
// foundation.
fem::FeModel with_support(const Part& part) {
  fem::FeModel supported = part.model;
  if (!part.held_face.empty()) {
    supported.supports = structure::foundation_support(part);
    return supported;
  }
  std::vector<fem::Index> all(size_t(supported.mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
  supported.supports = fem::three_two_one_support(supported.mesh, all);
  return supported;
}

// The superposition's patterns into the body (motion times only: the static
// study, solved in the same block, is written as static fields).
void write_load_patterns(post::BodyWriter& body, loads::LinkLoadPatterns& patterns,
                         const std::vector<mech::Frame>& motion) {
  post::LoadPatternData data;
  data.names = patterns.names;
  for (const auto& frame : motion) data.time_s.push_back(frame.t);
  data.coefficients = patterns.coefficients.leftCols(Eigen::Index(motion.size()));
  data.elastic_displacement_m = std::move(patterns.elastic_displacement_m);
  data.stress_pa = std::move(patterns.stress_pa);
  body.write_load_patterns(data);
}

}  // namespace

SupportedPart::SupportedPart(const Part& part, const fem::StaticSolverOptions& solver, const Log& log)
    : model_(with_support(part)) {
  log.info("part '{}': stiffness assembly and factorization (once for the whole motion)", part.body());
  analysis_ = std::make_unique<fem::LinearStaticAnalysis>(model_, log, solver);
}

PartSummary analyse_part_over_motion(const Part& part, const mech::MultibodyModel& model,
                                     const std::vector<mech::Frame>& motion, const std::optional<mech::Frame>& static_pose,
                                     post::ResultsWriter& writer, const loads::LinkStressOptions& options,
                                     const Log& log, const SupportedPart* factorized, PartStressHistory* history) {
  require(!motion.empty(), "{}: no output times to analyse", part.label);
  std::unique_ptr<SupportedPart> own;
  if (!factorized) {
    own = std::make_unique<SupportedPart>(part, options.solver, log);
    factorized = own.get();
  }
  const fem::FeModel& supported = factorized->model();

  loads::LinkDefinition definition = part.attachments;
  definition.model = &supported;
  // The frame is held on its foundation, which takes the resultant of its
  // loads: no equilibrium to check, its support reactions are real (no
  // inertia relief: the ground does not move).
  const bool held = !part.held_face.empty();
  definition.held_on_foundation = held;
  const loads::LinkLoads link_loads(definition, model);

  // The static pose is solved in the same blocks, after the motion, and kept
  // out of the envelope.
  std::vector<mech::Frame> frames = motion;
  if (static_pose) {
    frames.push_back(*static_pose);
    frames.back().t = motion.back().t + 1.0;  // marks the static study in messages
  }
  loads::LinkStressOptions stress_options = options;
  stress_options.envelope_steps = motion.size();
  if (held) stress_options.reaction_tolerance = std::numeric_limits<double>::infinity();
  // Fields are written at the output times asked for (all by default) and
  // always for the static study; the envelope covers every output time.
  require(options.callback_steps.empty() || options.callback_steps.size() == motion.size(),
          "{}: the field output mask has {} entries for {} output times", part.label,
          options.callback_steps.size(), motion.size());
  if (!stress_options.callback_steps.empty() && static_pose) stress_options.callback_steps.push_back(true);
  // The fatigue stage's history: step by step, every output time's stress
  // goes through the callback (the mask then only limits what is written).
  const bool keep_steps = history && !(options.load_path == loads::LoadPath::Superposition ||
                                       (options.load_path == loads::LoadPath::Auto && link_loads.superposable()));
  const auto written = [&](std::size_t step) { return options.callback_steps.empty() || options.callback_steps[step]; };
  if (keep_steps) {
    stress_options.callback_steps.clear();
    history->step_stress_pa.resize(6 * supported.mesh.node_count(), Eigen::Index(motion.size()));
  }

  post::BodyWriter& body = writer.add_body(part.body(), supported.mesh);
  write_solid_field(body, supported.mesh);
  body.begin_series({{post::layout::kDisplacement, "m", 3, post::kVectorComponents}, {post::layout::kVonMises, "Pa", 1, {}}});
  PartSummary ps;
  ps.body = part.body();
  ps.nodes = supported.mesh.node_count();
  ps.dofs = 3 * ps.nodes;
  const auto on_step = [&](std::size_t step, const fem::DisplacementField& u, const fem::NodalStress& s) {
    if (step < motion.size()) {
      if (keep_steps)
        history->step_stress_pa.col(Eigen::Index(step)) = Eigen::Map<const Eigen::VectorXd>(s.stress_pa.data(), s.stress_pa.size());
      if (written(step)) body.write_step(motion[step].t, {{post::layout::kDisplacement, u}, {post::layout::kVonMises, s.von_mises_pa}});
      return;
    }
    body.write_static(post::layout::static_name(post::layout::kDisplacement), "m", u, post::kVectorComponents);
    body.write_static(post::layout::static_name(post::layout::kVonMises), "Pa", s.von_mises_pa);
    body.write_static(post::layout::static_name(post::layout::kStress), "Pa", s.stress_pa, post::kVoigtComponents);
    ps.has_static_study = true;
    ps.static_von_mises_pa = s.von_mises_pa.maxCoeff();
    ps.static_displacement_m = fem::displacement_magnitude(u).maxCoeff();
  };
  loads::LinkEnvelope env =
      loads::analyse_link_over_motion(factorized->analysis(), link_loads, frames, log, stress_options, on_step);
  const post::IndexMatrix vm_step = env.max_von_mises_step.cast<fem::Index>();
  const post::IndexMatrix u_step = env.max_displacement_step.cast<fem::Index>();
  // Fields at some output times only: the envelope's steps index all of them.
  std::vector<double> step_times;
  if (!options.callback_steps.empty())
    for (const auto& frame : motion) step_times.push_back(frame.t);
  body.write_envelope(post::layout::kVonMises, "Pa", env.max_von_mises_pa, vm_step, post::layout::kEnvelopeMax, step_times);
  body.write_envelope(post::layout::kDisplacementMagnitude, "m", env.max_displacement_m, u_step, post::layout::kEnvelopeMax, step_times);

  ps.peak_von_mises_pa = env.peak_von_mises_pa;
  ps.peak_von_mises_time_s = motion[size_t(env.peak_von_mises_step)].t;
  ps.peak_von_mises_node = long(env.peak_von_mises_node);
  ps.peak_von_mises_at_m = supported.mesh.nodes.row(env.peak_von_mises_node).transpose();
  ps.peak_displacement_m = env.peak_displacement_m;
  ps.peak_displacement_time_s = motion[size_t(env.peak_displacement_step)].t;
  ps.factorize_seconds = env.solver.factorize_seconds;
  ps.solve_seconds = env.solve_seconds;
  ps.assembly_seconds = env.assembly_seconds;
  ps.recovery_seconds = env.recovery_seconds;
  ps.analyze_seconds = env.solver.analyze_seconds;
  ps.factor_nonzeros = env.solver.factor_nonzeros;
  ps.factor_bytes = env.solver.factor_bytes;
  ps.factorization_flops = env.solver.factorization_flops;
  ps.right_hand_sides = env.solved_right_hand_sides;
  ps.output_times = long(motion.size());
  ps.superposed = env.patterns.has_value();
  if (env.patterns && history) {
    history->pattern_stress_pa = env.patterns->stress_pa;
    history->coefficients = env.patterns->coefficients.leftCols(Eigen::Index(motion.size()));
  }
  if (env.patterns) write_load_patterns(body, *env.patterns, motion);
  ps.worst_equilibrium_residual = env.worst_equilibrium_residual;
  ps.worst_support_reaction = env.worst_support_reaction;
  ps.max_out_of_plane_moment_nm = env.max_out_of_plane_moment_nm;
  ps.iterative_solver = env.iterative_solver;
  ps.solver_summary = env.solver_summary;
  const Eigen::Vector3d at = ps.peak_von_mises_at_m / units::kMm;
  // A welded part: the peak's solid, and its seam when it lies on one.
  if (const std::string place = meshes::place_in_welded_part(supported.mesh, ps.peak_von_mises_node); !place.empty())
    log.info("  {}: the peak von Mises lies in {}", ps.body, place);
  log.detail("  {}: {} right-hand sides for {} output times{}", ps.body, ps.right_hand_sides, frames.size(),
           ps.superposed ? " (unit-load superposition)" : " (step by step)");
  if (held)
    log.info("  {}: peak von Mises {:.3f} MPa at t = {:.4f} s, node {} ({:.1f}, {:.1f}, {:.1f}) mm (body frame); "
             "the frame, held on its foundation '{}' (which takes the resultant of its loads)",
             ps.body, ps.peak_von_mises_pa / units::kMpa, ps.peak_von_mises_time_s, ps.peak_von_mises_node, at[0],
             at[1], at[2], part.held_face);
  else
    log.info("  {}: peak von Mises {:.3f} MPa at t = {:.4f} s, node {} ({:.1f}, {:.1f}, {:.1f}) mm (body frame); "
             "loads in equilibrium to {:.1e}, support reactions {:.1e}; out-of-plane moment on the pins up to {:.3g} N m",
             ps.body, ps.peak_von_mises_pa / units::kMpa, ps.peak_von_mises_time_s, ps.peak_von_mises_node, at[0],
             at[1], at[2], env.worst_equilibrium_residual, env.worst_support_reaction, ps.max_out_of_plane_moment_nm);
  return ps;
}

}  // namespace kinetofem::pipeline
