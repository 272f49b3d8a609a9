#include "kinetofem/pipeline/part_stress.hpp"

#include <limits>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::pipeline {

namespace {

// The contact pressure at every node of the mesh (0 off the bores).
post::FieldMatrix nodal_contact_pressure(const loads::LinkContactHistory& contact, Eigen::Index step, fem::Index nodes) {
  post::FieldMatrix p = post::FieldMatrix::Zero(nodes, 1);
  for (const auto& bore : contact.bores) {
    const Eigen::VectorXd values = bore.surface.nodal_pressure(bore.pressure_pa.col(step));
    for (size_t a = 0; a < bore.surface.nodes().size(); ++a) p(bore.surface.nodes()[a], 0) = values[Eigen::Index(a)];
  }
  return p;
}

// The pins' summaries from the contact history (motion times only) and
// its table per pin: time, peak pressure, its angle, the arc in contact.
void summarise_contact(const loads::LinkContactHistory& contact, const loads::LinkLoads& link_loads,
                       const std::vector<mech::Frame>& motion, const Part& part, post::ResultsWriter& writer,
                       PartSummary& ps) {
  constexpr double kDegree = std::numbers::pi / 180.0;
  for (size_t b = 0; b < contact.bores.size(); ++b) {
    const auto& bore = contact.bores[b];
    const loads::ContactBore& spec = link_loads.contact_bores()[b];
    PinContactSummary s;
    s.joint = bore.joint;
    s.face_set = bore.surface.face_set();
    for (const auto& j : part.attachments.joints)
      if (j.joint == bore.joint) s.fit = j.fit;
    s.clearance_m = bore.clearance_m;
    s.diameter_m = spec.diameter_m;
    s.min_arc_rad = std::numeric_limits<double>::infinity();
    post::FieldMatrix table(Eigen::Index(motion.size()), 4);
    for (size_t t = 0; t < motion.size(); ++t) {
      const fem::BoreContactState& state = bore.states[t];
      if (state.peak_pressure_pa > s.peak_pressure_pa) {
        s.peak_pressure_pa = state.peak_pressure_pa;
        s.peak_time_s = motion[t].t;
        s.peak_angle_rad = state.peak_angle_rad;
        s.arc_at_peak_rad = state.arc_rad;
      }
      s.max_arc_rad = std::max(s.max_arc_rad, state.arc_rad);
      s.min_arc_rad = std::min(s.min_arc_rad, state.arc_rad);
      table.row(Eigen::Index(t)) << motion[t].t, state.peak_pressure_pa, state.peak_angle_rad / kDegree,
          state.arc_rad / kDegree;
    }
    writer.write_table(fmt::format("contact.{}.{}", part.body(), bore.joint), "s, Pa, deg, deg", table,
                       {"time", "peak_pressure", "peak_angle", "arc"});
    ps.contacts.push_back(std::move(s));
  }
  ps.contact_corners = long(contact.contact_corners());
  ps.contact_set_up_seconds = contact.set_up_seconds;
  ps.contact_solve_seconds = contact.solve_seconds;
  ps.contact_condensed_bytes = contact.condensed_bytes;
  ps.contact_most_active_set_steps = contact.most_active_set_steps;
  ps.contact_interior_point_poses = contact.interior_point_poses;
  ps.contact_worst_penetration_m = contact.worst_penetration_m;
  ps.contact_worst_resultant_error = contact.worst_resultant_error;
}

// The superposition's patterns into the body (motion times only: the static
// study, solved in the same block, is written as static fields).
void write_load_patterns(post::BodyWriter& body, loads::LinkLoadPatterns& patterns, const std::vector<double>& times) {
  post::LoadPatternData data;
  data.names = patterns.names;
  data.time_s = times;
  data.coefficients = patterns.coefficients.leftCols(Eigen::Index(times.size()));
  data.elastic_displacement_m = std::move(patterns.elastic_displacement_m);
  data.stress_pa = std::move(patterns.stress_pa);
  body.write_load_patterns(data);
}

// The summary's fields an envelope gives: the peaks with their times and
// places (body frame), the solver's record, the checks.
void summarise_envelope(const loads::LinkEnvelope& env, const fem::Mesh& mesh, const std::vector<double>& times,
                        PartSummary& ps) {
  ps.peak_von_mises_pa = env.peak_von_mises_pa;
  ps.peak_von_mises_time_s = times[std::size_t(env.peak_von_mises_step)];
  ps.peak_von_mises_node = long(env.peak_von_mises_node);
  ps.peak_von_mises_at_m = mesh.nodes.row(env.peak_von_mises_node).transpose();
  ps.peak_displacement_m = env.peak_displacement_m;
  ps.peak_displacement_time_s = times[std::size_t(env.peak_displacement_step)];
  ps.factorize_seconds = env.solver.factorize_seconds;
  ps.solve_seconds = env.solve_seconds;
  ps.assembly_seconds = env.assembly_seconds;
  ps.recovery_seconds = env.recovery_seconds;
  ps.analyze_seconds = env.solver.analyze_seconds;
  ps.factor_nonzeros = env.solver.factor_nonzeros;
  ps.factor_bytes = env.solver.factor_bytes;
  ps.factorization_flops = env.solver.factorization_flops;
  ps.right_hand_sides = env.solved_right_hand_sides;
  ps.output_times = long(times.size());
  ps.superposed = env.patterns.has_value();
  ps.worst_equilibrium_residual = env.worst_equilibrium_residual;
  ps.worst_support_reaction = env.worst_support_reaction;
  ps.max_out_of_plane_moment_nm = env.max_out_of_plane_moment_nm;
  ps.iterative_solver = env.iterative_solver;
  ps.solver_summary = env.solver_summary;
}

}  // namespace

SupportedPart::SupportedPart(const Part& part, const fem::StaticSolverOptions& solver, const Log& log)
    : model_(structure::supported_model(part)) {
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

  // Pins in contact: solved at every output time first (on the same
  // factorization), so that each step's pressure is written with its stress.
  std::optional<loads::LinkContactHistory> contact;
  if (!link_loads.contact_bores().empty())
    contact = loads::solve_contact_over_motion(factorized->analysis(), link_loads, frames, log);

  post::BodyWriter& body = writer.add_body(part.body(), supported.mesh);
  write_solid_field(body, supported.mesh);
  std::vector<post::SeriesField> series = {{post::layout::kDisplacement, "m", 3, post::kVectorComponents},
                                           {post::layout::kVonMises, "Pa", 1, {}}};
  if (contact) series.push_back({post::layout::kContactPressure, "Pa", 1, {}});
  body.begin_series(series);
  const fem::Index nodes = supported.mesh.node_count();
  PartSummary ps;
  ps.body = part.body();
  ps.nodes = supported.mesh.node_count();
  ps.dofs = 3 * ps.nodes;
  const auto on_step = [&](std::size_t step, const fem::DisplacementField& u, const fem::NodalStress& s) {
    if (step < motion.size()) {
      if (keep_steps)
        history->step_stress_pa.col(Eigen::Index(step)) = Eigen::Map<const Eigen::VectorXd>(s.stress_pa.data(), s.stress_pa.size());
      if (!written(step)) return;
      if (contact)
        body.write_step(motion[step].t, {{post::layout::kDisplacement, u},
                                         {post::layout::kVonMises, s.von_mises_pa},
                                         {post::layout::kContactPressure,
                                          nodal_contact_pressure(*contact, Eigen::Index(step), nodes)}});
      else
        body.write_step(motion[step].t, {{post::layout::kDisplacement, u}, {post::layout::kVonMises, s.von_mises_pa}});
      return;
    }
    body.write_static(post::layout::static_name(post::layout::kDisplacement), "m", u, post::kVectorComponents);
    body.write_static(post::layout::static_name(post::layout::kVonMises), "Pa", s.von_mises_pa);
    body.write_static(post::layout::static_name(post::layout::kStress), "Pa", s.stress_pa, post::kVoigtComponents);
    if (contact)
      body.write_static(post::layout::static_name(post::layout::kContactPressure), "Pa",
                        nodal_contact_pressure(*contact, Eigen::Index(step), nodes));
    ps.has_static_study = true;
    ps.static_von_mises_pa = s.von_mises_pa.maxCoeff();
    ps.static_displacement_m = fem::displacement_magnitude(u).maxCoeff();
  };
  loads::LinkEnvelope env = loads::analyse_link_over_motion(factorized->analysis(), link_loads, frames, log,
                                                           stress_options, on_step, contact ? &*contact : nullptr);
  const post::IndexMatrix vm_step = env.max_von_mises_step.cast<fem::Index>();
  const post::IndexMatrix u_step = env.max_displacement_step.cast<fem::Index>();
  // Fields at some output times only: the envelope's steps index all of them.
  std::vector<double> step_times;
  if (!options.callback_steps.empty())
    for (const auto& frame : motion) step_times.push_back(frame.t);
  body.write_envelope(post::layout::kVonMises, "Pa", env.max_von_mises_pa, vm_step, post::layout::kEnvelopeMax, step_times);
  body.write_envelope(post::layout::kDisplacementMagnitude, "m", env.max_displacement_m, u_step, post::layout::kEnvelopeMax, step_times);
  if (contact) {
    post::FieldMatrix max_pressure = post::FieldMatrix::Zero(nodes, 1);
    post::IndexMatrix max_step = post::IndexMatrix::Zero(nodes, 1);
    for (size_t t = 0; t < motion.size(); ++t) {
      const post::FieldMatrix p = nodal_contact_pressure(*contact, Eigen::Index(t), nodes);
      for (fem::Index i = 0; i < nodes; ++i)
        if (p(i, 0) > max_pressure(i, 0)) max_pressure(i, 0) = p(i, 0), max_step(i, 0) = fem::Index(t);
    }
    body.write_envelope(post::layout::kContactPressure, "Pa", max_pressure, max_step, post::layout::kEnvelopeMax, step_times);
  }

  std::vector<double> times;
  for (const auto& frame : motion) times.push_back(frame.t);
  summarise_envelope(env, supported.mesh, times, ps);
  if (env.patterns && history) {
    history->pattern_stress_pa = env.patterns->stress_pa;
    history->coefficients = env.patterns->coefficients.leftCols(Eigen::Index(motion.size()));
  }
  if (env.patterns) write_load_patterns(body, *env.patterns, times);
  if (contact) {
    summarise_contact(*contact, link_loads, motion, part, writer, ps);
    constexpr double kDegree = std::numbers::pi / 180.0;
    for (const auto& c : ps.contacts)
      log.info("  {}: pin '{}' in contact with bore '{}' (diameter {:.2f} mm, radial clearance {:.1f} um{}): peak "
               "pressure {:.3f} MPa at t = {:.4f} s, {:.0f} deg from the part's x axis, contact arc {:.0f} deg there "
               "({:.0f} .. {:.0f} deg over the motion)",
               ps.body, c.joint, c.face_set, c.diameter_m / units::kMm, c.clearance_m * 1e6,
               c.fit.empty() ? std::string() : ", fit " + c.fit, c.peak_pressure_pa / units::kMpa, c.peak_time_s,
               c.peak_angle_rad / kDegree, c.arc_at_peak_rad / kDegree, c.min_arc_rad / kDegree,
               c.max_arc_rad / kDegree);
    log.detail("  {}: contact on {} corner nodes, {} output times: set-up {:.2f} s ({:.1f} MB condensed), solve "
               "{:.3f} s ({:.3g} ms per pose, at most {} active-set steps, {} poses by the interior point); "
               "penetration at most {:.1e} m, resultant error {:.1e}",
               ps.body, ps.contact_corners, frames.size(), ps.contact_set_up_seconds, ps.contact_condensed_bytes / 1e6,
               ps.contact_solve_seconds, 1e3 * ps.contact_solve_seconds / double(frames.size()),
               ps.contact_most_active_set_steps, ps.contact_interior_point_poses, ps.contact_worst_penetration_m,
               ps.contact_worst_resultant_error);
  }
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

PartSummary analyse_spatial_part_over_motion(const SpatialPart& part, const mech::spatial::Model& model,
                                             const std::vector<mech::spatial::Frame>& motion,
                                             post::ResultsWriter& writer, const loads::LinkStressOptions& options,
                                             const Log& log, PartStressHistory* history,
                                             fem::LinearStaticAnalysis* factorized) {
  const std::string& name = part.attachments.body;
  require(!motion.empty(), "{}: no output times to analyse", part.label);
  require(options.callback_steps.empty() || options.callback_steps.size() == motion.size(),
          "{}: the field output mask has {} entries for {} output times", part.label, options.callback_steps.size(),
          motion.size());
  std::optional<fem::FeModel> own_model;
  std::optional<fem::LinearStaticAnalysis> own_analysis;
  if (!factorized) {
    own_model = structure::spatial_supported_model(part);
    log.info("part '{}': stiffness assembly and factorization (once for the whole motion)", name);
    own_analysis.emplace(*own_model, log, options.solver);
  }
  fem::LinearStaticAnalysis& analysis = factorized ? *factorized : *own_analysis;
  const fem::FeModel& supported = analysis.model();
  loads::SpatialLinkDefinition definition = part.attachments;
  definition.model = &supported;
  const loads::SpatialLinkLoads link_loads(definition, model);

  post::BodyWriter& body = writer.add_body(name, supported.mesh);
  write_solid_field(body, supported.mesh);
  body.begin_series({{post::layout::kDisplacement, "m", 3, post::kVectorComponents},
                     {post::layout::kVonMises, "Pa", 1, {}}});
  const auto written = [&](std::size_t step) { return options.callback_steps.empty() || options.callback_steps[step]; };
  const auto on_step = [&](std::size_t step, const fem::DisplacementField& u, const fem::NodalStress& s) {
    if (written(step))
      body.write_step(motion[step].t, {{post::layout::kDisplacement, u}, {post::layout::kVonMises, s.von_mises_pa}});
  };
  loads::LinkEnvelope env = loads::analyse_link_over_motion(analysis, link_loads.history(motion), log, options, on_step);

  std::vector<double> times;
  for (const auto& frame : motion) times.push_back(frame.t);
  const std::vector<double> step_times = options.callback_steps.empty() ? std::vector<double>() : times;
  body.write_envelope(post::layout::kVonMises, "Pa", env.max_von_mises_pa, env.max_von_mises_step.cast<fem::Index>(),
                      post::layout::kEnvelopeMax, step_times);
  body.write_envelope(post::layout::kDisplacementMagnitude, "m", env.max_displacement_m,
                      env.max_displacement_step.cast<fem::Index>(), post::layout::kEnvelopeMax, step_times);
  PartSummary ps;
  ps.body = name;
  ps.nodes = supported.mesh.node_count();
  ps.dofs = 3 * ps.nodes;
  summarise_envelope(env, supported.mesh, times, ps);
  if (history) {
    history->source = StressHistorySource::SpatialFreeBodyPart;
    history->pattern_stress_pa = env.patterns->stress_pa;
    history->coefficients = env.patterns->coefficients;
  }
  write_load_patterns(body, *env.patterns, times);
  const Eigen::Vector3d at = ps.peak_von_mises_at_m / units::kMm;
  log.info("  {}: peak von Mises {:.3f} MPa at t = {:.4f} s, node {} ({:.1f}, {:.1f}, {:.1f}) mm (body frame); "
           "loads in equilibrium to {:.1e}, support reactions {:.1e}",
           ps.body, ps.peak_von_mises_pa / units::kMpa, ps.peak_von_mises_time_s, ps.peak_von_mises_node, at[0], at[1],
           at[2], env.worst_equilibrium_residual, env.worst_support_reaction);
  return ps;
}

}  // namespace kinetofem::pipeline
