// Verification 2: the SPEC §1 lever-chain manipulator (a = 500, c = 350,
// h = 100, r = 75 mm; gripper 20 kg and casting 15 kg at H) at rest with
// rigid links and an elastic chain (EA = 2e6 N): the deflection of the
// gripper point H from the chain's elongation and the kinematics, by hand.
//
// Hand formula (small displacements, world axes, perp(v) = z x v = (-v_y, v_x)):
//   The structure is statically determinate, so the chain's tension is the
//   multibody model's, T_c (frame.chains), and it stretches by
//       delta = T_c / k,   k = EA / b,   b = |B0 - T| (free length, T the tangent point).
//   The lever turns about A0 by what its drive allows: 0 for a rigid drive,
//   dtheta_l = -effort / k_d for a torsional stiffness k_d (the spring's
//   moment -k_d dtheta_l on the lever is the drive effort of the multibody
//   model); A moves by u_A = dtheta_l perp(A - A0).
//   The chain, followed from T to its hinge B0 along n = (B0 - T) / b, gets
//   longer by n . (u_B0 - u_T) with u_B0 = 0 and u_T = u_A + dtheta_a perp(T - A)
//   (T a point of the roller, rigid with the arm). Setting it to delta:
//       dtheta_a = -(delta + n . u_A) / (n . perp(T - A)),
//   |n . perp(T - A)| = r, the chain's lever arm about A (it is tangent to
//   the roller): with a rigid drive the arm turns about A by delta / r.
//   Then u_H = u_A + dtheta_a perp(H - A).
// References and tolerances:
//   * links as rigid bodies (no parts): the same linear equations, 1e-10;
//   * links as HEX20 box parts with E x 1e6: their own bending adds ~1e-6 of
//     the steel parts' deflection, far below the chain's: 1e-6.
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include <Eigen/Geometry>

#include "kinetofem/mechanisms/multibody/chain_geometry.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

constexpr double kChainEA = 2e6;  // N (a steel roller chain or a toothed belt)

Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }

Eigen::Vector2d hand_deflection_of_h(const mech::ManipulatorDefinition& def, const mech::Frame& frame, double kd) {
  const mech::LeverChainGeometry& g = def.geometry;
  const Eigen::Vector2d A0 = Eigen::Vector2d::Zero();
  const Eigen::Vector2d A = frame.bodies[2].q.head<2>();  // arm origin
  const double theta_arm = frame.bodies[2].q.z();
  const Eigen::Vector2d H = A + Eigen::Rotation2Dd(theta_arm) * Eigen::Vector2d(-g.c_m, g.h_m);
  const Eigen::Vector2d B0 = g.b0_point_m;
  const mech::ChainTangent tangent = mech::chain_tangent(B0, A, g.r_m, +1.0);
  const Eigen::Vector2d T = tangent.tangent_point_m;
  const double b = tangent.free_length_m;
  const Eigen::Vector2d n = (B0 - T) / b;
  const double delta = frame.chains.at(0).tension_N / (kChainEA / b);
  const double dtheta_lever = std::isinf(kd) ? 0.0 : -frame.drives.at(0).effort / kd;
  const Eigen::Vector2d uA = dtheta_lever * perp(A - A0);
  const double lever_arm = n.dot(perp(T - A));
  EXPECT_NEAR(std::abs(lever_arm), g.r_m, 1e-12);
  const double dtheta_arm = -(delta + n.dot(uA)) / lever_arm;
  return uA + dtheta_arm * perp(H - A);
}

AssemblyOptions options_with(double kd, bool parts, BoreCoupling coupling = BoreCoupling::Distributing) {
  AssemblyOptions o;
  o.coupling = coupling;
  o.chains = {{"chain", kChainEA}};
  if (!std::isinf(kd)) o.drives = {{"lever_drive", kd}};
  o.points = {{"H", "arm", "H", parts ? "x0" : ""}};
  return o;
}

void expect_hand_formula(bool with_parts, double dphi, double kd, double tolerance,
                         BoreCoupling coupling = BoreCoupling::Distributing) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  std::vector<pipeline::Part> parts;
  if (with_parts) {
    parts = test::lever_chain_parts(def, test::steel(1e6));
    pipeline::apply_mass_properties(model, parts, Log::quiet());
  }
  const mech::Frame frame = pipeline::solve_static_pose(model, {dphi});
  ElasticAssembly assembly(parts, model, options_with(kd, with_parts, coupling));
  const PoseSolution pose = assembly.solve(frame);
  const Eigen::Vector2d expected = hand_deflection_of_h(def, frame, kd);
  const Eigen::Vector3d u = pose.point("H").displacement_m;
  const double error = (u.head<2>() - expected).norm() / expected.norm();
  std::printf(
      "  %s (%s), dphi = %.0f deg, k_d = %g N m/rad: |u_H| %.6e m (hand %.6e m), error %.2e; chain tension %.3f N "
      "(multibody %.3f N)\n",
      with_parts ? "parts E x 1e6" : "rigid bodies", name_of(coupling), dphi / test::kDeg, kd, u.head<2>().norm(), expected.norm(), error,
      pose.chain("chain").tension_n, frame.chains[0].tension_N);
  EXPECT_LT(error, tolerance);
  EXPECT_LT(std::abs(u.z()), tolerance * expected.norm());
  EXPECT_NEAR(pose.chain("chain").tension_n, frame.chains[0].tension_N, 1e-8 * frame.chains[0].tension_N);
}

TEST(ElasticAssemblyLeverChain, RigidBodiesDesignPoseMatchTheHandFormula) {
  expect_hand_formula(false, 0.0, kRigid, 1e-10);
}

TEST(ElasticAssemblyLeverChain, RigidBodiesTurnedPoseWithCompliantDriveMatchTheHandFormula) {
  expect_hand_formula(false, 20 * test::kDeg, 2e4, 1e-10);
}

TEST(ElasticAssemblyLeverChain, StiffPartsDesignPoseMatchTheHandFormula) {
  expect_hand_formula(true, 0.0, kRigid, 1e-6);
}

TEST(ElasticAssemblyLeverChain, StiffPartsTurnedPoseWithCompliantDriveMatchTheHandFormula) {
  expect_hand_formula(true, 20 * test::kDeg, 2e4, 1e-6);
}

// The same with kinematic (rigid-bore) couplings: with parts this stiff the
// coupling does not matter, so the hand formula holds to the same 1e-6.
TEST(ElasticAssemblyLeverChain, StiffPartsWithRigidBoresMatchTheHandFormula) {
  expect_hand_formula(true, 0.0, kRigid, 1e-6, BoreCoupling::RigidBore);
  expect_hand_formula(true, 20 * test::kDeg, 2e4, 1e-6, BoreCoupling::RigidBore);
}

}  // namespace
}  // namespace kinetofem::structure
