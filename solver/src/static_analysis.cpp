#include "kinetofem/solver/static_analysis.hpp"

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/node_graph_ordering.hpp"

namespace kinetofem::fem {

LinearStaticAnalysis::LinearStaticAnalysis(const FeModel& model, const Log& log,
                                           CholmodOptions options)
    : LinearStaticAnalysis(model, log,
                           StaticSolverOptions{LinearSolverMethod::Direct, options, AmgOptions{}}) {}

LinearStaticAnalysis::LinearStaticAnalysis(const FeModel& model, const Log& log,
                                           const StaticSolverOptions& options)
    : model_(model),
      log_(log),
      materials_((model.mesh.validate(), element_materials(model))),
      dofs_(model.mesh.node_count(), model.supports),
      solver_(options.direct, &log) {
  const Mesh& mesh = model.mesh;
  log_.detail("  FE model: {} nodes, {} elements, {} DoFs ({} free, {} prescribed)",
            mesh.node_count(), mesh.element_count(), dofs_.dof_count(), dofs_.free_count(),
            dofs_.prescribed_count());
  require(dofs_.free_count() > 0, "FE model has no free DoFs: every node is supported");
  Stopwatch clock;
  check_element_jacobians(mesh);
  stiffness_ = assemble_stiffness(mesh, materials_, dofs_);
  timings_.assembly_seconds = clock.seconds();
  log_.detail("  assembly: {:.2f} s", timings_.assembly_seconds);

  // Choice of the linear solver. Direct and Auto first run CHOLMOD's symbolic
  // analysis, which predicts the factor's size before any numeric work.
  bool iterative = options.method == LinearSolverMethod::Iterative;
  if (!iterative) {
    try {
      if (options.direct.ordering == CholmodOptions::Ordering::NodeGraphMetis) {
        // METIS on the node graph (node_graph_ordering.hpp): about the fill of
        // CHOLMOD's METIS on the DoF graph (+2 %), a 1.6-2x faster analysis.
        NodeGraphOrderingTimes t;
        const GivenOrdering ordering = node_graph_ordering(mesh, dofs_, &t);
        log_.detail("  ordering: METIS on the node graph, graph {:.3f} s, METIS_NodeND {:.3f} s",
                  t.graph_seconds, t.metis_seconds);
        solver_.analyze(stiffness_.free_free, ordering);
      } else {
        solver_.analyze(stiffness_.free_free);
      }
    } catch (const Error& error) {
      // analyze() fills its statistics before it compares the predicted factor
      // with the limit, so filled statistics mean the limit was the reason;
      // any other failure (CHOLMOD itself) is not a reason to switch.
      const CholmodStatistics& predicted = solver_.statistics();
      const bool too_large = predicted.equations == stiffness_.free_free.rows() &&
                             predicted.factor_bytes > 0.0;
      if (options.method == LinearSolverMethod::Direct || !too_large) throw;
      log_.info("  solver: iterative (AMG-preconditioned CG), because {}", error.what());
      iterative = true;
    }
    if (!iterative && options.method == LinearSolverMethod::Auto)
      log_.detail("  solver: direct (CHOLMOD), the factor fits the memory limit");
  }
  if (iterative) {
    amg_ = std::make_unique<AmgSolver>(options.iterative, &log);
    amg_->setup(stiffness_.free_free, mesh.nodes, dofs_);
    return;
  }
  if (!options.defer_factorization) factorize_direct();
}

void LinearStaticAnalysis::factorize() {
  if (!is_factorized()) factorize_direct();
}

void LinearStaticAnalysis::release_factor() {
  if (amg_) return;
  solver_.release_factor();
  factorized_ = false;
}

void LinearStaticAnalysis::factorize_direct() {
  try {
    solver_.factorize(stiffness_.free_free);
    factorized_ = true;
  } catch (const NotPositiveDefinite& error) {
    // The commonest cause, worth naming: a direction no support holds at all
    // (the whole model can translate along it).
    std::string free_directions;
    for (int c = 0; c < 3; ++c) {
      bool held = false;
      for (const auto& support : model_.supports) held = held || (support.fixed[c] && !support.nodes.empty());
      if (!held) free_directions += std::string(free_directions.empty() ? "" : ", ") + "xyz"[c];
    }
    // No equation: the factorization went through on round-off pivots and
    // only the condition estimate caught it (which of the two happens
    // depends on the CPU's BLAS kernels); the free directions still name it.
    if (error.equation() < 0) {
      if (free_directions.empty()) throw;
      fail("{}: no support fixes displacements along {}, so the model can move freely", error.what(),
           free_directions);
    }
    // Name the node and direction of the equation where the factorization failed.
    Index dof = -1;
    for (Index d = 0; d < dofs_.dof_count(); ++d)
      if (dofs_.equation(d) == error.equation()) dof = d;
    const std::string cause =
        free_directions.empty()
            ? std::string("the model has a rigid-body mode left unsupported or an element without stiffness")
            : fmt::format("no support fixes displacements along {}, so the model can move freely "
                          "(a rigid-body mode left unsupported)",
                          free_directions);
    fail("stiffness matrix is not positive definite at node {} direction {} (equation {}): {}",
         dof / 3, "xyz"[dof % 3], error.equation(), cause);
  }
}

std::vector<DisplacementField> LinearStaticAnalysis::solve(const std::vector<LoadCase>& load_cases) {
  Stopwatch clock;
  const Eigen::MatrixXd F = assemble_external_forces(model_.mesh, materials_, load_cases);
  timings_.load_assembly_seconds = clock.seconds();
  return solve_forces(F);
}

std::string LinearStaticAnalysis::solver_summary() const {
  if (amg_) {
    const AmgStatistics& st = amg_->statistics();
    return fmt::format("AMG-PCG (hypre): {} levels, operator complexity {:.2f}, set-up {:.2f} s, "
                       "{} right-hand side{}, at most {} iterations, {:.2f} s of solves",
                       st.levels, st.operator_complexity, st.setup_seconds, st.total_rhs,
                       st.total_rhs == 1 ? "" : "s", st.max_iterations(), st.total_solve_seconds);
  }
  const CholmodStatistics& st = solver_.statistics();
  return fmt::format("CHOLMOD: nnz(L) {:.4g}, {:.3g} flops, factorization {:.2f} s ({:.1f} GFLOP/s)",
                     st.factor_nonzeros, st.factorization_flops, st.factorize_seconds,
                     st.factorize_gflops());
}

std::vector<DisplacementField> LinearStaticAnalysis::solve_forces(
    const Eigen::MatrixXd& external_forces) {
  require(external_forces.rows() == dofs_.dof_count(),
          "external force block has {} rows, the model {} DoFs", external_forces.rows(),
          dofs_.dof_count());
  const Index cases = external_forces.cols();
  Eigen::MatrixXd rhs(dofs_.free_count(), cases);
  for (Index d = 0; d < dofs_.dof_count(); ++d) {
    const Index eq = dofs_.equation(d);
    if (eq >= 0) rhs.row(eq) = external_forces.row(d);
  }
  rhs.colwise() -= stiffness_.prescribed_coupling_force;
  require(is_factorized(), "the stiffness is analysed but not factorized: call factorize() before solving");
  const Eigen::MatrixXd x = amg_ ? amg_->solve(rhs) : solver_.solve(rhs);
  std::vector<DisplacementField> out;
  out.reserve(size_t(cases));
  for (Index k = 0; k < cases; ++k) {
    const Eigen::VectorXd full = dofs_.expand(x.col(k));
    out.push_back(Eigen::Map<const DisplacementField>(full.data(), model_.mesh.node_count(), 3));
  }
  return out;
}

Eigen::VectorXd LinearStaticAnalysis::reactions(const DisplacementField& displacement,
                                                const Eigen::VectorXd& external_force) const {
  Eigen::VectorXd r = internal_forces(model_.mesh, materials_, displacement) - external_force;
  for (Index d = 0; d < dofs_.dof_count(); ++d)
    if (dofs_.equation(d) >= 0) r[d] = 0.0;
  return r;
}

Eigen::VectorXd LinearStaticAnalysis::reactions_at(const DisplacementField& displacement,
                                                   const Eigen::VectorXd& external_force,
                                                   const std::vector<Index>& nodes) const {
  Eigen::VectorXd r = internal_forces_at(model_.mesh, materials_, displacement, nodes);
  for (size_t k = 0; k < nodes.size(); ++k)
    r.segment<3>(3 * Index(k)) -= external_force.segment<3>(3 * nodes[k]);
  return r;
}

}  // namespace kinetofem::fem
