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
#include "kinetofem/verification/box_mesh.hpp"
#include "kinetofem/verification/fe_probes.hpp"
#include "kinetofem/verification/patch_test.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;
using kv::BoxMeshOptions;
using kv::distorted_box;

// The box, its distorted meshes and the displacement patch test are those of
// `kinetofem verify` (kinetofem/verification/patch_test.hpp): corners moved at
// random (20 % of a cell) and by a smooth sine warp; HEX20 also gets curved
// edges (mid nodes off the chords). TET10 keeps straight edges: its 4-point
// rule (degree 2) integrates int dN/dx dV exactly only when the element map
// is affine; on curved TET10 the patch test fails by ~1e-4 (see CurvedTet10
// below).
const Eigen::Vector3d box_length = kv::patch_box_length();

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

TEST_P(PatchTest, LinearDisplacementFieldIsReproduced) {
  const kv::PatchErrors errors = kv::displacement_patch_test(distorted_box(GetParam()));
  ASSERT_GT(errors.interior_nodes, 0);
  // Reference: u = A x + b exactly at the interior nodes; 1e-10 relative (round-off).
  EXPECT_LT(errors.displacement, kv::kPatchTolerance) << errors.interior_nodes << " interior nodes";
  // Reference: sigma = D eps(A) at every Gauss point; 1e-10 relative.
  EXPECT_LT(errors.gauss_stress, kv::kPatchTolerance);
  // Extrapolation and averaging reproduce a constant stress at the nodes too;
  // reference the same D eps(A), 1e-10 relative.
  EXPECT_LT(errors.nodal_stress, kv::kPatchTolerance);
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
  const Mesh mesh = kv::box_mesh(options);
  ASSERT_NO_THROW(check_element_jacobians(mesh));
  const kv::PatchErrors errors = kv::displacement_patch_test(mesh);
  EXPECT_LT(errors.displacement, kv::kPatchTolerance);
  EXPECT_LT(errors.gauss_stress, kv::kPatchTolerance);
}

TEST_P(PatchTest, ConstantStressFromSurfaceTractions) {
  FeModel model;
  model.mesh = distorted_box(GetParam());
  model.material = kv::patch_material();
  Eigen::Matrix3d sigma0;
  sigma0 << 80e6, 15e6, -10e6,  //
      15e6, -30e6, 25e6,        //
      -10e6, 25e6, 50e6;

  // 3-2-1 supports at three corners: (0,0,0) all, (Lx,0,0) y and z, (0,Ly,0) z.
  auto corner = [&](const Eigen::Vector3d& x) {
    const auto nodes = kv::nodes_where(
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
                         ::testing::ValuesIn(all_element_types),
                         [](const auto& info) { return std::string(name_of(info.param)); });

}  // namespace
}  // namespace kinetofem::fem
