// The assembly's modes with a frame part: the ground carries an FE column
// held at its foot (structure::Part::held_face), reduced by Craig-Bampton
// with its foundation fixed and no rigid-body modes
// (vibration::reduce_held_craig_bampton), its top bore tied to the moving
// bodies through the ground joint and drive like the assembly's statics.
//
// 1. A column (L x h x t, HEX20) held on its foot y0; on its top bore a rigid
//    link of mass m (centre of mass on the pin, almost no rotary inertia)
//    pinned and held by a rigid drive: a cantilever with a tip mass.
//    References:
//    (a) a direct eigen-solve of the same held FE column with the link's
//        6 x 6 rigid mass on the coupling of its top bore (Lanczos on the
//        full model, fem::solve_generalized_eigen): the first three
//        frequencies within 1e-6 relative (the reduction with its residual
//        vectors and a cutoff well above them reproduces the full model to
//        round-off of the two eigen solves);
//    (b) Euler-Bernoulli with Rayleigh's effective tip mass, per bending plane
//        f = (1/2pi) sqrt(3 E I / (L^3 (m + 0.2357 m_beam))): the first two
//        frequencies (bending out of the plane, about x; in the plane, about
//        z) within 1.5 % (what this approximation leaves out: shear
//        deformation, about 0.5 % of the stiffness at L / h = 12; the clamped
//        foot also holding the Poisson contraction, measured 0.5 % stiffer in
//        the statics' column test; Rayleigh's mass 0.2357 m_beam, exact to
//        0.1 % at m = 5 m_beam).
// 2. The two-link arm of structure_fixtures.hpp on the column (its ground pin
//    J1 and drive d1 on the column's top bore) in motion: the reduced model's
//    static response to the pose's loads equals the elastic assembly's own
//    static solution at the tracked point (the vibration stage's
//    "reduced-statics check") within 1e-6 of it.
// 3. reduce_held_craig_bampton on a clamped beam's factorized analysis equals
//    reduce_craig_bampton of the same supported model with its own
//    factorization (the same algorithm, other solves): fixed-interface
//    frequencies and the boundary blocks of K_r and M_r within 1e-9
//    (round-off of two factorizations and two Lanczos runs); an analysis
//    without supports is an Error naming the part.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"
#include "tip_mass_model.hpp"

namespace kinetofem::structure {
namespace {

using Eigen::Index;
using Eigen::MatrixXd;
using Eigen::VectorXd;

struct ColumnWithTipMass {
  double L = 0.6, h = 0.05, t = 0.04;  // m: length, depth along x (in the plane), thickness along z
  double m = 0.0;                      // kg, the link (5 x the column's)
  double J = 1e-6;                     // kg m^2, the link's I_zz (about its centre of mass, on the pin)
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;

  ColumnWithTipMass() {
    parts = {test::held_column_part({"frame", nullptr, {{"A", "y1"}}, {}, {{"d", "y1"}}}, L, h, t, {4, 24, 3}, 0.0)};
    m = 5.0 * parts[0].mass.mass_kg;
    model.name = "column with a tip mass";
    model.characteristic_length_m = L;
    mech::Body frame;
    frame.name = "frame";
    frame.fixed = true;
    frame.points["top"] = {0.0, L};
    mech::Body link;
    link.name = "link";
    link.mass_kg = m;
    link.inertia_kgm2 = J;
    link.pose = {0.0, L, 0.0};
    model.bodies = {frame, link};
    model.joints.push_back(mech::make_revolute("A", "frame", "top", "link", "origin"));
    mech::MotionDrive d;
    d.name = "d";
    d.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "link", "origin", {1, 0}};
    d.law = std::make_shared<mech::Polynomial345Law>(0.0, 1.0);  // held at its initial angle
    model.motion_drives = {d};
  }
};

// The held column's full model with the link's rigid mass on its top coupling:
// the lowest `count` frequencies.
VectorXd full_frequencies(const ColumnWithTipMass& c, const ElasticAssembly& assembly, int count) {
  const pipeline::Part& column = c.parts[0];
  const fem::DofMap dofs(column.model.mesh.node_count(), foundation_support(column));
  const fem::SymmetricUpperMatrix K =
      fem::assemble_stiffness(column.model.mesh, column.model.material, dofs).free_free;
  const fem::SymmetricUpperMatrix M = fem::assemble_mass(column.model.mesh, column.model.material, dofs);
  // The pin A's coupling on y1 (reference (0, L, 0): the link's origin, so the
  // link's 6 coordinates are the coupling's; the rigid drive ties the
  // rotation about z that the pin leaves free).
  const MatrixXd G = assembly.interface_columns("frame").leftCols(6);
  fem::LowRankMass link{MatrixXd::Zero(dofs.free_count(), 6), MatrixXd::Zero(6, 6)};
  for (Index d = 0; d < dofs.dof_count(); ++d)
    if (const Index eq = dofs.equation(d); eq >= 0) link.basis.row(eq) = G.row(d);
  Eigen::Matrix<double, 6, 1> diag;
  diag << c.m, c.m, c.m, 0.5 * c.J, 0.5 * c.J, c.J;  // AssemblyModes: I_xx = I_yy = I_zz / 2
  link.mass = diag.asDiagonal();
  fem::EigenOptions options;
  options.modes = count;
  options.label = "held column + link (full)";
  return fem::solve_generalized_eigen(K, M, options, &link).frequency_hz;
}

TEST(AssemblyModesFramePart, ColumnWithTipMassMatchesTheFullHeldModelAndBeamTheory) {
  const ColumnWithTipMass c;
  const mech::Frame pose = mech::run_kinematics(mech::MultibodySystem(c.model), {0.0}).frames.front();
  AssemblyOptions ao;
  ao.recover_stress = false;
  const ElasticAssembly assembly(c.parts, c.model, ao);
  const VectorXd full = full_frequencies(c, assembly, 3);

  // (a) The reduction against the full model, the cutoff at 4 x the third
  // frequency (the residual vectors make the error fall like (f / cutoff)^4).
  vibration::AssemblyModesOptions mo;
  mo.modes = 3;
  mo.part_mode_cutoff_hz = 4.0 * full(2);
  const vibration::AssemblyModes modes(assembly, c.parts, c.model, mo, {pose}, Log::quiet());
  const vibration::PoseModes reduced = modes.modes(pose);
  ASSERT_EQ(modes.reductions().size(), 1u);
  const vibration::PartReduction& r = modes.reductions()[0];
  std::printf("  held column: %lld free DoFs -> %ld boundary + %ld fixed-interface modes + %ld residual vectors\n",
              r.dofs, long(r.boundary), long(r.modes), long(r.residual));
  EXPECT_EQ(r.dofs, 3 * c.parts[0].model.mesh.node_count() -
                        3 * Index(fem::nodes_of_faces(c.parts[0].model.mesh.face_set("y0")).size()));
  for (int i = 0; i < 3; ++i) {
    const double error = reduced.frequency_hz(i) / full(i) - 1;
    std::printf("  mode %d: reduced %.8f Hz, full held model %.8f Hz (%+.2e)\n", i + 1, reduced.frequency_hz(i),
                full(i), error);
    EXPECT_NEAR(error, 0.0, 1e-6) << "mode " << i + 1;
  }
  // The default rule (automatic cutoff 2 x f_max): 1e-4, the assemblies' requirement.
  vibration::AssemblyModesOptions automatic;
  automatic.modes = 3;
  const vibration::PoseModes by_rule =
      vibration::AssemblyModes(assembly, c.parts, c.model, automatic, {pose}, Log::quiet()).modes(pose);
  for (int i = 0; i < 3; ++i) {
    std::printf("  mode %d, default rule: %.8f Hz (%+.2e)\n", i + 1, by_rule.frequency_hz(i),
                by_rule.frequency_hz(i) / full(i) - 1);
    EXPECT_NEAR(by_rule.frequency_hz(i) / full(i), 1.0, 1e-4) << "mode " << i + 1;
  }

  // (b) Euler-Bernoulli with Rayleigh's tip mass.
  const fem::IsotropicMaterial& mat = c.parts[0].model.material;
  const double m_beam = c.parts[0].mass.mass_kg;
  auto rayleigh = [&](double I) {
    return std::sqrt(3 * mat.youngs_modulus_pa * I / (c.L * c.L * c.L * (c.m + 0.2357 * m_beam))) /
           (2 * std::numbers::pi);
  };
  const double out_of_plane = rayleigh(c.h * c.t * c.t * c.t / 12), in_plane = rayleigh(c.t * c.h * c.h * c.h / 12);
  std::printf("  Rayleigh: out of the plane %.5f Hz (%+.3f %%), in the plane %.5f Hz (%+.3f %%)\n", out_of_plane,
              100 * (reduced.frequency_hz(0) / out_of_plane - 1), in_plane,
              100 * (reduced.frequency_hz(1) / in_plane - 1));
  EXPECT_NEAR(reduced.frequency_hz(0), out_of_plane, 0.015 * out_of_plane);
  EXPECT_NEAR(reduced.frequency_hz(1), in_plane, 0.015 * in_plane);
}

TEST(AssemblyModesFramePart, ReducedStaticsOfTwoLinkArmOnColumnEqualTheAssemblys) {
  const test::TwoLinkArm arm;
  mech::MultibodyModel m = test::two_link_arm(arm);
  std::vector<pipeline::Part> parts = test::two_link_parts(arm);
  pipeline::apply_mass_properties(m, parts, Log::quiet());
  parts.push_back(test::held_column_part({"frame", nullptr, {{"J1", "y1"}}, {}, {{"d1", "y1"}}}, 0.5, 0.04, 0.04, {2, 12, 2},
                              -0.5));
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(m), {0.0, 0.2, 0.5}).frames;

  AssemblyOptions options;
  options.drives = {{"d2", 3000.0}};
  options.points = {{"H", "link2", "tip", "x1"}};
  options.recover_stress = false;
  ElasticAssembly assembly(parts, m, options);
  vibration::AssemblyModesOptions mo;
  mo.modes = 4;
  const vibration::AssemblyModes modes(assembly, parts, m, mo, frames, Log::quiet());
  for (const mech::Frame& frame : frames) {
    const PoseSolution pose = assembly.solve(frame);
    const Eigen::Vector3d expected = pose.point("H").displacement_m;
    const VectorXd xs = modes.static_response(frame, modes.load(frame));
    const Eigen::Vector3d reduced = modes.point_rows("H", frame) * xs;
    const double mismatch = (reduced - expected).norm() / expected.norm();
    std::printf("  t = %.2f s: H %.6e m (assembly) vs %.6e m (reduced model), mismatch %.2e; f1 %.4f Hz\n", frame.t,
                expected.norm(), reduced.norm(), mismatch, modes.modes(frame).frequency_hz(0));
    // The vibration stage's reduced-statics check (docs/vibration.md).
    EXPECT_LT(mismatch, 1e-6) << "t = " << frame.t;
  }
}

TEST(AssemblyModesFramePart, HeldReductionOnASharedFactorEqualsTheOwnFactorReduction) {
  const vibration_tests::TipMassBeam b;
  const fem::FeModel clamped = b.model(true);
  const std::vector<vibration::PartInterface> tip = {b.tip_interface(clamped)};
  vibration::CraigBamptonOptions options;
  options.highest_frequency_of_interest_hz = 200.0;
  options.eigen.label = "clamped beam";
  const vibration::CraigBamptonModel own = vibration::reduce_craig_bampton(clamped, tip, options);
  const Log quiet = Log::quiet();
  fem::LinearStaticAnalysis analysis(clamped, quiet);
  const vibration::CraigBamptonModel held = vibration::reduce_held_craig_bampton(analysis, tip, options);
  ASSERT_EQ(held.mode_count, own.mode_count);
  ASSERT_GT(held.mode_count, 0);
  EXPECT_FALSE(held.free_body);
  EXPECT_EQ(held.free_dofs, own.free_dofs);
  EXPECT_EQ(held.constraint_modes.rows(), own.free_dofs);
  const Index nb = held.boundary_count;
  const double k_error = (held.stiffness.topLeftCorner(nb, nb) - own.stiffness.topLeftCorner(nb, nb)).cwiseAbs().maxCoeff() /
                         own.stiffness.topLeftCorner(nb, nb).cwiseAbs().maxCoeff();
  const double m_error = (held.mass.topLeftCorner(nb, nb) - own.mass.topLeftCorner(nb, nb)).cwiseAbs().maxCoeff() /
                         own.mass.topLeftCorner(nb, nb).cwiseAbs().maxCoeff();
  const double f_error =
      ((held.normal_frequency_hz - own.normal_frequency_hz).cwiseQuotient(own.normal_frequency_hz)).cwiseAbs().maxCoeff();
  std::printf("  held vs own factor: %ld modes, K_bb %.1e, M_bb %.1e, frequencies %.1e\n", long(held.mode_count),
              k_error, m_error, f_error);
  EXPECT_LT(k_error, 1e-9);
  EXPECT_LT(m_error, 1e-9);
  EXPECT_LT(f_error, 1e-9);
  // Over the mesh's DoFs: zero on the clamp.
  const MatrixXd full = vibration::expand_to_mesh_dofs(held.constraint_modes, analysis.dofs());
  for (const fem::Index n : clamped.mesh.node_set("x0"))
    EXPECT_EQ(full.middleRows(3 * n, 3).cwiseAbs().maxCoeff(), 0.0);

  fem::FeModel free = clamped;
  free.supports.clear();
  fem::StaticSolverOptions deferred;
  deferred.defer_factorization = true;
  fem::LinearStaticAnalysis unsupported(free, quiet, deferred);
  EXPECT_THROW(
      {
        try {
          vibration::reduce_held_craig_bampton(unsupported, tip, options);
        } catch (const Error& e) {
          EXPECT_NE(std::string(e.what()).find("'clamped beam'"), std::string::npos) << e.what();
          EXPECT_NE(std::string(e.what()).find("no supports"), std::string::npos) << e.what();
          throw;
        }
      },
      Error);
}

}  // namespace
}  // namespace kinetofem::structure
