// Verification of the load transfer onto link FE models against known
// results: a link under a pure rigid-body acceleration balanced at its bores
// is a simply supported beam under a distributed load; each bore-load
// distribution against its defining distribution.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/verification/accelerated_link.hpp"
#include "kinetofem/verification/fe_probes.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;

// verification/geometry/beam_link.geo, TET10 of 6 mm (the mesh of `kinetofem
// verify` loads.accelerated_link).
const Mesh& beam_mesh() {
  static const Mesh mesh = kv::beam_link_mesh();
  return mesh;
}

TEST(LoadTransferVerification, AcceleratedLinkBalancedAtItsBoresIsASimplySupportedBeam) {
  // The link translates with a = 100 m/s^2 along y, its d'Alembert body
  // force balanced by the two pin reactions m a / 2 (distributing couplings
  // on the bores): a simply supported beam, M_mid = R L/2 - q (L/2 + e)^2/2,
  // sigma_xx = M_mid (h/2) / I. Reference, model and evaluation:
  // kinetofem/verification/accelerated_link.hpp. Tolerance 2 % (kBeamTheoryTolerance, there) on
  // the recovered nodal stress at the extreme fibres at mid-span.
  const kv::AcceleratedLinkResult r = kv::solve_accelerated_link(beam_mesh());
  ASSERT_GT(r.top_nodes, 0);
  ASSERT_GT(r.bottom_nodes, 0);
  const double sigma_beam = r.beam_stress_pa;
  std::printf("beam under rigid-body acceleration: sigma_xx top %.4f MPa, bottom %.4f MPa, beam theory %.4f MPa\n",
              r.top_pa * 1e-6, r.bottom_pa * 1e-6, sigma_beam * 1e-6);
  // The body force -rho a points along -y and the pins push +y: the beam sags
  // towards -y between them, so the +y fibre is in compression.
  EXPECT_NEAR(-r.top_pa, sigma_beam, kv::kBeamTheoryTolerance * sigma_beam);
  EXPECT_NEAR(r.bottom_pa, sigma_beam, kv::kBeamTheoryTolerance * sigma_beam);
}

TEST(LoadTransferVerification, CouplingOfAForceThroughTheBoreCentreIsAUniformTraction) {
  // Known result: the distributing coupling's weights are the consistent
  // tributary areas, so a force through the bore's centroid gives the
  // consistent nodal forces of the uniform traction F / area. Not to
  // round-off: on curved TRI6 faces the corner nodes get small consistent
  // weights of either sign, and the coupling drops the negative ones (a node
  // must not pull against the load), which rescales the others by
  // area / sum(weights) (measured 7e-6 of |F|). Tolerance 1e-4 of |F|.
  const Mesh& mesh = beam_mesh();
  DistributingCoupling coupling(mesh, "bore_2");
  const Eigen::Vector3d F(300.0, -1200.0, 40.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.node_count());
  coupling.add(F, Eigen::Vector3d::Zero(), coupling.centroid(), f);
  const double area = surface_area(mesh, mesh.face_set("bore_2"));
  const auto uniform = kv::consistent_face_forces(
      mesh, "bore_2", [&](const Eigen::Vector3d&, const Eigen::Vector3d&) { return Eigen::Vector3d(F / area); });
  double worst = 0;
  for (const auto& nf : uniform) worst = std::max(worst, (f.segment<3>(3 * nf.node) - nf.force_n).norm());
  std::printf("coupling vs uniform traction: largest nodal difference %.2e of |F|\n", worst / F.norm());
  EXPECT_LT(worst, 1e-4 * F.norm());
}

TEST(LoadTransferVerification, BearingPressureFollowsTheAnalyticCosineDistribution) {
  // Known result: a pin force F on a bore of radius R and length t carried by
  // p = p0 cos(phi) over the loaded half, p0 = 2 F / (pi R t). The nodal
  // forces must be the consistent nodal forces of that analytic pressure, to
  // the accuracy with which the mesh represents the cylinder and the edge of
  // the loaded half (tolerance 2 % of F in the norm of the difference).
  const Mesh& mesh = beam_mesh();
  const double R = 0.008, t = 0.02;
  const Eigen::Vector3d F(500.0, 866.0, 0.0);
  const Eigen::Vector3d dir = F.normalized();
  const double p0 = 2 * F.norm() / (std::numbers::pi * R * t);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.node_count());
  add_bearing_pressure(mesh, {"bore_1", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()}, F, f);
  const auto analytic = kv::consistent_face_forces(mesh, "bore_1", [&](const Eigen::Vector3d& x, const Eigen::Vector3d&) {
    const Eigen::Vector3d n = Eigen::Vector3d(x.x(), x.y(), 0).normalized();
    const double c = n.dot(dir);
    return Eigen::Vector3d(c > 0 ? Eigen::Vector3d(p0 * c * n) : Eigen::Vector3d::Zero());
  });
  double diff = 0;
  for (const auto& nf : analytic) diff += (f.segment<3>(3 * nf.node) - nf.force_n).squaredNorm();
  std::printf("bearing pressure vs analytic cosine: |difference| = %.3e of |F|\n", std::sqrt(diff) / F.norm());
  EXPECT_LT(std::sqrt(diff), 0.02 * F.norm());
}

}  // namespace
}  // namespace kinetofem::fem
