// The linear solve path of the static analysis: CHOLMOD against an
// independent sparse factorization, singular models, inverted elements and
// block solves of many load cases.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/verification/box_mesh.hpp"
#include "kinetofem/verification/direct_solvers.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;

const Eigen::Vector3d beam_length(0.6, 0.15, 0.1);

FeModel clamped_beam(ElementType type, std::array<int, 3> divisions) {
  FeModel model;
  kv::BoxMeshOptions options;
  options.length_m = beam_length;
  options.divisions = divisions;
  options.type = type;
  options.random_perturbation = 0.15;
  options.seed = 3;
  model.mesh = kv::box_mesh(options);
  model.material = IsotropicMaterial{"steel", 210e9, 0.3, 7850.0};
  model.supports = {{"clamp", model.mesh.node_set("x0"), {true, true, true},
                     Eigen::Vector3d::Zero()}};
  return model;
}

LoadCase mixed_load() {
  LoadCase load;
  load.tractions = {{"x1", Eigen::Vector3d(1e6, -3e6, 2e6)}, {"y1", Eigen::Vector3d(0, 0, -5e5)}};
  load.pressures = {{"z1", 2e5}};
  load.gravity_m_s2 = Eigen::Vector3d(0, -9.81, 0);
  return load;
}

bool all_finite(const DisplacementField& u) { return u.allFinite(); }

TEST(LinearSolver, CholmodAgreesWithEigenSimplicialLdlt) {
  // The comparison of `kinetofem verify` fem.cholmod_vs_ldlt
  // (kinetofem/verification/direct_solvers.hpp), here on a clamped beam; an
  // LDLT failure is an Error.
  const kv::DirectSolverComparison c =
      kv::compare_cholmod_with_ldlt(clamped_beam(ElementType::Hex20, {8, 3, 2}), mixed_load());
  // Reference: Eigen's SimplicialLDLT on the same K_ff and load; 1e-10 relative.
  EXPECT_LT(c.relative_difference, kv::kDirectSolverTolerance);
  // Both solve the system itself (relative residual, round-off level).
  EXPECT_LT(c.relative_residual, 1e-10);
  EXPECT_GT(c.factor_nonzeros, c.matrix_nonzeros);
}

// Runs the analysis; a singular model must end in an Error, never in a
// displacement with NaN or Inf.
void expect_singular_model_error(const FeModel& model) {
  const Log log = Log::quiet();
  try {
    LinearStaticAnalysis analysis(model, log);
    const auto u = analysis.solve({mixed_load()});
    ADD_FAILURE() << "singular model solved without an Error; displacement finite: "
                  << all_finite(u.at(0));
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("not positive definite"));
  }
}

TEST(LinearSolver, UnsupportedModelIsAnError) {
  FeModel model = clamped_beam(ElementType::Hex8, {6, 2, 2});
  model.supports.clear();
  expect_singular_model_error(model);
}

TEST(LinearSolver, SupportsInOneDirectionOnlyAreAnError) {
  FeModel model = clamped_beam(ElementType::Tet10, {4, 2, 2});
  model.supports[0].fixed = {true, false, false};  // y, z translations and x rotation left
  expect_singular_model_error(model);
}

TEST(LinearSolver, InvertedElementIsNamed) {
  FeModel model = clamped_beam(ElementType::Hex8, {5, 5, 5});
  // Turn element 93 inside out: swap its bottom (0-3) and top (4-7) corners.
  auto& c = model.mesh.blocks[0].connectivity;
  for (int k = 0; k < 4; ++k) std::swap(c[93 * 8 + k], c[93 * 8 + 4 + k]);
  try {
    check_element_jacobians(model.mesh);
    ADD_FAILURE() << "check_element_jacobians accepted an inverted element";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("element 93 (HEX8)"));
  }
  const DofMap dofs(model.mesh.node_count(), model.supports);
  try {
    assemble_stiffness(model.mesh, model.material, dofs);
    ADD_FAILURE() << "assemble_stiffness accepted an inverted element";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("element 93 (HEX8)"));
  }
  const Log log = Log::quiet();
  EXPECT_THROW(LinearStaticAnalysis(model, log), Error);
}

TEST(LinearSolver, InvertedTet10IsNamed) {
  FeModel model = clamped_beam(ElementType::Tet10, {3, 2, 2});
  // Mirror element 41: swap corners 1 and 2 with their mid-edge nodes
  // (0-1 <-> 2-0, 3-1 <-> 3-2), a valid TET10 of negative volume.
  auto& c = model.mesh.blocks[0].connectivity;
  const size_t e = 41 * 10;
  std::swap(c[e + 1], c[e + 2]);
  std::swap(c[e + 4], c[e + 6]);
  std::swap(c[e + 8], c[e + 9]);
  try {
    check_element_jacobians(model.mesh);
    ADD_FAILURE() << "check_element_jacobians accepted an inverted element";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("element 41 (TET10)"));
  }
}

TEST(LinearSolver, BlockSolveEqualsSeparateSolves) {
  const FeModel model = clamped_beam(ElementType::Tet10, {6, 2, 2});
  // 24 load cases: the mixed load scaled and rotated, plus nodal forces.
  std::vector<LoadCase> cases;
  for (int k = 0; k < 24; ++k) {
    LoadCase load = mixed_load();
    load.name = fmt::format("case {}", k);
    const double s = 1.0 + 0.1 * k;
    for (auto& t : load.tractions) t.traction_pa = s * Eigen::Vector3d(t.traction_pa[(k) % 3],
                                                                        t.traction_pa[(k + 1) % 3],
                                                                        t.traction_pa[(k + 2) % 3]);
    load.pressures[0].pressure_pa *= (k % 2 ? -1.0 : 1.0);
    load.nodal_forces = {{Index(k * 7 % model.mesh.node_count()), Eigen::Vector3d(1e3, -k, 5)}};
    cases.push_back(std::move(load));
  }
  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const auto block = analysis.solve(cases);
  ASSERT_EQ(block.size(), cases.size());
  for (size_t k = 0; k < cases.size(); ++k) {
    const auto single = analysis.solve({cases[k]}).at(0);
    // Reference: the separate solve of the same case; 1e-12 relative (the
    // same factor, so only summation order can differ).
    EXPECT_LT((block[k] - single).norm() / single.norm(), 1e-12) << cases[k].name;
  }
}


TEST(LinearSolver, AReleasedFactorIsMadeAgainBitForBit) {
  // The pipeline frees a part's factor after its last solve when the parts'
  // factors do not fit in memory together (LinearStaticAnalysis::release_factor).
  const FeModel model = clamped_beam(ElementType::Tet10, {6, 2, 2});
  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const DisplacementField first = analysis.solve({mixed_load()}).at(0);
  const CholmodStatistics before = analysis.solver_statistics();
  analysis.release_factor();
  EXPECT_FALSE(analysis.is_factorized());
  try {
    analysis.solve({mixed_load()});
    ADD_FAILURE() << "a solve after release_factor ran without an Error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), ::testing::HasSubstr("not factorized"));
  }
  analysis.release_factor();  // twice: a no-op
  analysis.factorize();
  ASSERT_TRUE(analysis.is_factorized());
  const DisplacementField again = analysis.solve({mixed_load()}).at(0);
  // Reference: the first factor. Same symbolic analysis and arithmetic: equal
  // bit for bit, and the same statistics.
  EXPECT_EQ((again - first).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(analysis.solver_statistics().factor_nonzeros, before.factor_nonzeros);
  EXPECT_EQ(analysis.solver_statistics().factorization_flops, before.factorization_flops);
  EXPECT_EQ(analysis.solver_statistics().reciprocal_condition, before.reciprocal_condition);
}

}  // namespace
}  // namespace kinetofem::fem
