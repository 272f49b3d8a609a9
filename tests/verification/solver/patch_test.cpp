// Patch tests of the solid elements on distorted meshes.
//
// Reference: a linear displacement field u = A x + b lies in the span of every
// isoparametric element's shape functions (sum N_i = 1, sum N_i x_i = x), so
// a conforming, consistent element reproduces it exactly: with u prescribed
// on the boundary the interior nodes take u(x) and every Gauss point carries
// the constant stress D * eps(A). The force-driven variant applies the
// tractions t = sigma0 n of a constant stress sigma0 on the six faces with
// 3-2-1 point supports (statically determinate, so their reactions vanish):
// every Gauss point must carry sigma0. "Exactly" means to round-off; we allow
// 1e-10 relative (the systems here have condition numbers ~1e4-1e6).
#include <gtest/gtest.h>

#include <cmath>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/box_mesh.hpp"
#include "kinetofem/testing/fe_probes.hpp"

namespace kinetofem::fem {
namespace {

using testing::BoxMeshOptions;

const Eigen::Vector3d box_length(1.0, 0.8, 0.6);

// Corners moved at random (20 % of a cell) and by a smooth sine warp. HEX20
// also gets curved edges (mid nodes off the chords). TET10 keeps straight
// edges: its 4-point rule (degree 2) integrates int dN/dx dV exactly only
// when the element map is affine; on curved TET10 the patch test fails by
// ~1e-4 (see CurvedTet10 below).
Mesh distorted_box(ElementType type, bool curved) {
  BoxMeshOptions options;
  options.length_m = box_length;
  options.divisions = {3, 3, 3};
  options.type = type;
  options.random_perturbation = 0.2;
  options.seed = 7;
  if (curved) {
    options.mid_node_perturbation = 0.1;
    options.smooth_map = testing::sine_warp(box_length, 0.05);
  }
  return testing::box_mesh(options);
}

Mesh distorted_box(ElementType type) { return distorted_box(type, type != ElementType::Tet10); }

IsotropicMaterial steel() { return IsotropicMaterial{"steel", 210e9, 0.3, 7850.0}; }

// Voigt strain (xx, yy, zz, xy, yz, zx; engineering shear) of u = A x + b.
Vector6d voigt_strain(const Eigen::Matrix3d& A) {
  Vector6d e;
  e << A(0, 0), A(1, 1), A(2, 2), A(0, 1) + A(1, 0), A(1, 2) + A(2, 1), A(2, 0) + A(0, 2);
  return e;
}

class PatchTest : public ::testing::TestWithParam<ElementType> {};

TEST_P(PatchTest, DistortedMeshIsValid) {
  const Mesh mesh = distorted_box(GetParam());
  EXPECT_NO_THROW(check_element_jacobians(mesh));
  // Every node still lies in the box (the faces stay plane and in place).
  for (Index n = 0; n < mesh.node_count(); ++n)
    for (int d = 0; d < 3; ++d) {
      EXPECT_GE(mesh.nodes(n, d), -1e-15);
      EXPECT_LE(mesh.nodes(n, d), box_length[d] * (1 + 1e-15));
    }
}

// Relative errors of the displacement patch test on a mesh: interior nodal
// displacement, Gauss-point stress and recovered nodal stress.
struct PatchErrors {
  double displacement = 0.0, gauss_stress = 0.0, nodal_stress = 0.0;
  int interior_nodes = 0;
};

PatchErrors linear_field_patch(const Mesh& mesh) {
  FeModel model;
  model.mesh = mesh;
  model.material = steel();
  Eigen::Matrix3d A;
  A << 1.0e-3, -0.4e-3, 0.7e-3,  //
      0.3e-3, -0.6e-3, 0.2e-3,   //
      -0.5e-3, 0.9e-3, 0.8e-3;
  const Eigen::Vector3d b(2e-4, -1e-4, 3e-4);
  auto exact = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return A * x + b; };
  model.supports = testing::prescribe_field(model.mesh, model.mesh.node_set("boundary"), exact);

  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve({LoadCase{}}).at(0);

  PatchErrors errors;
  const auto& boundary = model.mesh.node_set("boundary");
  double scale = 0.0;
  for (Index n = 0; n < model.mesh.node_count(); ++n) {
    const Eigen::Vector3d ue = exact(model.mesh.nodes.row(n).transpose());
    scale = std::max(scale, ue.norm());
    if (std::binary_search(boundary.begin(), boundary.end(), n)) continue;
    ++errors.interior_nodes;
    errors.displacement = std::max(errors.displacement, (u.row(n).transpose() - ue).norm());
  }
  errors.displacement /= scale;

  const Vector6d sigma = steel().elasticity_matrix() * voigt_strain(A);
  const auto gauss = gauss_point_stress(model.mesh, model.material, u);
  for (Index p = 0; p < gauss.stress_pa.rows(); ++p)
    errors.gauss_stress =
        std::max(errors.gauss_stress, (gauss.stress_pa.row(p).transpose() - sigma).norm());
  errors.gauss_stress /= sigma.norm();
  const auto nodal = recover_nodal_stress(model.mesh, model.material, u);
  for (Index n = 0; n < nodal.stress_pa.rows(); ++n)
    errors.nodal_stress =
        std::max(errors.nodal_stress, (nodal.stress_pa.row(n).transpose() - sigma).norm());
  errors.nodal_stress /= sigma.norm();
  return errors;
}

TEST_P(PatchTest, LinearDisplacementFieldIsReproduced) {
  const PatchErrors errors = linear_field_patch(distorted_box(GetParam()));
  ASSERT_GT(errors.interior_nodes, 0);
  // Reference: u = A x + b exactly at the interior nodes; 1e-10 relative (round-off).
  EXPECT_LT(errors.displacement, 1e-10) << errors.interior_nodes << " interior nodes";
  // Reference: sigma = D eps(A) at every Gauss point; 1e-10 relative.
  EXPECT_LT(errors.gauss_stress, 1e-10);
  // Extrapolation and averaging reproduce a constant stress at the nodes too;
  // reference the same D eps(A), 1e-10 relative.
  EXPECT_LT(errors.nodal_stress, 1e-10);
}

// Curved TET10 (mid nodes off the chords): the stiffness rule must integrate
// int B^T sigma0 dV = int adj(J)^T dN/dxi sigma0 dxi, a cubic on a curved
// TET10, exactly for the patch test to pass; the 4-point (degree 2) rule
// does not: measured 5e-5 in the interior displacement and 6e-4 in the
// Gauss-point stress (random 0.1, mid-node 0.05 distortion). Disabled until the element
// library uses a degree >= 3 rule for TET10 stiffness (reported to the lead);
// same reference and tolerance as above.
TEST(PatchTestCurved, CurvedTet10) {
  BoxMeshOptions options;
  options.length_m = box_length;
  options.divisions = {3, 3, 3};
  options.type = ElementType::Tet10;
  options.random_perturbation = 0.1;
  options.mid_node_perturbation = 0.05;
  const Mesh mesh = testing::box_mesh(options);
  ASSERT_NO_THROW(check_element_jacobians(mesh));
  const PatchErrors errors = linear_field_patch(mesh);
  EXPECT_LT(errors.displacement, 1e-10);
  EXPECT_LT(errors.gauss_stress, 1e-10);
}

TEST_P(PatchTest, ConstantStressFromSurfaceTractions) {
  FeModel model;
  model.mesh = distorted_box(GetParam());
  model.material = steel();
  Eigen::Matrix3d sigma0;
  sigma0 << 80e6, 15e6, -10e6,  //
      15e6, -30e6, 25e6,        //
      -10e6, 25e6, 50e6;

  // 3-2-1 supports at three corners: (0,0,0) all, (Lx,0,0) y and z, (0,Ly,0) z.
  auto corner = [&](const Eigen::Vector3d& x) {
    const auto nodes = testing::nodes_where(
        model.mesh, [&](const Eigen::Vector3d& p) { return (p - x).norm() < 1e-9; });
    EXPECT_EQ(nodes.size(), 1u);
    return nodes.at(0);
  };
  model.supports = {
      {"origin", {corner({0, 0, 0})}, {true, true, true}, Eigen::Vector3d::Zero()},
      {"x-corner", {corner({box_length.x(), 0, 0})}, {false, true, true}, Eigen::Vector3d::Zero()},
      {"y-corner", {corner({0, box_length.y(), 0})}, {false, false, true}, Eigen::Vector3d::Zero()}};

  LoadCase load;
  const std::pair<const char*, Eigen::Vector3d> faces[] = {
      {"x0", -Eigen::Vector3d::UnitX()}, {"x1", Eigen::Vector3d::UnitX()},
      {"y0", -Eigen::Vector3d::UnitY()}, {"y1", Eigen::Vector3d::UnitY()},
      {"z0", -Eigen::Vector3d::UnitZ()}, {"z1", Eigen::Vector3d::UnitZ()}};
  for (const auto& [name, normal] : faces) load.tractions.push_back({name, sigma0 * normal});

  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve({load}).at(0);

  Vector6d expected;
  expected << sigma0(0, 0), sigma0(1, 1), sigma0(2, 2), sigma0(0, 1), sigma0(1, 2), sigma0(2, 0);
  const auto gauss = gauss_point_stress(model.mesh, model.material, u);
  double worst = 0.0;
  for (Index p = 0; p < gauss.stress_pa.rows(); ++p)
    worst = std::max(worst, (gauss.stress_pa.row(p).transpose() - expected).norm());
  // Reference: sigma = sigma0 at every Gauss point; 1e-10 relative.
  EXPECT_LT(worst / expected.norm(), 1e-10);

  // The loads are self-equilibrated, so the 3-2-1 supports carry nothing:
  // reactions below 1e-10 of the largest face resultant.
  const Eigen::MatrixXd f = assemble_external_forces(model.mesh, model.material, {load});
  const Eigen::VectorXd reactions = analysis.reactions(u, f.col(0));
  const double face_force = sigma0.norm() * box_length.x() * box_length.y();
  EXPECT_LT(reactions.cwiseAbs().maxCoeff() / face_force, 1e-10);
}

INSTANTIATE_TEST_SUITE_P(Elements, PatchTest,
                         ::testing::Values(ElementType::Tet4, ElementType::Tet10, ElementType::Hex8,
                                           ElementType::Hex20),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace kinetofem::fem
