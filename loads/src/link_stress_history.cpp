#include "kinetofem/loads/link_stress_history.hpp"

#include "kinetofem/solver/rigid_body.hpp"

#include <algorithm>

#include "kinetofem/core/error.hpp"
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

LinkEnvelope analyse_link_over_motion(fem::LinearStaticAnalysis& analysis, const LinkLoads& loads,
                                      const std::vector<mech::Frame>& frames, const Log& log,
                                      const LinkStressOptions& options, const StepCallback& on_step) {
  require(!frames.empty(), "link '{}': no output times to analyse", loads.body());
  const fem::FeModel& model = analysis.model();
  const fem::Index nodes = model.mesh.node_count();
  std::vector<fem::Index> supported;
  for (const auto& s : model.supports) supported.insert(supported.end(), s.nodes.begin(), s.nodes.end());

  LinkEnvelope env;
  env.max_von_mises_pa = Eigen::VectorXd::Constant(nodes, -1.0);
  env.max_von_mises_step = Eigen::VectorXi::Zero(nodes);
  env.max_displacement_m = Eigen::VectorXd::Constant(nodes, -1.0);
  env.max_displacement_step = Eigen::VectorXi::Zero(nodes);

  Stopwatch clock;
  env.assembly_seconds = analysis.timings().assembly_seconds;

  Progress progress(log, fmt::format("link '{}' time steps", loads.body()), long(frames.size()));
  const std::size_t block = std::size_t(std::max(1, options.block_size));
  for (std::size_t first = 0; first < frames.size(); first += block) {
    const std::size_t count = std::min(block, frames.size() - first);
    Eigen::MatrixXd F(3 * nodes, Eigen::Index(count));
    for (std::size_t k = 0; k < count; ++k) {
      const LinkLoadResult r = loads.loads_at(frames[first + k]);
      env.worst_equilibrium_residual = std::max(env.worst_equilibrium_residual, r.equilibrium_residual);
      env.max_out_of_plane_moment_nm = std::max(env.max_out_of_plane_moment_nm, r.out_of_plane_moment_nm);
      F.col(Eigen::Index(k)) = r.forces;
    }
    clock.restart();
    const auto displacements = analysis.solve_forces(F);
    env.solve_seconds += clock.seconds();
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t step = first + k;
      const fem::DisplacementField& u = displacements[k];
      const Eigen::VectorXd f = F.col(Eigen::Index(k));
      // Reactions of the determinate support: (K u - f) at its six DoFs.
      const Eigen::VectorXd reaction = analysis.reactions_at(u, f, supported);
      // Relative to the total load the link carries (sum of the nodal force
      // magnitudes): the reactions come out of K u - f, so they carry the
      // solve's round-off amplified by the condition of K.
      const double load_scale =
          std::max(Eigen::Map<const Eigen::Matrix<double, 3, Eigen::Dynamic>>(f.data(), 3, nodes)
                       .colwise()
                       .norm()
                       .sum(),
                   1e-300);
      const double relative = reaction.norm() / load_scale;
      env.worst_support_reaction = std::max(env.worst_support_reaction, relative);
      if (!(relative <= options.reaction_tolerance))
        fail("link '{}' at t = {:.6g} s: the 3-2-1 support carries {:.2e} of the link's total "
             "load; the loads are not self-equilibrated",
             loads.body(), frames[step].t, relative);
      clock.restart();
      const fem::NodalStress stress = fem::recover_nodal_stress(model.mesh, model.material, u);
      // Deformation measure: the elastic displacement without the rigid-body
      // part the 3-2-1 support's arbitrary nodes put into it (computed once:
      // the callback gets the same field).
      const fem::DisplacementField elastic = fem::remove_rigid_body_motion(model.mesh, u);
      const Eigen::VectorXd magnitude = fem::displacement_magnitude(elastic);
      const bool in_envelope = options.envelope_steps == 0 || step < options.envelope_steps;
      for (fem::Index i = 0; in_envelope && i < nodes; ++i) {
        if (stress.von_mises_pa[i] > env.max_von_mises_pa[i]) {
          env.max_von_mises_pa[i] = stress.von_mises_pa[i];
          env.max_von_mises_step[i] = int(step);
        }
        if (magnitude[i] > env.max_displacement_m[i]) {
          env.max_displacement_m[i] = magnitude[i];
          env.max_displacement_step[i] = int(step);
        }
      }
      env.recovery_seconds += clock.seconds();
      if (on_step) on_step(step, elastic, stress);
      progress.advance(long(step + 1));
    }
  }
  progress.finish();
  env.peak_von_mises_pa = env.max_von_mises_pa.maxCoeff(&env.peak_von_mises_node);
  env.peak_von_mises_step = env.max_von_mises_step[env.peak_von_mises_node];
  env.peak_displacement_m = env.max_displacement_m.maxCoeff(&env.peak_displacement_node);
  env.peak_displacement_step = env.max_displacement_step[env.peak_displacement_node];
  env.solver = analysis.solver_statistics();
  env.iterative_solver = analysis.uses_iterative_solver();
  env.solver_summary = analysis.solver_summary();
  return env;
}

}  // namespace kinetofem::loads
