// Cost of the elastic assembly against the per-link analysis on the same
// meshes: the two-link arm of structure_fixtures.hpp with finer bars (HEX20,
// 30 x 4 x 2 cells, ~6 000 DoFs each) over 21 output times of its motion.
// Printed: the assembly's one-off setup (assembly, factorization, the 6m
// interface solves per part) and its time per pose (loads, load solve, dense
// system, field and stress recovery), against loads::analyse_link_over_motion
// (its own factorization, then loads, solves, stress recovery, per part).
// Checked (the model is statically determinate, verification 4): the same
// von Mises fields, 1e-6 of the peak.
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

TEST(ElasticAssemblyCost, FactorizationOnceThenPosesAtThePriceOfThePerLinkAnalysis) {
  const test::TwoLinkArm geometry;
  std::vector<pipeline::Part> parts = test::two_link_parts(geometry);
  for (auto& p : parts) {
    test::BarSize size;
    size.length_m = 0.30;
    size.cells = {30, 4, 2};
    p.model.mesh = test::bar_mesh(size);
    p.mass = fem::mass_properties(p.model.mesh, p.model.material);
  }
  mech::MultibodyModel model = test::two_link_arm(geometry);
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const std::vector<mech::Frame> frames =
      mech::run_kinematics(mech::MultibodySystem(model), mech::equally_spaced_times(0.5, 21)).frames;

  Stopwatch clock;
  ElasticAssembly assembly(parts, model);
  const double setup = clock.seconds();
  clock.restart();
  const std::vector<PoseSolution> poses = assembly.solve(frames);
  const double solve = clock.seconds();
  const AssemblyStatistics& s = assembly.statistics();

  double per_link_total = 0.0, per_link_factorize = 0.0, per_link_steps = 0.0, worst = 0.0;
  for (const pipeline::Part& part : parts) {
    fem::FeModel supported = part.model;
    std::vector<fem::Index> all(size_t(supported.mesh.node_count()));
    for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
    supported.supports = fem::three_two_one_support(supported.mesh, all);
    loads::LinkDefinition def = part.attachments;
    def.model = &supported;
    const loads::LinkLoads link_loads(def, model);
    std::vector<Eigen::VectorXd> vm;
    clock.restart();
    const loads::LinkEnvelope env = loads::analyse_link_over_motion(
        supported, link_loads, frames, Log::quiet(), {},
        [&](std::size_t, const fem::DisplacementField&, const fem::NodalStress& st) { vm.push_back(st.von_mises_pa); });
    per_link_total += clock.seconds();
    per_link_factorize += env.assembly_seconds + env.solver.analyze_seconds + env.solver.factorize_seconds;
    per_link_steps += env.solve_seconds + env.recovery_seconds;
    for (size_t f = 0; f < frames.size(); ++f)
      worst =
          std::max(worst, (poses[f].part(part.body()).von_mises_pa - vm[f]).cwiseAbs().maxCoeff() / vm[f].maxCoeff());
  }
  const double n = double(frames.size());
  std::printf("  %ld DoFs in %d parts, %ld interface columns, %d unknowns in the dense system, %zu poses\n",
              s.part_dofs, s.elastic_parts, s.interface_columns, s.unknowns, frames.size());
  std::printf(
      "  assembly: setup %.3f s (factorization %.3f s), then %.2f ms per pose (loads %.2f, load solve %.2f, "
      "dense system %.2f, recovery %.2f ms)\n",
      setup, s.factorize_seconds, 1e3 * solve / n, 1e3 * s.loads_seconds / n, 1e3 * s.load_solve_seconds / n,
      1e3 * s.system_seconds / n, 1e3 * s.recovery_seconds / n);
  std::printf(
      "  per-link analysis: %.3f s in all, of which assembly + factorization %.3f s; %.2f ms per pose "
      "(all in), solves + recovery %.2f ms per pose\n",
      per_link_total, per_link_factorize, 1e3 * per_link_total / n, 1e3 * per_link_steps / n);
  std::printf("  von Mises, assembly vs per-link: %.2e of the peak\n", worst);
  EXPECT_EQ(s.poses, long(frames.size()));
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace kinetofem::structure
