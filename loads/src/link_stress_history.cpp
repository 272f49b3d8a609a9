#include "kinetofem/loads/link_stress_history.hpp"

#include "kinetofem/solver/rigid_body.hpp"

#include <algorithm>

#include <Eigen/SVD>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/dense_product.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::loads {

LinkEnvelope analyse_link_over_motion(const fem::FeModel& model, const LinkLoads& loads,
                                      const std::vector<mech::Frame>& frames, const Log& log,
                                      const LinkStressOptions& options, const StepCallback& on_step) {
  require(!frames.empty(), "link '{}': no output times to analyse", loads.body());
  log.info("link '{}': stiffness assembly and factorization (once for {} output times)",
           loads.body(), frames.size());
  fem::LinearStaticAnalysis analysis(model, log, options.solver);
  return analyse_link_over_motion(analysis, loads, frames, log, options, on_step);
}

namespace {

bool wants_callback(const LinkStressOptions& options, std::size_t step) {
  return options.callback_steps.empty() || (step < options.callback_steps.size() && options.callback_steps[step]);
}

// Relative size of the 3-2-1 support's reactions: relative to the total
// load the link carries (sum of the nodal force magnitudes), since the
// reactions come out of K u - f and carry the solve's round-off amplified by
// the condition of K.
double relative_support_reaction(const Eigen::VectorXd& reaction, const double* forces, fem::Index nodes) {
  const double load_scale =
      std::max(Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(forces, 3, nodes).colwise().norm().sum(),
               1e-300);
  return reaction.norm() / load_scale;
}

void check_support_reaction(LinkEnvelope& env, double relative, const std::string& part, double t,
                            const LinkStressOptions& options) {
  env.worst_support_reaction = std::max(env.worst_support_reaction, relative);
  if (!(relative <= options.reaction_tolerance))
    fail("link '{}' at t = {:.6g} s: the 3-2-1 support carries {:.2e} of the link's total "
         "load; the loads are not self-equilibrated",
         part, t, relative);
}

// Node i's von Mises stress and deformation magnitude at `step` into the envelope.
inline void fold_node(LinkEnvelope& env, Eigen::Index i, std::size_t step, double von_mises, double magnitude) {
  if (von_mises > env.max_von_mises_pa[i]) {
    env.max_von_mises_pa[i] = von_mises;
    env.max_von_mises_step[i] = int(step);
  }
  if (magnitude > env.max_displacement_m[i]) {
    env.max_displacement_m[i] = magnitude;
    env.max_displacement_step[i] = int(step);
  }
}

// One step's von Mises stress and deformation magnitude into the envelope.
void fold_into_envelope(LinkEnvelope& env, std::size_t step, const Eigen::Ref<const Eigen::VectorXd>& von_mises,
                        const Eigen::Ref<const Eigen::VectorXd>& magnitude) {
  for (Eigen::Index i = 0; i < von_mises.size(); ++i) fold_node(env, i, step, von_mises[i], magnitude[i]);
}

std::vector<fem::Index> supported_nodes(const fem::FeModel& model) {
  std::vector<fem::Index> supported;
  for (const auto& s : model.supports) supported.insert(supported.end(), s.nodes.begin(), s.nodes.end());
  return supported;
}

// A frame's nodal forces: LinkLoads::loads_at, or for a link with pins in
// contact the remaining patterns and the contact forces.
LinkLoadResult forces_at(const LinkLoads& loads, const std::vector<mech::Frame>& frames, std::size_t step,
                         const LinkContactHistory* contact, const Eigen::MatrixXd& patterns) {
  if (!contact) return loads.loads_at(frames[step]);
  const LinkLoadCoefficients c = loads.coefficients_at(frames[step]);
  LinkLoadResult r;
  r.forces = patterns * contact->remaining_coefficients.col(Eigen::Index(step));
  contact->add_forces(contact->pressure_pa.col(Eigen::Index(step)), r.forces);
  r.equilibrium_residual = c.equilibrium_residual;
  r.out_of_plane_moment_nm = c.out_of_plane_moment_nm;
  r.out_of_plane_force_n = c.out_of_plane_force_n;
  return r;
}

void step_by_step(fem::LinearStaticAnalysis& analysis, const LinkLoads& loads, const std::vector<mech::Frame>& frames,
                  const LinkContactHistory* contact, const LinkStressOptions& options, const StepCallback& on_step,
                  Progress& progress, LinkEnvelope& env) {
  const Eigen::MatrixXd patterns = contact ? loads.pattern_forces() : Eigen::MatrixXd();
  const fem::FeModel& model = analysis.model();
  const fem::Index nodes = model.mesh.node_count();
  const std::vector<fem::Index> supported = supported_nodes(model);
  Stopwatch clock;
  const std::size_t block = std::size_t(std::max(1, options.block_size));
  for (std::size_t first = 0; first < frames.size(); first += block) {
    const std::size_t count = std::min(block, frames.size() - first);
    Eigen::MatrixXd F(3 * nodes, Eigen::Index(count));
    for (std::size_t k = 0; k < count; ++k) {
      const LinkLoadResult r = forces_at(loads, frames, first + k, contact, patterns);
      env.worst_equilibrium_residual = std::max(env.worst_equilibrium_residual, r.equilibrium_residual);
      env.max_out_of_plane_moment_nm = std::max(env.max_out_of_plane_moment_nm, r.out_of_plane_moment_nm);
      F.col(Eigen::Index(k)) = r.forces;
    }
    clock.restart();
    const auto displacements = analysis.solve_forces(F);
    env.solve_seconds += clock.seconds();
    env.solved_right_hand_sides += long(count);
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t step = first + k;
      const fem::DisplacementField& u = displacements[k];
      const Eigen::VectorXd f = F.col(Eigen::Index(k));
      // Reactions of the determinate support: (K u - f) at its six DoFs.
      const Eigen::VectorXd reaction = analysis.reactions_at(u, f, supported);
      check_support_reaction(env, relative_support_reaction(reaction, f.data(), nodes), loads.body(), frames[step].t,
                             options);
      clock.restart();
      const fem::NodalStress stress = fem::recover_nodal_stress(model.mesh, analysis.materials(), u);
      // Deformation measure: the elastic displacement without the rigid-body
      // part the 3-2-1 support's arbitrary nodes put into it (computed once:
      // the callback gets the same field).
      const fem::DisplacementField elastic = fem::remove_rigid_body_motion(model.mesh, u);
      if (options.envelope_steps == 0 || step < options.envelope_steps)
        fold_into_envelope(env, step, stress.von_mises_pa, fem::displacement_magnitude(elastic));
      env.recovery_seconds += clock.seconds();
      if (on_step && wants_callback(options, step)) on_step(step, elastic, stress);
      progress.advance(long(step + 1));
    }
  }
}

// The contact pressures as load patterns: p(t) = U (U^T p(t)) with U the
// left singular vectors of the history [p(t)] whose singular values exceed
// 1e-13 of the largest (the dropped part is below that share of the
// pressure), so a motion whose contact spans few shapes adds few patterns. Appends to names, P (3 N x .) and C (. x frames).
void append_contact_patterns(const LinkContactHistory& contact, std::vector<std::string>& names,
                             Eigen::MatrixXd& P, Eigen::MatrixXd& C) {
  const Eigen::BDCSVD<Eigen::MatrixXd> svd(contact.pressure_pa, Eigen::ComputeThinU);
  const Eigen::VectorXd& sigma = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < sigma.size() && sigma[rank] > 1e-13 * sigma[0]) ++rank;
  const Eigen::MatrixXd U = svd.matrixU().leftCols(rank);
  const Eigen::Index p = P.cols();
  P.conservativeResize(Eigen::NoChange, p + rank);
  P.rightCols(rank).setZero();
  contact.add_forces(U, P.rightCols(rank));
  C.conservativeResize(C.rows() + rank, Eigen::NoChange);
  C.bottomRows(rank) = U.transpose() * contact.pressure_pa;
  for (Eigen::Index k = 0; k < rank; ++k) names.push_back(fmt::format("contact.shape_{}", k + 1));
}

// Every output time as a combination of the pattern fields (header: the
// superposition path), whatever built the patterns and their coefficients.
void superpose_patterns(fem::LinearStaticAnalysis& analysis, const PatternLoadHistory& loads,
                        const LinkStressOptions& options, const StepCallback& on_step, Progress& progress,
                        const Log& log, LinkEnvelope& env) {
  const fem::FeModel& model = analysis.model();
  const fem::Index nodes = model.mesh.node_count();
  const std::vector<fem::Index> supported = supported_nodes(model);
  const Eigen::Index steps = loads.coefficients.cols();
  const std::vector<std::string>& all_names = loads.names;
  const Eigen::MatrixXd& all_coefficients = loads.coefficients;
  const Eigen::MatrixXd& all_patterns = loads.patterns;
  env.worst_equilibrium_residual = std::max(env.worst_equilibrium_residual, loads.worst_equilibrium_residual);

  // 1. Patterns with a coefficient at some time (a zero row adds exactly 0).
  std::vector<Eigen::Index> kept;
  for (Eigen::Index k = 0; k < all_coefficients.rows(); ++k)
    if ((all_coefficients.row(k).array() != 0.0).any()) kept.push_back(k);
  const Eigen::Index m = Eigen::Index(kept.size());
  LinkLoadPatterns patterns;
  patterns.coefficients.resize(m, steps);
  Eigen::MatrixXd P(3 * nodes, m);
  {
    for (Eigen::Index k = 0; k < m; ++k) {
      patterns.names.push_back(all_names[size_t(kept[size_t(k)])]);
      patterns.coefficients.row(k) = all_coefficients.row(kept[size_t(k)]);
      P.col(k) = all_patterns.col(kept[size_t(k)]);
    }
  }
  log.detail("  link '{}': unit-load superposition: {} load patterns for {} output times", loads.part, m, steps);

  // 2. One block solve and one stress recovery per pattern.
  Stopwatch clock;
  const std::vector<fem::DisplacementField> unit = analysis.solve_forces(P);
  env.solve_seconds += clock.seconds();
  env.solved_right_hand_sides = long(m);
  clock.restart();
  Eigen::MatrixXd reaction_patterns(3 * Eigen::Index(supported.size()), m);
  patterns.elastic_displacement_m.resize(3 * nodes, m);
  patterns.stress_pa.resize(6 * nodes, m);
  for (Eigen::Index k = 0; k < m; ++k) {
    const fem::DisplacementField& u = unit[size_t(k)];
    reaction_patterns.col(k) = analysis.reactions_at(u, P.col(k), supported);
    const fem::DisplacementField elastic = fem::remove_rigid_body_motion(model.mesh, u);
    patterns.elastic_displacement_m.col(k) = Eigen::Map<const Eigen::VectorXd>(elastic.data(), 3 * nodes);
    const fem::NodalStress stress = fem::recover_nodal_stress(model.mesh, analysis.materials(), u);
    patterns.stress_pa.col(k) = Eigen::Map<const Eigen::VectorXd>(stress.stress_pa.data(), 6 * nodes);
  }

  // 3. Every frame as a combination, in blocks of frames. The products read
  // the pattern fields once per block (memory-bound for small blocks), so
  // blocks are as long as about 256 MB of buffers allow; the buffers are
  // allocated once (fresh ones per block cost more in page faults than the
  // arithmetic).
  const Eigen::Index block = std::clamp<Eigen::Index>(
      Eigen::Index(256e6 / (8.0 * 9.0 * double(std::max<fem::Index>(nodes, 1)))), 1, 512);
  Eigen::MatrixXd stress(6 * nodes, block), elastic(3 * nodes, block), reactions(reaction_patterns.rows(), block);
  // The support reaction is measured against sum_k |c_k| sum_i |P_ik|, a bound
  // of the step's total load sum_i |f_i| (triangle inequality; the patterns
  // are sparse and hardly cancel, so the bound is close), instead of forming
  // f = P c at every step.
  Eigen::VectorXd pattern_load(m);
  for (Eigen::Index k = 0; k < m; ++k)
    pattern_load[k] = Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(P.col(k).data(), 3, nodes)
                          .colwise()
                          .norm()
                          .sum();
  Eigen::VectorXd von_mises(nodes), magnitude(nodes);
  for (Eigen::Index first = 0; first < steps; first += block) {
    const Eigen::Index count = std::min(block, steps - first);
    const auto C = patterns.coefficients.middleCols(first, count);
    fem::blas_product(patterns.stress_pa, C, stress.leftCols(count));
    fem::blas_product(patterns.elastic_displacement_m, C, elastic.leftCols(count));
    reactions.leftCols(count).noalias() = reaction_patterns * C;
    for (Eigen::Index k = 0; k < count; ++k) {
      const std::size_t step = std::size_t(first + k);
      const double load_bound = std::max(C.col(k).cwiseAbs().dot(pattern_load), 1e-300);
      check_support_reaction(env, reactions.col(k).norm() / load_bound, loads.part, loads.times[step], options);
      const Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>> s(stress.col(k).data(), 6, nodes);
      const Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>> e(elastic.col(k).data(), 3, nodes);
      const bool in_envelope = options.envelope_steps == 0 || step < options.envelope_steps;
#pragma omp parallel for schedule(static)
      for (fem::Index i = 0; i < nodes; ++i) {
        von_mises[i] = fem::von_mises(s.col(i));
        magnitude[i] = e.col(i).norm();
        if (in_envelope) fold_node(env, i, step, von_mises[i], magnitude[i]);
      }
      if (on_step && wants_callback(options, step)) {
        const fem::DisplacementField u = e.transpose();
        fem::NodalStress nodal;
        nodal.stress_pa = s.transpose();
        nodal.von_mises_pa = von_mises;
        on_step(step, u, nodal);
      }
      progress.advance(long(step + 1));
    }
  }
  env.recovery_seconds += clock.seconds();
  env.patterns = std::move(patterns);
}

// The planar loads of every frame as a pattern history; with pins in
// contact, what remains on the patterns and the contact forces as patterns
// of their own.
PatternLoadHistory planar_history(const LinkLoads& loads, const std::vector<mech::Frame>& frames,
                                  const LinkContactHistory* contact, LinkEnvelope& env) {
  PatternLoadHistory h;
  h.part = loads.body();
  h.names = loads.pattern_names();
  h.coefficients.resize(loads.pattern_count(), Eigen::Index(frames.size()));
  for (std::size_t t = 0; t < frames.size(); ++t) {
    const LinkLoadCoefficients c = loads.coefficients_at(frames[t]);
    h.worst_equilibrium_residual = std::max(h.worst_equilibrium_residual, c.equilibrium_residual);
    env.max_out_of_plane_moment_nm = std::max(env.max_out_of_plane_moment_nm, c.out_of_plane_moment_nm);
    h.coefficients.col(Eigen::Index(t)) = c.coefficients;
    h.times.push_back(frames[t].t);
  }
  h.patterns = loads.pattern_forces();
  if (contact) {
    h.coefficients = contact->remaining_coefficients;
    append_contact_patterns(*contact, h.names, h.patterns, h.coefficients);
  }
  return h;
}

// A fresh envelope for `nodes` nodes (every maximum below any value).
LinkEnvelope empty_envelope(fem::Index nodes) {
  LinkEnvelope env;
  env.max_von_mises_pa = Eigen::VectorXd::Constant(nodes, -1.0);
  env.max_von_mises_step = Eigen::VectorXi::Zero(nodes);
  env.max_displacement_m = Eigen::VectorXd::Constant(nodes, -1.0);
  env.max_displacement_step = Eigen::VectorXi::Zero(nodes);
  return env;
}

// The critical instant and place, and the solver's report.
void finish_envelope(fem::LinearStaticAnalysis& analysis, LinkEnvelope& env) {
  env.peak_von_mises_pa = env.max_von_mises_pa.maxCoeff(&env.peak_von_mises_node);
  env.peak_von_mises_step = env.max_von_mises_step[env.peak_von_mises_node];
  env.peak_displacement_m = env.max_displacement_m.maxCoeff(&env.peak_displacement_node);
  env.peak_displacement_step = env.max_displacement_step[env.peak_displacement_node];
  env.solver = analysis.solver_statistics();
  env.iterative_solver = analysis.uses_iterative_solver();
  env.solver_summary = analysis.solver_summary();
}

}  // namespace

LinkEnvelope analyse_link_over_motion(fem::LinearStaticAnalysis& analysis, const LinkLoads& loads,
                                      const std::vector<mech::Frame>& frames, const Log& log,
                                      const LinkStressOptions& options, const StepCallback& on_step,
                                      const LinkContactHistory* contact) {
  require(!frames.empty(), "link '{}': no output times to analyse", loads.body());
  std::optional<LinkContactHistory> own_contact;
  if (!loads.contact_bores().empty() && !contact) {
    own_contact = solve_contact_over_motion(analysis, loads, frames, log);
    contact = &*own_contact;
  }
  require(!contact || contact->pressure_pa.cols() == Eigen::Index(frames.size()),
          "link '{}': the contact history has {} output times, the motion {}", loads.body(),
          contact ? contact->pressure_pa.cols() : 0, frames.size());
  require(options.load_path != LoadPath::Superposition || loads.superposable(),
          "link '{}': unit-load superposition was asked for, but a joint's cosine bearing pressure is not a "
          "combination of fixed load patterns; use the step-by-step path", loads.body());
  LinkEnvelope env = empty_envelope(analysis.model().mesh.node_count());
  env.assembly_seconds = analysis.timings().assembly_seconds;

  Progress progress(log, fmt::format("link '{}' time steps", loads.body()), long(frames.size()));
  const bool superpose = options.load_path == LoadPath::Superposition ||
                         (options.load_path == LoadPath::Auto && loads.superposable());
  if (superpose)
    superpose_patterns(analysis, planar_history(loads, frames, contact, env), options, on_step, progress, log, env);
  else
    step_by_step(analysis, loads, frames, contact, options, on_step, progress, env);
  progress.finish();
  finish_envelope(analysis, env);
  env.contact = std::move(own_contact);
  return env;
}

LinkEnvelope analyse_link_over_motion(fem::LinearStaticAnalysis& analysis, const PatternLoadHistory& loads,
                                      const Log& log, const LinkStressOptions& options, const StepCallback& on_step) {
  const fem::Index nodes = analysis.model().mesh.node_count();
  require(loads.coefficients.cols() > 0, "link '{}': no output times to analyse", loads.part);
  require(loads.patterns.cols() == loads.coefficients.rows() &&
              Eigen::Index(loads.names.size()) == loads.patterns.cols() &&
              Eigen::Index(loads.times.size()) == loads.coefficients.cols() && loads.patterns.rows() == 3 * nodes,
          "link '{}': the load history's patterns ({} x {}), names ({}), coefficients ({} x {}) and times ({}) "
          "disagree with each other or with the mesh ({} nodes)",
          loads.part, loads.patterns.rows(), loads.patterns.cols(), loads.names.size(), loads.coefficients.rows(),
          loads.coefficients.cols(), loads.times.size(), nodes);
  LinkEnvelope env = empty_envelope(nodes);
  env.assembly_seconds = analysis.timings().assembly_seconds;
  Progress progress(log, fmt::format("link '{}' time steps", loads.part), long(loads.times.size()));
  superpose_patterns(analysis, loads, options, on_step, progress, log, env);
  progress.finish();
  finish_envelope(analysis, env);
  return env;
}

}  // namespace kinetofem::loads
