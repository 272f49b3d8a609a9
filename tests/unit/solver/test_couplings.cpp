// Load-transfer tests: distributing coupling, bearing pressure, rigid-body
// motion loads and the 3-2-1 support, on a link with two bores.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::fem {
namespace {

const Mesh& link_mesh() {
  static const Mesh mesh = [] {
    meshes::MeshOptions options;
    options.element_size_m = 0.008;
    options.order = 2;
    return meshes::mesh_geometry("tests/data/meshes/link_two_bores.geo", options);
  }();
  return mesh;
}

TEST(DistributingCoupling, ReproducesTheResultantForceAndMomentExactly) {
  const Mesh& mesh = link_mesh();
  DistributingCoupling coupling(mesh, "bore_2");
  // Centroid on the pin axis by symmetry of the bore; the unstructured mesh
  // is not exactly symmetric: within 1 micrometre.
  EXPECT_NEAR(coupling.centroid().x(), 0.24, 1e-6);
  EXPECT_NEAR(coupling.centroid().y(), 0.0, 1e-6);
  const Eigen::Vector3d F(120.0, -450.0, 30.0), M(5.0, -2.0, 17.0), ref(0.25, 0.01, 0.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.node_count());
  coupling.add(F, M, ref, f);
  Eigen::Vector3d F_out, M_out;
  resultant(mesh, f, ref, F_out, M_out);
  // Reference: static equivalence, exact up to round-off (1e-10 relative).
  EXPECT_LT((F_out - F).norm(), 1e-10 * F.norm());
  EXPECT_LT((M_out - M).norm(), 1e-10 * M.norm() + 1e-10 * F.norm() * 0.01);
}

TEST(BearingPressure, CarriesTheRadialForceWithACosineDistribution) {
  const Mesh& mesh = link_mesh();
  BoreGeometry bore{"bore_1", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()};
  const Eigen::Vector3d F(-800.0, 600.0, 50.0);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.node_count());
  const Eigen::Vector3d axial = add_bearing_pressure(mesh, bore, F, f);
  EXPECT_NEAR(axial.z(), 50.0, 1e-12);  // the axial part is not carried, it is returned
  Eigen::Vector3d F_out, M_out;
  resultant(mesh, f, Eigen::Vector3d::Zero(), F_out, M_out);
  // Reference: resultant = radial force, exactly (the cosine's amplitude
  // vector is solved on the discrete bore): 1e-10 relative.
  const Eigen::Vector3d radial(-800, 600, 0);
  EXPECT_LT((F_out - radial).norm(), 1e-10 * radial.norm());
  // A radial pressure has no moment about the pin axis.
  EXPECT_LT(std::abs(M_out.z()), 1e-10 * F.norm() * 0.015);
  // Only the half facing the force is loaded (nodes of the faces cut by the
  // half's edge excepted: up to one element, ~23 deg, beyond it).
  const Eigen::Vector3d dir = Eigen::Vector3d(-800, 600, 0).normalized();
  for (Index node : nodes_of_faces(mesh.face_set("bore_1"))) {
    const Eigen::Vector3d x = mesh.nodes.row(node).transpose();
    const Eigen::Vector3d load = f.segment<3>(3 * node);
    if (Eigen::Vector3d(x.x(), x.y(), 0).normalized().dot(dir) < -0.5) EXPECT_LT(load.norm(), 1e-12);
  }
}

TEST(RigidBodyMotionLoads, ResultantIsMassTimesAccelerationOfTheCentreOfMass) {
  const Mesh& mesh = link_mesh();
  IsotropicMaterial steel;
  RigidBodyMotionLoads inertia(mesh, steel);
  // Mass = rho V; the two come from different Gauss rules, which agree to
  // ~1e-10 on curved (non-affine) TET10 elements: tolerance 1e-8.
  EXPECT_NEAR(inertia.mass_kg(), steel.density_kg_m3 * mesh_volume(mesh), 1e-8 * inertia.mass_kg());
  const Eigen::Vector3d g(0, -9.81, 0), aO(2.0, -1.0, 0.0), w(0, 0, 3.0), alpha(0, 0, -12.0);
  const Eigen::VectorXd f = inertia.forces(g, aO, w, alpha);
  const Eigen::Vector3d c = inertia.centre_of_mass_m();
  const Eigen::Vector3d a_com = aO + alpha.cross(c) + w.cross(w.cross(c));
  Eigen::Vector3d F, M;
  resultant(mesh, f, c, F, M);
  // Reference: Newton, F = m (g - a_G), exact for the affine field (1e-10).
  EXPECT_LT((F - inertia.mass_kg() * (g - a_com)).norm(), 1e-10 * F.norm());
  // Euler for planar motion about z: M_G,z = -I_Gz alpha_z; I_Gz from the
  // mesh by the same basis (second moments): check the sign and order only
  // against the box estimate m (L^2 + W^2) / 12 within 15 % (holes removed).
  const double box_inertia = inertia.mass_kg() * (0.30 * 0.30 + 0.06 * 0.06) / 12.0;
  EXPECT_NEAR(M.z() / (-alpha.z()), box_inertia, 0.15 * box_inertia);
}

TEST(MassProperties, MatchTheRigidBodyLoadsAndEuler) {
  const Mesh& mesh = link_mesh();
  IsotropicMaterial steel;
  const MassProperties mp = mass_properties(mesh, steel);
  RigidBodyMotionLoads inertia(mesh, steel);
  // Same Gauss rule as the motion loads: mass and centre agree to round-off.
  EXPECT_NEAR(mp.mass_kg, inertia.mass_kg(), 1e-12 * mp.mass_kg);
  EXPECT_LT((mp.centre_of_mass_m - inertia.centre_of_mass_m()).norm(), 1e-12);
  // Euler: a pure angular acceleration alpha about z through the centre of
  // mass gives the inertia moment -I_zz alpha (the body force is affine, so
  // the consistent nodal forces reproduce it exactly: 1e-9).
  const Eigen::Vector3d c = mp.centre_of_mass_m, alpha(0, 0, 7.0);
  const Eigen::Vector3d aO = -alpha.cross(c);  // origin acceleration making a_G = 0
  Eigen::Vector3d F, M;
  resultant(mesh, inertia.forces(Eigen::Vector3d::Zero(), aO, Eigen::Vector3d::Zero(), alpha), c, F, M);
  EXPECT_LT(F.norm(), 1e-9 * mp.mass_kg * 7.0 * 0.3);
  EXPECT_NEAR(M.z(), -mp.inertia_about_com_kgm2(2, 2) * 7.0, 1e-9 * std::abs(M.z()));
}

TEST(RemoveRigidBodyMotion, LeavesNothingOfARigidMotionAndKeepsAStretch) {
  const Mesh& mesh = link_mesh();
  DisplacementField u(mesh.node_count(), 3), stretch(mesh.node_count(), 3);
  const Eigen::Vector3d t(1e-4, -2e-4, 3e-5), theta(1e-4, 2e-4, -3e-4);
  for (Index i = 0; i < mesh.node_count(); ++i) {
    const Eigen::Vector3d x = mesh.nodes.row(i).transpose();
    u.row(i) = (t + theta.cross(x)).transpose();
    stretch.row(i) << 1e-3 * (x.x() - 0.12), 0, 0;  // symmetric about the centroid: no rigid part
  }
  // A small rigid motion is linear in x: it is removed exactly (round-off).
  EXPECT_LT(remove_rigid_body_motion(mesh, u).cwiseAbs().maxCoeff(), 1e-15);
  const DisplacementField kept = remove_rigid_body_motion(mesh, u + stretch);
  EXPECT_LT((kept - remove_rigid_body_motion(mesh, stretch)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_GT(kept.col(0).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(ThreeTwoOneSupport, FreeLinkUnderSelfEquilibratedLoadsHasZeroReactions) {
  const Mesh& mesh = link_mesh();
  FeModel model;
  model.mesh = mesh;
  std::vector<Index> all(size_t(mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = Index(i);
  model.supports = three_two_one_support(mesh, all);
  // Tension between the two pins (equal and opposite forces), through
  // distributing couplings: a self-equilibrated load.
  Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * mesh.node_count());
  DistributingCoupling(mesh, "bore_1").add(Eigen::Vector3d(-1000, 0, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), f);
  DistributingCoupling(mesh, "bore_2").add(Eigen::Vector3d(1000, 0, 0), Eigen::Vector3d::Zero(), Eigen::Vector3d(0.24, 0, 0), f);
  Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  Eigen::MatrixXd F = f;
  const auto u = analysis.solve_forces(F);
  const Eigen::VectorXd r = analysis.reactions(u[0], f);
  // Statically determinate support: reactions vanish to round-off (1e-8 of the load).
  EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-8 * 1000.0);
  // The link stretches: far-field stress ~ F / A_net in the middle (60 x 20 mm):
  // 1000 / 1.2e-3 = 0.83 MPa (within 10 %, away from the bores).
  const NodalStress s = recover_nodal_stress(mesh, model.material, u[0]);
  double sum = 0;
  int n = 0;
  for (Index i = 0; i < mesh.node_count(); ++i)
    if (std::abs(mesh.nodes(i, 0) - 0.12) < 0.005) {
      sum += s.stress_pa(i, 0);
      ++n;
    }
  ASSERT_GT(n, 0);
  EXPECT_NEAR(sum / n, 1000.0 / 1.2e-3, 0.10 * 1000.0 / 1.2e-3);
}

}  // namespace
}  // namespace kinetofem::fem
