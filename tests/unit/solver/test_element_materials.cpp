// Unit tests of a material per element set (solver/include/kinetofem/solver/
// element_materials.hpp, FeModel::set_materials): the two-material bar in
// series, the mass properties and d'Alembert loads of a two-density block,
// stress recovery with each element's D, the one-material path unchanged, and
// the checks of the listed sets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/mass_matrix.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/box_mesh.hpp"

namespace kinetofem::fem {
namespace {

// Element sets "solid.a" (elements whose centroid lies at x < split_m) and
// "solid.b" (the others): two solids of one conformal mesh.
void split_at(Mesh& mesh, double split_m) {
  std::vector<Index>& a = mesh.element_sets["solid.a"];
  std::vector<Index>& b = mesh.element_sets["solid.b"];
  Index first = 0;
  for (const auto& block : mesh.blocks) {
    const int corners = corner_nodes(block.type);
    for (Index e = 0; e < block.size(); ++e) {
      double x = 0.0;
      for (int k = 0; k < corners; ++k) x += mesh.nodes(block.element(e)[size_t(k)], 0) / corners;
      (x < split_m ? a : b).push_back(first + e);
    }
    first += block.size();
  }
}

Mesh box(ElementType type, const Eigen::Vector3d& length_m, std::array<int, 3> divisions,
         double split_m) {
  testing::BoxMeshOptions options;
  options.length_m = length_m;
  options.divisions = divisions;
  options.type = type;
  Mesh mesh = testing::box_mesh(options);
  split_at(mesh, split_m);
  return mesh;
}

// Poisson's ratio 0: a bar in tension has no lateral strain, so the clamped
// end and the interface between the two materials do not disturb the
// uniaxial state, and the exact solution (u_x linear in each segment) lies
// in the finite-element space.
const IsotropicMaterial kSteel{"steel", 210e9, 0.0, 7850.0};
const IsotropicMaterial kAluminium{"aluminium", 70e9, 0.0, 2700.0};

struct Bar {
  double length_a_m = 0.25, length_b_m = 0.15, side_m = 0.02, force_n = 1e4;
  double area() const { return side_m * side_m; }
};

FeModel bar_model(ElementType type, const Bar& bar) {
  FeModel model;
  model.mesh = box(type, {bar.length_a_m + bar.length_b_m, bar.side_m, bar.side_m}, {8, 2, 2},
                   bar.length_a_m);
  model.supports = {{"clamp", model.mesh.node_set("x0"), {true, true, true}, Eigen::Vector3d::Zero()}};
  return model;
}

LoadCase end_force(const Bar& bar) {
  LoadCase load;
  load.tractions = {{"x1", Eigen::Vector3d(bar.force_n / bar.area(), 0.0, 0.0)}};
  return load;
}

TEST(ElementMaterials, TwoMaterialBarInSeriesStretchesBySumOfItsSegments) {
  const Bar bar;
  // Reference: two bars in series, u_tip = F L1 / (E1 A) + F L2 / (E2 A),
  // exact here (nu = 0, see above): only round-off of the solve remains.
  const double expected = bar.force_n * bar.length_a_m / (kSteel.youngs_modulus_pa * bar.area()) +
                          bar.force_n * bar.length_b_m / (kAluminium.youngs_modulus_pa * bar.area());
  const double sigma = bar.force_n / bar.area();
  const IsotropicMaterial unused{"unused", 1e3, 0.0, 1.0};
  const Log log = Log::quiet();
  for (ElementType type : {ElementType::Hex8, ElementType::Tet10}) {
    // Segment b listed, a takes the model's material; then both listed, so
    // the model's material (absurdly soft) holds no element.
    for (bool both_listed : {false, true}) {
      FeModel model = bar_model(type, bar);
      model.material = both_listed ? unused : kSteel;
      model.set_materials = {{"solid.b", kAluminium}};
      if (both_listed) model.set_materials.push_back({"solid.a", kSteel});
      LinearStaticAnalysis analysis(model, log);
      const LoadCase load = end_force(bar);
      const DisplacementField u = analysis.solve({load}).front();
      for (Index node : model.mesh.node_set("x1")) {
        // 1e-9: the exact solution is discrete; the rest is the solve's round-off.
        EXPECT_NEAR(u(node, 0), expected, 1e-9 * expected) << name_of(type) << " node " << node;
        EXPECT_NEAR(u.row(node).tail<2>().norm(), 0.0, 1e-9 * expected) << name_of(type);
      }

      // Each element's stress with its own D: sigma_xx = F / A in both
      // segments (with one D for all, segment b would show E1 / E2 times it).
      const GaussPointStress gauss = gauss_point_stress(model.mesh, analysis.materials(), u);
      for (Eigen::Index q = 0; q < gauss.stress_pa.rows(); ++q) {
        EXPECT_NEAR(gauss.stress_pa(q, 0), sigma, 1e-8 * sigma) << name_of(type) << " point " << q;
        EXPECT_NEAR(gauss.stress_pa.row(q).tail<5>().cwiseAbs().maxCoeff(), 0.0, 1e-8 * sigma);
      }
      const NodalStress nodal = recover_nodal_stress(model.mesh, analysis.materials(), u);
      EXPECT_NEAR(nodal.von_mises_pa.maxCoeff(), sigma, 1e-8 * sigma) << name_of(type);

      // The clamp's reaction balances the end force (internal forces with
      // each element's stiffness).
      const Eigen::MatrixXd F = assemble_external_forces(model.mesh, analysis.materials(), {load});
      const Eigen::VectorXd r = analysis.reactions(u, F.col(0));
      double reaction_x = 0.0;
      for (Index node : model.mesh.node_set("x0")) reaction_x += r[3 * node];
      EXPECT_NEAR(reaction_x, -bar.force_n, 1e-9 * bar.force_n) << name_of(type);
    }
  }
}

// A block of two densities: [0, a] x [0, b] x [0, c] with x < a1 of density
// rho1 and the rest rho2.
struct Block {
  double a = 0.3, a1 = 0.2, b = 0.1, c = 0.05;
  IsotropicMaterial light{"aluminium", 70e9, 0.33, 2700.0};
  IsotropicMaterial heavy{"steel", 210e9, 0.3, 7850.0};
};

FeModel block_model(ElementType type, const Block& k) {
  FeModel model;
  model.mesh = box(type, {k.a, k.b, k.c}, {6, 2, 1}, k.a1);
  model.material = k.heavy;
  model.set_materials = {{"solid.b", k.light}};
  return model;
}

// Hand sum of the two boxes: masses, centre of mass, and the inertia about it
// from each box's own (m (h^2 + w^2) / 12 on the diagonal) and the parallel-
// axis terms m (|d|^2 1 - d d^T).
MassProperties hand_sum(const Block& k) {
  struct Piece {
    double mass, length, centre_x;
  };
  const double a2 = k.a - k.a1;
  const Piece pieces[2] = {{k.heavy.density_kg_m3 * k.a1 * k.b * k.c, k.a1, 0.5 * k.a1},
                           {k.light.density_kg_m3 * a2 * k.b * k.c, a2, k.a1 + 0.5 * a2}};
  MassProperties out;
  for (const Piece& p : pieces) out.mass_kg += p.mass;
  out.centre_of_mass_m = {(pieces[0].mass * pieces[0].centre_x + pieces[1].mass * pieces[1].centre_x) / out.mass_kg,
                          0.5 * k.b, 0.5 * k.c};
  for (const Piece& p : pieces) {
    const Eigen::Vector3d d = Eigen::Vector3d(p.centre_x, 0.5 * k.b, 0.5 * k.c) - out.centre_of_mass_m;
    const Eigen::Vector3d own = p.mass / 12.0 *
                                Eigen::Vector3d(k.b * k.b + k.c * k.c, p.length * p.length + k.c * k.c,
                                                p.length * p.length + k.b * k.b);
    out.inertia_about_com_kgm2 += Eigen::Matrix3d(own.asDiagonal()) +
                                  p.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return out;
}

TEST(ElementMaterials, MassPropertiesOfTwoDensityBlockAreTheHandSum) {
  const Block k;
  const MassProperties expected = hand_sum(k);
  for (ElementType type : {ElementType::Hex8, ElementType::Tet10, ElementType::Hex20}) {
    const FeModel model = block_model(type, k);
    const MassProperties mp = mass_properties(model.mesh, element_materials(model));
    // 1e-12: the load rules integrate straight-sided elements exactly.
    EXPECT_NEAR(mp.mass_kg, expected.mass_kg, 1e-12 * expected.mass_kg) << name_of(type);
    EXPECT_LT((mp.centre_of_mass_m - expected.centre_of_mass_m).norm(), 1e-12 * k.a) << name_of(type);
    const double scale = expected.inertia_about_com_kgm2.cwiseAbs().maxCoeff();
    EXPECT_LT((mp.inertia_about_com_kgm2 - expected.inertia_about_com_kgm2).cwiseAbs().maxCoeff(), 1e-12 * scale)
        << name_of(type);
  }
}

TEST(ElementMaterials, MassMatrixGravityAndMotionLoadsUseEachElementsDensity) {
  const Block k;
  const MassProperties expected = hand_sum(k);
  const FeModel model = block_model(ElementType::Tet10, k);
  const ElementMaterials materials = element_materials(model);

  // Consistent mass: a unit rigid translation carries the whole mass,
  // v^T M v = m (exact for straight-sided elements).
  const DofMap dofs(model.mesh.node_count(), {});
  const SymmetricUpperMatrix M = assemble_mass(model.mesh, materials, dofs);
  const Eigen::VectorXd v = rigid_body_field(model.mesh, Eigen::Vector3d::UnitY(), Eigen::Vector3d::Zero());
  EXPECT_NEAR(v.dot(M.selfadjointView<Eigen::Upper>() * v), expected.mass_kg, 1e-12 * expected.mass_kg);

  // Gravity: the nodal forces add up to m g.
  LoadCase weight;
  weight.gravity_m_s2 = {0.0, -9.81, 0.0};
  const Eigen::MatrixXd F = assemble_external_forces(model.mesh, materials, {weight});
  Eigen::Vector3d total, moment;
  resultant(model.mesh, F.col(0), expected.centre_of_mass_m, total, moment);
  EXPECT_NEAR(total.y(), -9.81 * expected.mass_kg, 1e-12 * 9.81 * expected.mass_kg);
  EXPECT_LT(moment.norm(), 1e-12 * 9.81 * expected.mass_kg * k.a);  // acts at the centre of mass

  // d'Alembert loads of a rigid motion: their basis carries the same mass
  // and centre of mass.
  const RigidBodyMotionLoads motion(model.mesh, materials);
  EXPECT_NEAR(motion.mass_kg(), expected.mass_kg, 1e-12 * expected.mass_kg);
  EXPECT_LT((motion.centre_of_mass_m() - expected.centre_of_mass_m).norm(), 1e-12 * k.a);
}

// The largest difference of a and b relative to a's largest entry.
double relative_difference(const Eigen::Ref<const Eigen::MatrixXd>& a, const Eigen::Ref<const Eigen::MatrixXd>& b) {
  EXPECT_EQ(a.rows(), b.rows());
  EXPECT_EQ(a.cols(), b.cols());
  if (a.rows() != b.rows() || a.cols() != b.cols()) return 1.0;
  return (a - b).cwiseAbs().maxCoeff() / std::max(a.cwiseAbs().maxCoeff(), 1e-300);
}

// The stored values of a sparse matrix as a column.
Eigen::Map<const Eigen::VectorXd> values_of(const Eigen::SparseMatrix<double>& A) {
  return {A.valuePtr(), A.nonZeros()};
}

TEST(ElementMaterials, OneListedSetOfTheModelsMaterialChangesNothingButRoundOff) {
  // The per-element lookup does the arithmetic of a one-material model: with
  // every element listed under the model's own material, every result equals
  // the one-material result to round-off. Not to the bit: the assembled
  // matrices add element contributions with OpenMP atomics under dynamic
  // scheduling, so with two or more threads the order of the sums, and the
  // last bit, changes from run to run. A wrong material would move entries by
  // O(1); 1e-14 of the largest entry is a few units in the last place.
  constexpr double round_off = 1e-14;
  const Block k;
  FeModel one = block_model(ElementType::Tet10, k);
  one.set_materials.clear();
  one.mesh.element_sets["all"] = one.mesh.element_sets.at("solid.a");
  for (Index e : one.mesh.element_sets.at("solid.b")) one.mesh.element_sets["all"].push_back(e);
  FeModel listed = one;
  listed.set_materials = {{"all", one.material}};
  const ElementMaterials a = element_materials(one), b = element_materials(listed);
  ASSERT_TRUE(a.uniform());
  ASSERT_FALSE(b.uniform());

  const DofMap dofs(one.mesh.node_count(), {});
  const AssembledStiffness Ka = assemble_stiffness(one.mesh, a, dofs), Kb = assemble_stiffness(one.mesh, b, dofs);
  EXPECT_LE(relative_difference(values_of(Ka.free_free), values_of(Kb.free_free)), round_off);
  const SymmetricUpperMatrix Ma = assemble_mass(one.mesh, a, dofs), Mb = assemble_mass(one.mesh, b, dofs);
  EXPECT_LE(relative_difference(values_of(Ma), values_of(Mb)), round_off);
  LoadCase weight;
  weight.gravity_m_s2 = {1.0, -9.81, 0.5};
  EXPECT_LE(relative_difference(assemble_external_forces(one.mesh, a, {weight}),
                                assemble_external_forces(one.mesh, b, {weight})),
            round_off);
  DisplacementField u(one.mesh.node_count(), 3);  // any field with all strains nonzero
  for (Index n = 0; n < u.rows(); ++n)
    u.row(n) = 1e-4 * Eigen::RowVector3d(std::sin(3.0 * n), std::cos(5.0 * n), std::sin(7.0 * n + 1.0));
  EXPECT_LE(relative_difference(recover_nodal_stress(one.mesh, a, u).stress_pa,
                                recover_nodal_stress(one.mesh, b, u).stress_pa),
            round_off);
  EXPECT_LE(relative_difference(internal_forces(one.mesh, a, u), internal_forces(one.mesh, b, u)), round_off);
  const MassProperties pa = mass_properties(one.mesh, a), pb = mass_properties(one.mesh, b);
  EXPECT_NEAR(pa.mass_kg, pb.mass_kg, round_off * pa.mass_kg);
  EXPECT_LE((pa.centre_of_mass_m - pb.centre_of_mass_m).norm(), round_off * k.a);
  EXPECT_LE(relative_difference(pa.inertia_about_com_kgm2, pb.inertia_about_com_kgm2), round_off);
}

// The Error of element_materials(model), or "" if none.
std::string error_of(const FeModel& model) {
  try {
    element_materials(model);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ElementMaterials, AnUnknownSetIsAnErrorNamingItAndTheSetsPresent) {
  FeModel model = block_model(ElementType::Hex8, Block{});
  model.set_materials.push_back({"solid.c", kSteel});
  const std::string message = error_of(model);
  EXPECT_NE(message.find("element set 'solid.c'"), std::string::npos) << message;
  EXPECT_NE(message.find("element sets present: solid.a, solid.b"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  // The analysis checks it before it assembles anything.
  const Log log = Log::quiet();
  EXPECT_THROW(LinearStaticAnalysis(model, log), Error);
}

TEST(ElementMaterials, AnElementInTwoListedSetsIsAnError) {
  FeModel model = block_model(ElementType::Hex8, Block{});
  model.mesh.element_sets["lug"] = {model.mesh.element_sets.at("solid.b").back()};
  model.set_materials.push_back({"lug", kSteel});
  const std::string message = error_of(model);
  EXPECT_NE(message.find(fmt::format("element {} is in two element sets with a material, 'solid.b' and 'lug'",
                                     model.mesh.element_sets.at("solid.b").back())),
            std::string::npos)
      << message;
  // An element set of the mesh that is not listed may overlap freely.
  model.set_materials.pop_back();
  EXPECT_EQ(error_of(model), "");
}

TEST(ElementMaterials, ASetListedTwiceIsAnError) {
  FeModel model = block_model(ElementType::Hex8, Block{});
  model.set_materials.push_back({"solid.b", kSteel});
  EXPECT_NE(error_of(model).find("element set 'solid.b' is given a material twice"), std::string::npos)
      << error_of(model);
}

TEST(ElementMaterials, AnInvalidListedMaterialIsAnErrorNamingItsSet) {
  FeModel model = block_model(ElementType::Hex8, Block{});
  model.set_materials.front().material.youngs_modulus_pa = -1.0;
  const std::string message = error_of(model);
  EXPECT_NE(message.find("element set 'solid.b': material 'aluminium': Young's modulus"), std::string::npos)
      << message;
  model.set_materials.front().material.youngs_modulus_pa = 70e9;
  model.set_materials.front().material.poisson_ratio = 0.5;
  EXPECT_NE(error_of(model).find("Poisson's ratio"), std::string::npos) << error_of(model);
  // The model's own material is checked as before, listed sets or not.
  model.set_materials.front().material.poisson_ratio = 0.33;
  model.material.density_kg_m3 = -1.0;
  EXPECT_NE(error_of(model).find("material 'steel': density"), std::string::npos) << error_of(model);
}

}  // namespace
}  // namespace kinetofem::fem
