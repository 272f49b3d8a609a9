// Craig-Bampton reduction (vibration/craig_bampton.hpp) of a part of two
// materials (FeModel::set_materials: the solids of a welded part): a clamped
// beam whose outer half is brass, the inner half steel, reduced to its tip
// coupling. Reference: the full FE eigen-solve of the same two-material
// model (stiffness and mass with each element's material); tolerance 1e-4
// relative on the first five frequencies, as test_craig_bampton.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "beam_models.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/vibration/craig_bampton.hpp"

namespace kinetofem::vibration_tests {
namespace {

// The beam of BeamGeometry (steel), clamped at x = 0, its elements beyond
// x = L / 2 in the element set "solid.tip" of brass.
fem::FeModel two_material_beam(const BeamGeometry& g) {
  fem::FeModel model = beam_model(g, fem::ElementType::Hex20, {20, 2, 1}, true);
  fem::Index first = 0;
  for (const auto& block : model.mesh.blocks) {
    for (fem::Index e = 0; e < block.size(); ++e) {
      double x = 0.0;
      for (int k = 0; k < fem::corner_nodes(block.type); ++k)
        x += model.mesh.nodes(block.element(e)[size_t(k)], 0) / fem::corner_nodes(block.type);
      if (x > 0.5 * g.length_m) model.mesh.element_sets["solid.tip"].push_back(first + e);
    }
    first += block.size();
  }
  model.set_materials = {{"solid.tip", fem::IsotropicMaterial{"brass", 100e9, 0.0, 8500.0}}};
  return model;
}

// The first `count` frequencies of the full model, each element of its own material.
Eigen::VectorXd full_frequencies(const fem::FeModel& model, int count) {
  const fem::DofMap dofs(model.mesh.node_count(), model.supports);
  const fem::ElementMaterials materials = fem::element_materials(model);
  fem::EigenOptions options;
  options.modes = count;
  options.label = "full two-material beam";
  const Log log = Log::quiet();
  return fem::solve_generalized_eigen(fem::assemble_stiffness(model.mesh, materials, dofs).free_free,
                                      fem::assemble_mass(model.mesh, materials, dofs), options, nullptr, &log)
      .frequency_hz;
}

TEST(CraigBampton, TwoMaterialPartReproducesItsFullModel) {
  const BeamGeometry g;
  const fem::FeModel model = two_material_beam(g);
  const Eigen::VectorXd full = full_frequencies(model, 5);
  // The brass half moves the frequencies well away from the all-steel
  // beam's, so a reduction with one material could not pass the check below.
  fem::FeModel steel = model;
  steel.set_materials.clear();
  const Eigen::VectorXd all_steel = full_frequencies(steel, 5);
  EXPECT_GT((full.array() / all_steel.array() - 1.0).abs().minCoeff(), 0.05);

  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = full[4];
  options.eigen.label = "two-material beam";
  const vibration::CraigBamptonModel cb = vibration::reduce_craig_bampton(
      model, {vibration::coupling_interface(model.mesh, "x1", {g.length_m, 0.5 * g.depth_m, 0.5 * g.thickness_m}, "tip")},
      options);
  const Eigen::VectorXd reduced = vibration::dense_frequencies_hz(cb.stiffness, cb.mass, 5);
  for (Eigen::Index i = 0; i < full.size(); ++i) {
    std::printf("two-material mode %lld: reduced %.7f Hz, full %.7f Hz (all steel %.7f Hz), error %+.2e\n",
                static_cast<long long>(i + 1), reduced[i], full[i], all_steel[i], reduced[i] / full[i] - 1.0);
    // Reference: the full two-material FE eigen-solve; tolerance 1e-4.
    EXPECT_NEAR(reduced[i] / full[i], 1.0, 1e-4) << "mode " << i + 1;
  }
}

}  // namespace
}  // namespace kinetofem::vibration_tests
