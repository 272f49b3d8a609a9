// Craig-Bampton reduction of one part (vibration/craig_bampton.hpp) against
// the full FE eigen-solve, with the default part-mode rule (fixed-interface
// modes up to 2 x the highest frequency of interest, f_max = the full model's
// 5th frequency, plus the residual vectors). Reference: the full model's first
// five frequencies; tolerance 1e-4 relative (vibration verification 4's
// tolerance, docs/vibration.md). (c) also prints the error against the cutoff factor with and
// without the residual vectors (the reason for the default).
//
// (a) Supported part, coupling interface: the tip-mass cantilever of
//     test_tip_mass.cpp, clamped at x = 0 as the part's own support; the
//     interface is the tip coupling (6 coordinates), the point mass is added
//     to the reduced mass at those coordinates.
// (b) Free part, clamped through its interface DoFs: the same beam without
//     supports, interfaces = the nodal DoFs of the face x = 0 and the tip
//     coupling; the reduction uses the 3-2-1 support and the rigid modes;
//     in the reduced model the face's coordinates are held (removed), the
//     point mass added at the tip: the full model of (a) again.
// (c) Free part, free-free: the reduced model with no coordinate held has
//     six zero frequencies and the full free-free beam's elastic ones.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "tip_mass_model.hpp"

namespace kinetofem::vibration_tests {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;

// The full clamped model with the tip mass: its first `count` frequencies.
Eigen::VectorXd full_clamped_frequencies(const TipMassBeam& b, int count) {
  const fem::FeModel model = b.model(true);
  const fem::DofMap dofs(model.mesh.node_count(), model.supports);
  const Matrices m = assemble(model, dofs);
  const fem::LowRankMass point = b.point_mass(model, dofs);
  fem::EigenOptions options;
  options.modes = count;
  options.label = "full cantilever + tip mass";
  const Log log;
  return fem::solve_generalized_eigen(m.stiffness, m.mass, options, &point, &log).frequency_hz;
}

// Rows / columns `keep` of a square matrix.
MatrixXd select(const MatrixXd& A, const std::vector<Index>& keep) {
  MatrixXd out(Index(keep.size()), Index(keep.size()));
  for (size_t i = 0; i < keep.size(); ++i)
    for (size_t j = 0; j < keep.size(); ++j) out(Index(i), Index(j)) = A(keep[i], keep[j]);
  return out;
}

void expect_close(const Eigen::VectorXd& reduced, const Eigen::VectorXd& full, const char* what) {
  for (Index i = 0; i < full.size(); ++i) {
    std::printf("%s mode %lld: reduced %.7f Hz, full %.7f Hz, error %+.2e\n", what,
                static_cast<long long>(i + 1), reduced[i], full[i], reduced[i] / full[i] - 1.0);
    // Reference: the full FE eigen-solve; tolerance 1e-4.
    EXPECT_NEAR(reduced[i] / full[i], 1.0, 1e-4) << what << " mode " << i + 1;
  }
}

TEST(CraigBampton, SupportedPartWithCouplingInterfaceReproducesFullModel) {
  const TipMassBeam b;
  const Eigen::VectorXd full = full_clamped_frequencies(b, 5);
  const fem::FeModel model = b.model(true);
  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = full[4];
  options.eigen.label = "cantilever";
  const Log log;
  const vibration::CraigBamptonModel cb =
      vibration::reduce_craig_bampton(model, {b.tip_interface(model)}, options, &log);
  EXPECT_GT(cb.first_dropped_hz, cb.cutoff_hz);
  EXPECT_LT(cb.coupling_stiffness_check, 1e-8);
  EXPECT_LT(cb.constraint_check, 1e-8);
  MatrixXd M = cb.mass;
  M.topLeftCorner(6, 6) += b.tip_mass_matrix();
  expect_close(vibration::dense_frequencies_hz(cb.stiffness, M, 5), full, "(a) supported");
}

TEST(CraigBampton, FreePartClampedThroughItsInterfaceDofsReproducesFullModel) {
  const TipMassBeam b;
  const Eigen::VectorXd full = full_clamped_frequencies(b, 5);
  const fem::FeModel model = b.model(false);
  const vibration::PartInterface root =
      vibration::nodal_interface(model.mesh, model.mesh.node_set("x0"), "root face");
  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = full[4];
  options.eigen.label = "free beam";
  const Log log;
  const vibration::CraigBamptonModel cb =
      vibration::reduce_craig_bampton(model, {root, b.tip_interface(model)}, options, &log);
  EXPECT_TRUE(cb.free_body);
  EXPECT_GT(cb.first_dropped_hz, cb.cutoff_hz);
  EXPECT_LT(cb.constraint_check, 1e-8);
  // Hold the root face's coordinates, add the tip mass.
  const Index nb_root = root.columns.cols();
  std::vector<Index> keep;
  for (Index i = nb_root; i < cb.stiffness.rows(); ++i) keep.push_back(i);
  MatrixXd M = cb.mass;
  M.block(nb_root, nb_root, 6, 6) += b.tip_mass_matrix();
  expect_close(vibration::dense_frequencies_hz(select(cb.stiffness, keep), select(M, keep), 5),
               full, "(b) clamped through the interface");
}

TEST(CraigBampton, FreePartFreeFreeReproducesFullModel) {
  TipMassBeam b;
  b.divisions = {25, 2, 1};  // the free-free check needs no fine mesh
  const fem::FeModel model = b.model(false);
  const fem::DofMap dofs(model.mesh.node_count(), {});
  const Matrices m = assemble(model, dofs);
  fem::EigenOptions eig;
  eig.modes = 11;
  eig.shift_rad2_s2 = -std::pow(2.0 * std::numbers::pi * 30.0, 2);  // first elastic ~106 Hz
  eig.label = "full free-free beam";
  const Log log;
  const Eigen::VectorXd full =
      fem::solve_generalized_eigen(m.stiffness, m.mass, eig, nullptr, &log).frequency_hz;
  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = full[10];
  options.eigen.label = "free-free beam";
  const vibration::CraigBamptonModel cb = vibration::reduce_craig_bampton(
      model,
      {vibration::coupling_interface(model.mesh, "x0", {0.0, 0.02, 0.01}, "root"),
       b.tip_interface(model)},
      options, &log);
  for (double factor : {2.0, 8.0}) {
   for (bool residual : {false, true}) {
    vibration::CraigBamptonOptions o = options;
    o.cutoff_factor = factor;
    o.residual_vectors = residual;
    const vibration::CraigBamptonModel r = vibration::reduce_craig_bampton(
        model,
        {vibration::coupling_interface(model.mesh, "x0", {0.0, 0.02, 0.01}, "root"),
         b.tip_interface(model)},
        o);
    const Eigen::VectorXd f = vibration::dense_frequencies_hz(r.stiffness, r.mass, 11);
    std::printf("(c) cutoff factor %4.1f%s: %lld fixed-interface modes, max error of elastic modes "
                "1-5 %.2e\n",
                factor, residual ? " + residual vectors" : "", static_cast<long long>(r.mode_count),
                (f.tail(5).array() / full.tail(5).array() - 1.0).abs().maxCoeff());
   }
  }
  const Eigen::VectorXd reduced = vibration::dense_frequencies_hz(cb.stiffness, cb.mass, 11);
  for (Index i = 0; i < 6; ++i) {
    std::printf("(c) rigid mode %lld: reduced %.3e Hz, full %.3e Hz\n",
                static_cast<long long>(i + 1), reduced[i], full[i]);
    // Reference: zero; "numerically zero": below 1e-4 of the first elastic.
    EXPECT_LT(std::abs(reduced[i]), 1e-4 * full[6]);
  }
  expect_close(reduced.tail(5), full.tail(5), "(c) free-free elastic");
}

TEST(CraigBampton, SharesTheStressStagesFactorization) {
  // (d) The free beam of (c) reduced through a LinearStaticAnalysis with its
  // 3-2-1 support (what pipeline::SupportedPart holds) against the reduction
  // with its own factorization. Reference: the own-factorization model's
  // first eleven frequencies; tolerance 1e-9 relative on the elastic ones
  // (the same subspace up to round-off), 1e-4 of the first elastic on the
  // rigid ones.
  TipMassBeam b;
  b.divisions = {25, 2, 1};
  const fem::FeModel model = b.model(false);
  fem::FeModel supported = model;
  std::vector<fem::Index> all(size_t(model.mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
  supported.supports = fem::three_two_one_support(model.mesh, all);
  const Log quiet = Log::quiet();
  fem::LinearStaticAnalysis analysis(supported, quiet);
  const std::vector<vibration::PartInterface> interfaces = {
      vibration::coupling_interface(model.mesh, "x0", {0.0, 0.02, 0.01}, "root"),
      b.tip_interface(model)};
  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = 600.0;
  options.eigen.label = "free beam (shared factorization)";
  const Log log;
  const vibration::CraigBamptonModel shared =
      vibration::reduce_craig_bampton(analysis, interfaces, options, &log);
  options.eigen.label = "free beam (own factorization)";
  const vibration::CraigBamptonModel own = vibration::reduce_craig_bampton(model, interfaces, options);
  ASSERT_EQ(shared.mode_count, own.mode_count);
  const Eigen::VectorXd fs = vibration::dense_frequencies_hz(shared.stiffness, shared.mass, 11);
  const Eigen::VectorXd fo = vibration::dense_frequencies_hz(own.stiffness, own.mass, 11);
  for (Index i = 0; i < 11; ++i) {
    std::printf("(d) mode %lld: shared %.10g Hz, own %.10g Hz\n", static_cast<long long>(i + 1),
                fs[i], fo[i]);
    if (i < 6)
      EXPECT_LT(std::abs(fs[i]), 1e-4 * fo[6]);
    else
      EXPECT_NEAR(fs[i] / fo[i], 1.0, 1e-9);
  }
  // A support that is not 3-2-1 is refused.
  fem::FeModel clamped = model;
  clamped.supports = {{"clamp", model.mesh.node_set("x0")}};
  fem::LinearStaticAnalysis clamped_analysis(clamped, quiet);
  EXPECT_THROW(vibration::reduce_craig_bampton(clamped_analysis, interfaces, options), Error);
}

TEST(CraigBampton, BadInputsAreErrors) {
  const TipMassBeam b;
  const fem::FeModel model = b.model(true);
  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = 0.0;
  EXPECT_THROW(vibration::reduce_craig_bampton(model, {b.tip_interface(model)}, options), Error);
  options.highest_frequency_of_interest_hz = 100.0;
  options.cutoff_factor = 0.5;
  EXPECT_THROW(vibration::reduce_craig_bampton(model, {b.tip_interface(model)}, options), Error);
  options.cutoff_factor = 4.0;
  fem::FeModel massless = model;
  massless.material.density_kg_m3 = 0.0;
  options.eigen.label = "link 1";
  try {
    vibration::reduce_craig_bampton(massless, {b.tip_interface(massless)}, options);
    FAIL() << "zero density accepted";
  } catch (const Error& e) {
    std::printf("zero density: %s\n", e.what());
    EXPECT_NE(std::string(e.what()).find("'link 1'"), std::string::npos);
  }
  // A free part held by one node: its rigid rotation is not held.
  fem::FeModel free = b.model(false);
  try {
    vibration::reduce_craig_bampton(free, {vibration::nodal_interface(free.mesh, {0}, "one node")},
                                    options);
    FAIL() << "one node held a free body";
  } catch (const Error& e) {
    std::printf("one-node interface: %s\n", e.what());
  }
}

}  // namespace
}  // namespace kinetofem::vibration_tests
