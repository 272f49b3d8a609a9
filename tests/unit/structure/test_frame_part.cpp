// The frame as a part of the ground in ElasticAssembly
// (structure/elastic_assembly.hpp): its interfaces, its held flexibility,
// no rigid motion, and the errors, on the two-link arm of
// structure_fixtures.hpp standing on a small column.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "structure_fixtures.hpp"

namespace kinetofem::structure {
namespace {

using test::error_of;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// A column 0.4 m high under the frame's origin (J1, d1 on its top face y1),
// its foot y0 the foundation.
pipeline::Part column(const std::string& held_face = "y0") {
  testing::BoxMeshOptions box;
  box.type = fem::ElementType::Hex20;
  box.length_m = {0.04, 0.4, 0.04};
  box.divisions = {2, 8, 2};
  fem::Mesh mesh = testing::box_mesh(box);
  mesh.nodes.col(0).array() -= 0.02;
  mesh.nodes.col(1).array() -= 0.4;
  mesh.nodes.col(2).array() -= 0.02;
  pipeline::Part part =
      test::mesh_part("frame", {"frame", nullptr, {{"J1", "y1"}}, {}, {{"d1", "y1"}}}, std::move(mesh), test::steel());
  part.held_face = held_face;
  return part;
}

struct ArmOnColumn {
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
  mech::Frame frame;
};

ArmOnColumn arm_on_column() {
  ArmOnColumn a;
  a.model = test::two_link_arm();
  a.parts = test::two_link_parts();
  a.parts.push_back(column());
  pipeline::apply_mass_properties(a.model, a.parts, Log::quiet());  // the frame's: printed only
  a.frame = mech::run_kinematics(mech::MultibodySystem(a.model), {0.2}).frames.front();
  return a;
}

TEST(ElasticAssemblyFrame, TheGroundJointAndDriveActOnTheFramesBore) {
  const ArmOnColumn a = arm_on_column();
  EXPECT_EQ(a.model.bodies[0].mass_kg, 0.0);  // no mass properties go into the ground
  ElasticAssembly assembly(a.parts, a.model);
  int on_frame = 0;
  for (const InterfaceInfo& i : assembly.interfaces())
    if (i.body == "frame") {
      ++on_frame;
      EXPECT_TRUE(i.elastic);
      EXPECT_EQ(i.face_set, "y1");
      EXPECT_LT(i.reference_body_m.norm(), 1e-12);  // J1 at the frame's origin, the face's centroid z = 0
    }
  EXPECT_EQ(on_frame, 2);  // J1 and d1
  // Held on its foundation: the flexibility is positive definite (no rigid modes).
  const Eigen::MatrixXd F = assembly.flexibility("frame");
  EXPECT_LT((F - F.transpose()).norm(), 1e-12 * F.norm());
  const Eigen::VectorXd translational = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(F.topLeftCorner(3, 3)).eigenvalues();
  EXPECT_GT(translational.minCoeff(), 0.0);
  EXPECT_EQ(assembly.statistics().elastic_parts, 3);
  EXPECT_EQ(assembly.statistics().rigid_bodies, 0);
}

TEST(ElasticAssemblyFrame, TheFrameHasNoRigidMotionAndItsFootStays) {
  const ArmOnColumn a = arm_on_column();
  ElasticAssembly assembly(a.parts, a.model);
  const PoseSolution pose = assembly.solve(a.frame);
  for (const BodyMotion& b : pose.bodies) EXPECT_NE(b.body, "frame");  // moving bodies only
  const PartField& field = pose.part("frame");
  for (const fem::Index n : fem::nodes_of_faces(a.parts[2].model.mesh.face_set("y0")))
    EXPECT_EQ(field.displacement_m.row(n).norm(), 0.0);
  EXPECT_GT(field.max_displacement_m, 0.0);
  // The ground side of J1 is the interface load on the frame: equal and
  // opposite to link1's side (a pin between the two interfaces).
  const JointLoad& j1 = pose.joint("J1");
  EXPECT_LT((j1.force_on_i_n + j1.force_on_j_n).norm(), 1e-9 * j1.force_on_j_n.norm());
}

TEST(ElasticAssemblyFrame, FramePartErrorsNameThePartAndTheFace) {
  const ArmOnColumn a = arm_on_column();
  std::vector<pipeline::Part> parts = a.parts;
  parts[2].held_face.clear();
  std::string message = error_of([&] { ElasticAssembly(parts, a.model); });
  EXPECT_TRUE(contains(message, "a part of the ground (a frame) needs held_face")) << message;
  parts[2].held_face = "foot";
  message = error_of([&] { ElasticAssembly(parts, a.model); });
  EXPECT_TRUE(contains(message, "held_face 'foot': mesh has no face set 'foot'")) << message;
  parts = a.parts;
  parts[0].held_face = "x0";
  message = error_of([&] { ElasticAssembly(parts, a.model); });
  EXPECT_TRUE(contains(message, "held_face 'x0' is for a part of the ground (a frame); body 'link1' moves")) << message;
  // A frame that names no face for a ground joint: the joint acts on it, so that is an error.
  parts = a.parts;
  parts[2].attachments.joints.clear();
  message = error_of([&] { ElasticAssembly(parts, a.model); });
  EXPECT_TRUE(contains(message, "joint 'J1' acts on body 'frame' but the part names no face set")) << message;
}

TEST(ElasticAssemblyFrame, AFrameNoJointActsOnIsAnError) {
  // A second fixed body carries the frame; every joint goes to the other one.
  ArmOnColumn a = arm_on_column();
  mech::Body base;
  base.name = "base";
  base.fixed = true;
  a.model.bodies.push_back(base);
  std::vector<pipeline::Part> parts = a.parts;
  parts[2].attachments = {"base", nullptr, {}, {}, {}};
  parts[2].label = "part 'base' (test column)";
  const std::string message = error_of([&] { ElasticAssembly(parts, a.model); });
  EXPECT_TRUE(contains(message, "no joint, chain or drive of the mechanism acts on the frame (body 'base')")) << message;
}

}  // namespace
}  // namespace kinetofem::structure
