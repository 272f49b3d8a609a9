// ElasticAssembly (structure/elastic_assembly.hpp): interfaces, flexibility,
// the rigid-body path and the errors, on the small models of
// structure_fixtures.hpp.
#include <memory>

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "structure_fixtures.hpp"

namespace kinetofem::structure {
namespace {

using test::error_of;

struct Arm {
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
  std::vector<mech::Frame> frames;
};

Arm arm() {
  Arm a;
  a.parts = test::two_link_parts();
  a.model = test::two_link_arm();
  pipeline::apply_mass_properties(a.model, a.parts, Log::quiet());
  a.frames = mech::run_kinematics(mech::MultibodySystem(a.model), {0.1, 0.3}).frames;
  return a;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ElasticAssembly, InterfacesAreTheJointAndDriveEndsWithTheirReferencePoints) {
  const Arm a = arm();
  const ElasticAssembly assembly(a.parts, a.model);
  const std::vector<InterfaceInfo> in = assembly.interfaces();
  // J1 (link1), J2 (link1, link2), d1 (link1), d2 (link1, link2).
  ASSERT_EQ(in.size(), 6u);
  EXPECT_EQ(in[0].body, "link1");
  EXPECT_EQ(in[0].kind, "joint");
  EXPECT_EQ(in[0].name, "J1");
  EXPECT_EQ(in[0].face_set, "x0");
  EXPECT_TRUE(in[0].elastic);
  EXPECT_LT(in[0].reference_body_m.norm(), 1e-12);  // the joint point, centroid z = 0
  EXPECT_EQ(in[1].name, "J2");
  EXPECT_LT((in[1].reference_body_m - Eigen::Vector3d(0.3, 0, 0)).norm(), 1e-12);
  EXPECT_EQ(in[2].body, "link2");
  EXPECT_EQ(in[4].kind, "drive");
  EXPECT_EQ(in[4].name, "d2");
  EXPECT_LT((in[4].reference_body_m - Eigen::Vector3d(0.3, 0, 0)).norm(), 1e-12);  // face x1's centroid
}

TEST(ElasticAssembly, FlexibilityIsSymmetricAndPositiveSemidefinite) {
  // F = G^T K_s^-1 G: symmetric by construction (symmetrized to round-off,
  // checked before: 1e-10 of its largest entry), eigenvalues >= 0 (K_s SPD).
  const Arm a = arm();
  const ElasticAssembly assembly(a.parts, a.model);
  const Eigen::MatrixXd F = assembly.flexibility("link1");
  ASSERT_EQ(F.rows(), 6 * 4);  // J1, J2, d1, d2
  EXPECT_LT((F - F.transpose()).cwiseAbs().maxCoeff(), 1e-12 * F.cwiseAbs().maxCoeff());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(F);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-10 * eig.eigenvalues().maxCoeff());
  EXPECT_NE(error_of([&] { assembly.flexibility("frame"); }).find("no elastic part"), std::string::npos);
}

TEST(ElasticAssembly, ZeroLoadsGiveZeroDisplacement) {
  Arm a = arm();
  a.model.gravity = {0.0, 0.0};
  for (auto& b : a.model.bodies) b.point_masses.clear();
  a.parts[1].attachments.point_masses.clear();
  const mech::Frame rest = mech::run_kinematics(mech::MultibodySystem(a.model), {0.0}).frames.front();
  ElasticAssembly assembly(a.parts, a.model);
  const PoseSolution pose = assembly.solve(rest);
  EXPECT_EQ(pose.max_displacement_m, 0.0);
  EXPECT_EQ(pose.rank, pose.unknowns);
}

TEST(ElasticAssembly, SolvesEveryPoseWithOneSetupAndReportsTheCost) {
  const Arm a = arm();
  ElasticAssembly assembly(a.parts, a.model);
  const double setup = assembly.statistics().setup_seconds;
  const std::vector<PoseSolution> poses = assembly.solve(a.frames);
  const PoseSolution again = assembly.solve(a.frames[1]);
  const AssemblyStatistics& s = assembly.statistics();
  EXPECT_EQ(s.poses, 3);
  EXPECT_EQ(s.setup_seconds, setup);  // nothing re-factorized
  EXPECT_EQ(s.elastic_parts, 2);
  EXPECT_EQ(s.rigid_bodies, 0);
  EXPECT_EQ(s.interface_columns, 6 * 6);
  EXPECT_EQ(s.unknowns, poses[0].unknowns);
  EXPECT_GT(s.pose_seconds(), 0.0);
  // Same pose, same answer (the block solve and the single solve).
  EXPECT_LT((again.part("link2").displacement_m - poses[1].part("link2").displacement_m).cwiseAbs().maxCoeff(),
            1e-14 * poses[1].max_displacement_m);
}

TEST(ElasticAssembly, PartsSetUpOneAtATimeWithLentFactorsFreedAfterwardsGiveTheSameSolution) {
  // PartsLentOneByOne + set_up_part(body, factor) (pipeline::PartFactors'
  // path for parts whose factors do not fit in memory together; the lender
  // frees each factor after its set-up). Reference: the assembly set up at
  // construction with its own factors; the same solves in the same order, so
  // the same numbers bit for bit.
  const Arm a = arm();
  ElasticAssembly reference(a.parts, a.model);
  std::vector<fem::FeModel> supported;
  for (const auto& part : a.parts) {
    supported.push_back(part.model);
    std::vector<fem::Index> all(size_t(part.model.mesh.node_count()));
    for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
    supported.back().supports = fem::three_two_one_support(part.model.mesh, all);
  }
  std::vector<std::unique_ptr<fem::LinearStaticAnalysis>> factors;
  const Log quiet = Log::quiet();
  for (const auto& model : supported) factors.push_back(std::make_unique<fem::LinearStaticAnalysis>(model, quiet));
  ElasticAssembly assembly(a.parts, a.model, AssemblyOptions{}, Log::quiet(), PartsLentOneByOne{});
  EXPECT_FALSE(assembly.is_set_up());
  EXPECT_NE(error_of([&] { assembly.solve(a.frames); }).find("not set up yet"), std::string::npos);
  assembly.set_up_part("link1", *factors[0]);
  // Everything but set_up_part needs every part set up.
  EXPECT_NE(error_of([&] { assembly.flexibility("link1"); }).find("not set up yet"), std::string::npos);
  assembly.set_up_part("link2", *factors[1]);
  EXPECT_TRUE(assembly.is_set_up());
  EXPECT_NE(error_of([&] { assembly.set_up_part("link2", *factors[1]); }).find("set up already"), std::string::npos);
  EXPECT_NE(error_of([&] { assembly.set_up_part("frame", *factors[0]); }).find("no elastic part"), std::string::npos);
  // Superposed loads: no pose solves with the factors, so their lender frees them.
  EXPECT_FALSE(assembly.solves_with_factor("link1"));
  EXPECT_FALSE(assembly.solves_with_factor("link2"));
  for (auto& f : factors) f->release_factor();
  const std::vector<PoseSolution> expected = reference.solve(a.frames);
  const std::vector<PoseSolution> got = assembly.solve(a.frames);
  ASSERT_EQ(got.size(), expected.size());
  for (size_t f = 0; f < got.size(); ++f)
    for (const std::string body : {"link1", "link2"}) {
      EXPECT_EQ((got[f].part(body).displacement_m - expected[f].part(body).displacement_m).cwiseAbs().maxCoeff(), 0.0)
          << body << " pose " << f;
      EXPECT_EQ((got[f].part(body).von_mises_pa - expected[f].part(body).von_mises_pa).cwiseAbs().maxCoeff(), 0.0)
          << body << " pose " << f;
    }
}

TEST(ElasticAssembly, DisplacementIncludesTheRigidMotionFromTheJoints) {
  // A compliant drive d1 lets link1 turn about J1: link2's tip moves by about
  // the drive's twist times the distance from J1, far more than the
  // elastic bending of the bars with rigid drives.
  const Arm a = arm();
  AssemblyOptions soft;
  soft.drives = {{"d1", 500.0}};
  ElasticAssembly stiff_assembly(a.parts, a.model), soft_assembly(a.parts, a.model, soft);
  const PoseSolution stiff = stiff_assembly.solve(a.frames[0]);
  const PoseSolution loose = soft_assembly.solve(a.frames[0]);
  const double twist = loose.drive("d1").twist_rad;
  EXPECT_NEAR(twist, -a.frames[0].drives[0].effort / 500.0, 1e-9 * std::abs(twist));  // determinate
  const double reach = 0.6;  // J1 to link2's tip, about (bent arm: less)
  EXPECT_GT(loose.max_displacement_m, 0.5 * std::abs(twist) * reach);
  EXPECT_GT(loose.max_displacement_m, 5 * stiff.max_displacement_m);
  EXPECT_EQ(loose.max_displacement_body, "link2");
}

TEST(ElasticAssembly, RigidBodiesCarryTheMultibodyReactions) {
  // No parts: every moving body rigid. Statically determinate, so the joint
  // loads are the multibody reactions (1e-10) and nothing moves (rigid
  // bodies, rigid drives): zero displacement of a tracked point.
  const Arm a = arm();
  AssemblyOptions o;
  o.points = {{"tip", "link2", "tip", ""}};
  ElasticAssembly assembly({}, a.model, o);
  const PoseSolution pose = assembly.solve(a.frames[0]);
  EXPECT_TRUE(pose.parts.empty());
  const mech::JointFrame& j2 = a.frames[0].joints[1];
  EXPECT_LT((pose.joint("J2").force_on_j_n.head<2>() - j2.on_j.force_world).norm(), 1e-10 * j2.on_j.force_world.norm());
  EXPECT_LT(pose.point("tip").displacement_m.norm(), 1e-15);
  EXPECT_EQ(assembly.statistics().rigid_bodies, 2);
}

TEST(ElasticAssembly, FreeRotationIsAnErrorNamingTheJoint) {
  // d1 with zero stiffness: nothing holds link1's rotation about J1.
  const Arm a = arm();
  AssemblyOptions o;
  o.drives = {{"d1", 0.0}};
  ElasticAssembly assembly(a.parts, a.model, o);
  const std::string message = error_of([&] { assembly.solve(a.frames[0]); });
  std::printf("  %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "elastic assembly at t = 0.1 s: the structure is a mechanism (rank ")) << message;
  EXPECT_TRUE(contains(message, "joint 'J1'")) << message;
  EXPECT_TRUE(contains(message, "drive 'd1' (zero torsional stiffness)")) << message;
  EXPECT_FALSE(contains(message, "singular")) << message;
}

TEST(ElasticAssembly, MissingDriveIsAMechanismNamingTheFreeJoint) {
  // The model without d2 (and the parts without its attachments): link2
  // swings freely about J2.
  Arm a = arm();
  mech::MultibodyModel model = a.model;
  model.motion_drives.pop_back();
  for (auto& p : a.parts)
    std::erase_if(p.attachments.drives, [](const loads::DriveAttachment& d) { return d.drive == "d2"; });
  ElasticAssembly assembly(a.parts, model);
  const std::string message = error_of([&] { assembly.solve(a.frames[0]); });
  std::printf("  %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "nothing holds the rotation about z at joint 'J2' (between 'link1' and 'link2')"))
      << message;
  EXPECT_FALSE(contains(message, "joint 'J1'")) << message;
}

TEST(ElasticAssembly, RigidIndeterminateLoopIsAnErrorNamingItsJoints) {
  // Rigid bodies closed into a loop by a third pin: the joint loads have a
  // self-stress state nothing determines.
  const Arm a = arm();
  mech::MultibodyModel model = a.model;
  model.joints.push_back(mech::make_revolute("J3", "frame", "origin", "link2", "tip"));
  ElasticAssembly assembly({}, model);
  const std::string message = error_of([&] { assembly.solve(a.frames[0]); });
  std::printf("  %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "the joint loads cannot be determined")) << message;
  EXPECT_TRUE(contains(message, "joint 'J3'")) << message;
}

TEST(ElasticAssembly, SlackChainIsAnError) {
  // The lever-chain manipulator with gravity reversed: the arm's weight
  // turns it the other way and the chain would have to push.
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  model.gravity = -model.gravity;
  mech::KinematicOptions ko;
  ko.slack_is_error = false;
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(model), {0.0}, ko).frames.front();
  AssemblyOptions o;
  o.chains = {{"chain", 2e6}};
  ElasticAssembly assembly({}, model, o);
  const std::string message = error_of([&] { assembly.solve(frame); });
  std::printf("  %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "chain 'chain' would have to push")) << message;
}

TEST(ElasticAssembly, ChainWithoutStiffnessIsAnError) {
  const mech::MultibodyModel model = mech::make_manipulator_model(test::lever_chain_definition());
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly({}, model); }),
                       "chain 'chain' has no axial stiffness (AssemblyOptions::chains: EA in N)"));
  AssemblyOptions o;
  o.chains = {{"chain", -1.0}};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly({}, model, o); }), "must be positive"));
}

TEST(ElasticAssembly, PartWithoutFaceSetForAJointIsAnError) {
  Arm a = arm();
  a.parts[1].attachments.joints.clear();
  const std::string message = error_of([&] { ElasticAssembly(a.parts, a.model); });
  EXPECT_TRUE(
      contains(message, "part 'link2' (test bar): joint 'J2' acts on body 'link2' but the part names no face set"))
      << message;
}

TEST(ElasticAssembly, PartWithoutFaceSetForADriveIsAnError) {
  Arm a = arm();
  a.parts[1].attachments.drives.clear();
  const std::string message = error_of([&] { ElasticAssembly(a.parts, a.model); });
  EXPECT_TRUE(contains(message, "motion drive 'd2' acts on body 'link2' but the part names no face set")) << message;
}

TEST(ElasticAssembly, MissingLoadAttachmentIsAnErrorNamingThePartAndTime) {
  // link2 without its payload's attachment: its loads miss the payload's
  // weight and inertia, which the multibody body has.
  Arm a = arm();
  a.parts[1].attachments.point_masses.clear();
  ElasticAssembly assembly(a.parts, a.model);
  const std::string message = error_of([&] { assembly.solve(a.frames[0]); });
  std::printf("  %s\n", message.c_str());
  EXPECT_TRUE(contains(message, "part 'link2' (test bar) at t = 0.1 s: its loads without the joint reactions"))
      << message;
  // Without the check (infinite tolerance) it solves.
  AssemblyOptions o;
  o.load_check_tolerance = std::numeric_limits<double>::infinity();
  ElasticAssembly unchecked(a.parts, a.model, o);
  EXPECT_NO_THROW(unchecked.solve(a.frames[0]));
}

TEST(ElasticAssembly, UnsupportedJointsAndBadOptionsAreErrors) {
  const Arm a = arm();
  mech::MultibodyModel model = a.model;
  model.joints[1].type = mech::JointType::Prismatic;
  model.joints[1].axis_i = Eigen::Vector2d::Zero();
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly({}, model); }), "prismatic axis is zero"));
  AssemblyOptions o;
  o.slides = {{"J1", 0.1, 0.0}};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(a.parts, a.model, o); }), "not a prismatic joint"));
  o = {};
  DriveHold axial{"d2"};
  axial.axial_stiffness_n_per_m = 1e6;
  o.drives = {axial};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(a.parts, a.model, o); }), "drive 'd2' drives an angle"));
  o = {};
  o.drives = {{"nope", 1.0}};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(a.parts, a.model, o); }), "motion drive 'nope'"));
  o = {};
  o.chains = {{"J1", 1.0}};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(a.parts, a.model, o); }), "chain 'J1'"));
  o = {};
  o.points = {{"P", "link2", "tip", ""}};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(a.parts, a.model, o); }),
                       "tracked point 'P' on part 'link2' needs a face set"));
  o.points = {{"P", "link2", "nowhere", "x1"}};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(a.parts, a.model, o); }), "point 'nowhere'"));
  std::vector<pipeline::Part> twice = {a.parts[0], a.parts[0]};
  EXPECT_TRUE(contains(error_of([&] { ElasticAssembly(twice, a.model); }), "body 'link1' has two parts"));
}

TEST(ElasticAssembly, FrameOfAnotherModelIsAnError) {
  const Arm a = arm();
  const mech::MultibodyModel other = mech::make_manipulator_model(test::lever_chain_definition());
  AssemblyOptions o;
  o.chains = {{"chain", 2e6}};
  ElasticAssembly assembly({}, other, o);
  EXPECT_TRUE(contains(error_of([&] { assembly.solve(mech::Frame{}); }), "the frame has 0 bodies"));
}

}  // namespace
}  // namespace kinetofem::structure
