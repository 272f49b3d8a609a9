// Verification 4: the split of a tracked point's displacement into the
// contributions of the parts, the chain and the compliant drives (unit-load
// method, structure/elastic_assembly.hpp PointContribution), its compliance
// matrix, and the degree of static indeterminacy the assembly reports.
//
// References and tolerances:
//   * sum of the contributions = the point's displacement: an identity of
//     linear elasticity (virtual work, u_H . e_c = sum over the elements of the
//     unit load's internal loads times the real deformation); both sides come
//     from one factorized system, so round-off: 1e-10 of |u_H|;
//   * the compliance matrix is symmetric (Maxwell-Betti): 1e-10 of its norm;
//   * rigid links and a rigid drive, an elastic chain: the compliance of H is
//     w w^T / k with w = -perp(H - A) / (n . perp(T - A)) the motion of H per
//     unit chain elongation (the hand derivation of test_assembly_lever_chain.cpp)
//     and k = EA / b: 1e-10;
//   * indeterminacy, counted by hand: the lever-chain (pins O and A, the chain,
//     the drive; 2 bodies) is determinate in and out of the plane; the two-link
//     arm closed to the ground by a third pin J3 has 2 extra in-plane and 3 extra
//     out-of-plane unknowns.
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include <Eigen/Geometry>

#include "kinetofem/mechanisms/multibody/chain_geometry.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

constexpr double kChainEA = 2e6;  // N

Eigen::Vector3d sum_of(const PointResult& p) {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (const auto& c : p.contributions) s += c.displacement_m;
  return s;
}

const PointContribution& contribution(const PointResult& p, const std::string& name) {
  for (const auto& c : p.contributions)
    if (c.name == name) return c;
  ADD_FAILURE() << "no contribution " << name;
  return p.contributions.front();
}

void expect_split_adds_up(const PointResult& p, const char* what) {
  const double error = (sum_of(p) - p.displacement_m).norm() / p.displacement_m.norm();
  const double asymmetry =
      (p.compliance_m_per_n - p.compliance_m_per_n.transpose()).norm() / p.compliance_m_per_n.norm();
  std::printf("  %s: |u_%s| = %.4e m, sum of %zu contributions - u: %.2e relative; compliance asymmetry %.2e\n", what,
              p.name.c_str(), p.displacement_m.norm(), p.contributions.size(), error, asymmetry);
  for (const auto& c : p.contributions)
    std::printf("    %-18s (%+.4e, %+.4e, %+.4e) m\n", c.name.c_str(), c.displacement_m.x(), c.displacement_m.y(),
                c.displacement_m.z());
  EXPECT_LT(error, 1e-10) << what;
  EXPECT_LT(asymmetry, 1e-10) << what;
  EXPECT_GT(p.compliance_m_per_n(0, 0), 0.0);
  EXPECT_GT(p.compliance_m_per_n(1, 1), 0.0);
}

void expect_lever_chain_split_adds_up(BoreCoupling coupling) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  AssemblyOptions o;
  o.chains = {{"chain", kChainEA}};
  o.drives = {{"lever_drive", 2e4}};
  o.points = {{"H", "arm", "H", "x0"}};
  o.coupling = coupling;
  ElasticAssembly assembly(parts, model, o);
  for (const double dphi : {0.0, 20 * test::kDeg}) {
    const PoseSolution pose = assembly.solve(pipeline::solve_static_pose(model, {dphi}));
    const PointResult& h = pose.point("H");
    expect_split_adds_up(h, dphi == 0.0 ? "lever-chain, design pose" : "lever-chain, dphi = 20 deg");
    ASSERT_EQ(h.contributions.size(), 4u);  // lever, arm, chain, drive
    for (const char* name : {"part.lever", "part.arm", "chain.chain", "drive.lever_drive"})
      EXPECT_GT(contribution(h, name).displacement_m.norm(), 0.0) << name;
    EXPECT_EQ(pose.indeterminacy.in_plane, 0);
    EXPECT_EQ(pose.indeterminacy.out_of_plane, 0);
  }
}

TEST(ElasticAssemblyUnitLoad, LeverChainContributionsAddUpToTheDeflectionOfH) {
  expect_lever_chain_split_adds_up(BoreCoupling::Distributing);
}

TEST(ElasticAssemblyUnitLoad, LeverChainContributionsAddUpWithRigidBores) {
  expect_lever_chain_split_adds_up(BoreCoupling::RigidBore);
}

TEST(ElasticAssemblyUnitLoad, RigidLeverChainComplianceOfHIsTheChainsByHand) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  const mech::MultibodyModel model = mech::make_manipulator_model(def);
  AssemblyOptions o;
  o.chains = {{"chain", kChainEA}};
  o.points = {{"H", "arm", "H", ""}};
  ElasticAssembly assembly({}, model, o);
  const mech::Frame frame = pipeline::solve_static_pose(model, {10 * test::kDeg});
  const PoseSolution pose = assembly.solve(frame);
  const PointResult& h = pose.point("H");

  const mech::LeverChainGeometry& g = def.geometry;
  const Eigen::Vector2d A = frame.bodies[2].q.head<2>();
  const Eigen::Vector2d H = A + Eigen::Rotation2Dd(frame.bodies[2].q.z()) * Eigen::Vector2d(-g.c_m, g.h_m);
  const mech::ChainTangent tangent = mech::chain_tangent(g.b0_point_m, A, g.r_m, +1.0);
  const Eigen::Vector2d T = tangent.tangent_point_m, n = (g.b0_point_m - T) / tangent.free_length_m;
  auto perp = [](const Eigen::Vector2d& v) { return Eigen::Vector2d(-v.y(), v.x()); };
  const Eigen::Vector2d w = -perp(H - A) / n.dot(perp(T - A));
  const Eigen::Matrix2d expected = w * w.transpose() / (kChainEA / tangent.free_length_m);
  const double error = (h.compliance_m_per_n.topLeftCorner<2, 2>() - expected).norm() / expected.norm();
  std::printf("  rigid lever-chain, dphi = 10 deg: compliance of H vs w w^T / k: %.2e relative (C_xx %.4e m/N)\n", error,
              h.compliance_m_per_n(0, 0));
  EXPECT_LT(error, 1e-10);
  // Everything is rigid but the chain: it is the only contribution.
  ASSERT_EQ(h.contributions.size(), 1u);
  EXPECT_LT((h.contributions[0].displacement_m - h.displacement_m).norm(), 1e-10 * h.displacement_m.norm());
}

TEST(ElasticAssemblyUnitLoad, ClosedLoopArmIsIndeterminateAndItsSplitStillAddsUp) {
  test::TwoLinkArm a;
  mech::MultibodyModel model = test::two_link_arm(a);
  std::vector<pipeline::Part> parts = test::two_link_parts(a);
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(model), {0.2}).frames;
  model.bodies[0].points["anchor"] = {0.0, 0.0};
  model.joints.push_back(mech::make_revolute("J3", "frame", "anchor", "link2", "tip"));
  parts[1].attachments.joints.push_back({"J3", "x1"});
  AssemblyOptions o;
  o.drives = {{"d2", 2000.0}};
  o.points = {{"mid", "link2", "origin", "x0"}};
  ElasticAssembly assembly(parts, model, o);
  const PoseSolution pose = assembly.solve(frames.front());
  expect_split_adds_up(pose.point("mid"), "closed-loop arm");
  EXPECT_EQ(pose.indeterminacy.in_plane, 2);
  EXPECT_EQ(pose.indeterminacy.out_of_plane, 3);
}

}  // namespace
}  // namespace kinetofem::structure
