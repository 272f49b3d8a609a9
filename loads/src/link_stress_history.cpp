#include "kinetofem/loads/link_stress_history.hpp"

#include "kinetofem/solver/rigid_body.hpp"

#include <algorithm>
#include <utility>

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

// Nodes per chunk of the fused envelope kernel: a chunk's tiles of 128
// frames (9.4 MB) stay well inside the last-level cache and are long enough
// for the BLAS to run at its rate.
constexpr Eigen::Index kChunkNodes = 1024, kChunkFrames = 128;

// The fields of a block's written frames (columns in the order of `steps`,
// local indices into the block), filled by fuse_block.
struct WrittenFields {
  std::vector<Eigen::Index> steps;
  Eigen::MatrixXd stress;     // 6 N x written, node-major Voigt
  Eigen::MatrixXd elastic;    // 3 N x written, node-major
  Eigen::MatrixXd von_mises;  // N x written
  // fuse_block's work space, kept between blocks.
  Eigen::MatrixXd chunk_stress, chunk_elastic, tile_stress, tile_elastic;
  Eigen::ArrayXd von_mises_tile, magnitude_tile;
};

// One block of frames (coefficients C, m x count, the first at frame
// `first`) into the envelope, without forming the block's full fields: per
// chunk of nodes, the chunk's pattern rows times C give its stresses and
// displacements in a tile that stays in cache, and von Mises, magnitude and
// the envelope are taken from the tile at once. The full products would
// write and read back 9 N doubles a frame from memory, which for many frames
// costs several times their arithmetic. The tiles' products go through the
// BLAS (threaded by it; several times Eigen's generic kernel on these tall,
// skinny products, see dense_product.hpp). The folds run on the calling
// thread: an OpenMP team between the BLAS calls spins against the BLAS's
// own threads (measured: most of the time went to the spinning). Each node
// folds the frames in order, so on ties the earliest frame still wins.
// Frames from `envelope_end` on enter no envelope.
void fuse_block(const LinkLoadPatterns& patterns, const Eigen::Ref<const Eigen::MatrixXd>& C, Eigen::Index first,
                Eigen::Index envelope_end, WrittenFields& fields, LinkEnvelope& env) {
  const Eigen::Index nodes = patterns.stress_pa.rows() / 6, count = C.cols();
  const Eigen::Index folded = std::clamp<Eigen::Index>(envelope_end - first, 0, count);
  fields.chunk_stress.resize(6 * std::min(kChunkNodes, nodes), C.rows());
  fields.chunk_elastic.resize(3 * std::min(kChunkNodes, nodes), C.rows());
  fields.tile_stress.resize(6 * std::min(kChunkNodes, nodes), std::min(kChunkFrames, count));
  fields.tile_elastic.resize(3 * std::min(kChunkNodes, nodes), std::min(kChunkFrames, count));
  fields.von_mises_tile.resize(std::min(kChunkNodes, nodes));
  fields.magnitude_tile.resize(std::min(kChunkNodes, nodes));
  if (folded == 0 && fields.steps.empty()) return;
  for (Eigen::Index i0 = 0; i0 < nodes; i0 += kChunkNodes) {
    const Eigen::Index n = std::min(kChunkNodes, nodes - i0);
    // The chunk's pattern rows component-major (its n sigma_xx rows, then
    // its n sigma_yy rows, ...): the tiles' components are then contiguous
    // and the von Mises stresses and magnitudes below vectorize. Copied once
    // a block, a small share of the products' reads; kept in cache for them.
    auto S = fields.chunk_stress.topRows(6 * n);
    auto E = fields.chunk_elastic.topRows(3 * n);
    for (int c = 0; c < 6; ++c)
      S.middleRows(c * n, n) = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, 6>>(
          patterns.stress_pa.data() + 6 * i0 + c, n, S.cols(), Eigen::Stride<Eigen::Dynamic, 6>(6 * nodes, 6));
    for (int c = 0; c < 3; ++c)
      E.middleRows(c * n, n) = Eigen::Map<const Eigen::MatrixXd, 0, Eigen::Stride<Eigen::Dynamic, 3>>(
          patterns.elastic_displacement_m.data() + 3 * i0 + c, n, E.cols(),
          Eigen::Stride<Eigen::Dynamic, 3>(3 * nodes, 3));
    for (Eigen::Index k0 = 0; k0 < count; k0 += kChunkFrames) {
      const Eigen::Index kn = std::min(kChunkFrames, count - k0);
      // The written frames among these, as (frame, column of `fields`).
      std::vector<std::pair<Eigen::Index, Eigen::Index>> write;
      for (Eigen::Index w = 0; w < Eigen::Index(fields.steps.size()); ++w)
        if (fields.steps[size_t(w)] >= k0 && fields.steps[size_t(w)] < k0 + kn)
          write.emplace_back(fields.steps[size_t(w)], w);
      const Eigen::Index fold_end = std::clamp<Eigen::Index>(folded, k0, k0 + kn);
      if (fold_end == k0 && write.empty()) continue;
      const auto Ck = C.middleCols(k0, kn);
      auto s = fields.tile_stress.topLeftCorner(6 * n, kn);
      auto e = fields.tile_elastic.topLeftCorner(3 * n, kn);
      fem::blas_product(S, Ck, s);
      fem::blas_product(E, Ck, e);
      auto vm = fields.von_mises_tile.head(n);
      auto magnitude = fields.magnitude_tile.head(n);
      auto next_written = write.begin();
      for (Eigen::Index k = k0; k < k0 + kn; ++k) {
        const bool written = next_written != write.end() && next_written->first == k;
        if (k >= fold_end && !written) continue;
        const auto sc = [&](int c) { return s.col(k - k0).segment(c * n, n).array(); };
        const auto ec = [&](int c) { return e.col(k - k0).segment(c * n, n).array(); };
        // fem::von_mises, on the chunk's nodes at once.
        vm = (0.5 * ((sc(0) - sc(1)).square() + (sc(1) - sc(2)).square() + (sc(2) - sc(0)).square()) +
              3.0 * (sc(3).square() + sc(4).square() + sc(5).square()))
                 .sqrt();
        if (k < fold_end) {
          magnitude = (ec(0).square() + ec(1).square() + ec(2).square()).sqrt();
          const std::size_t step = std::size_t(first + k);
          for (Eigen::Index j = 0; j < n; ++j) fold_node(env, i0 + j, step, vm[j], magnitude[j]);
        }
        if (written) {
          const Eigen::Index w = next_written->second;
          fields.von_mises.col(w).segment(i0, n) = vm.matrix();
          for (int c = 0; c < 6; ++c)
            Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<6>>(fields.stress.col(w).data() + 6 * i0 + c, n) =
                sc(c).matrix();
          for (int c = 0; c < 3; ++c)
            Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<3>>(fields.elastic.col(w).data() + 3 * i0 + c, n) =
                ec(c).matrix();
          ++next_written;
        }
      }
    }
  }
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

  // 3. Every frame as a combination, in blocks of frames: the envelope by
  // fuse_block (node chunks, no full fields), the written frames' fields
  // gathered on the way, then per frame in order the support check and the
  // callback. Blocks are as long as about 256 MB of written-field buffers
  // allow (all frames written is the worst case); the buffers are allocated
  // once (fresh ones per block cost more in page faults than the arithmetic).
  const Eigen::Index block = std::clamp<Eigen::Index>(
      Eigen::Index(256e6 / (8.0 * 10.0 * double(std::max<fem::Index>(nodes, 1)))), 1, 512);
  std::vector<char> written(size_t(steps), 0);
  Eigen::Index most_written = 0;
  for (Eigen::Index first = 0; first < steps; first += block) {
    Eigen::Index count = 0;
    for (Eigen::Index k = first; k < std::min(first + block, steps); ++k)
      if (on_step && wants_callback(options, size_t(k))) written[size_t(k)] = 1, ++count;
    most_written = std::max(most_written, count);
  }
  WrittenFields fields;
  fields.stress.resize(6 * nodes, most_written);
  fields.elastic.resize(3 * nodes, most_written);
  fields.von_mises.resize(nodes, most_written);
  Eigen::MatrixXd reactions(reaction_patterns.rows(), block);
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
  const Eigen::Index envelope_end =
      options.envelope_steps == 0 ? steps : std::min<Eigen::Index>(steps, Eigen::Index(options.envelope_steps));
  for (Eigen::Index first = 0; first < steps; first += block) {
    const Eigen::Index count = std::min(block, steps - first);
    const auto C = patterns.coefficients.middleCols(first, count);
    fields.steps.clear();
    for (Eigen::Index k = 0; k < count; ++k)
      if (written[size_t(first + k)]) fields.steps.push_back(k);
    fuse_block(patterns, C, first, envelope_end, fields, env);
    reactions.leftCols(count).noalias() = reaction_patterns * C;
    Eigen::Index w = 0;
    for (Eigen::Index k = 0; k < count; ++k) {
      const std::size_t step = std::size_t(first + k);
      const double load_bound = std::max(C.col(k).cwiseAbs().dot(pattern_load), 1e-300);
      check_support_reaction(env, reactions.col(k).norm() / load_bound, loads.part, loads.times[step], options);
      if (written[step]) {
        const fem::DisplacementField u =
            Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(fields.elastic.col(w).data(), 3, nodes)
                .transpose();
        fem::NodalStress nodal;
        nodal.stress_pa =
            Eigen::Map<const Eigen::Matrix<double, 6, Eigen::Dynamic>>(fields.stress.col(w).data(), 6, nodes)
                .transpose();
        nodal.von_mises_pa = fields.von_mises.col(w);
        on_step(step, u, nodal);
        ++w;
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
