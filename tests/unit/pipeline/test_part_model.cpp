// Stage "build the part models" (pipeline/part_model.hpp): placing a mesh in
// its body frame, the bodies' mass properties from their parts, and the fit
// checks of a part against the multibody model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinetofem/pipeline/manipulator_preset.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

using test::BeamSize;
using test::error_of;
using test::kDeg;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

fem::Index node_at(const fem::Mesh& mesh, const Eigen::Vector3d& x) {
  for (fem::Index i = 0; i < mesh.node_count(); ++i)
    if ((mesh.nodes.row(i).transpose() - x).norm() < 1e-12) return i;
  return -1;
}

mech::Body* body_named(mech::MultibodyModel& model, const std::string& name) {
  for (auto& b : model.bodies)
    if (b.name == name) return &b;
  return nullptr;
}

// ---- place_mesh -------------------------------------------------------------

TEST(PlaceMesh, QuarterTurnAndOffsetMoveAKnownNodeExactly) {
  testing::BoxMeshOptions box;
  box.length_m = {0.3, 0.04, 0.02};
  box.divisions = {3, 2, 1};
  fem::Mesh mesh = testing::box_mesh(box);
  const fem::Index corner = node_at(mesh, {0.3, 0.04, 0.02});
  ASSERT_GE(corner, 0);
  place_mesh(mesh, {{0.1, -0.2, 0.0}, 90 * kDeg});
  // Reference: x_body = R_z(90 deg) x + offset (part_model.hpp):
  // (0.3, 0.04, 0.02) -> (-0.04 + 0.1, 0.3 - 0.2, 0.02). Tolerance 1e-15 m:
  // cos(pi/2) = 6e-17 in double, times 0.3 m, plus the sums' round-off.
  EXPECT_NEAR(mesh.nodes(corner, 0), 0.06, 1e-15);
  EXPECT_NEAR(mesh.nodes(corner, 1), 0.10, 1e-15);
  EXPECT_EQ(mesh.nodes(corner, 2), 0.02);  // z untouched: the turn is about z (exact)
}

TEST(PlaceMesh, OffsetAlongThePinAxesPutsThePartInItsOwnPlane) {
  testing::BoxMeshOptions box;
  box.length_m = {0.3, 0.04, 0.02};
  box.divisions = {3, 2, 1};
  fem::Mesh mesh = testing::box_mesh(box);
  const fem::Index corner = node_at(mesh, {0.3, 0.04, 0.02});
  ASSERT_GE(corner, 0);
  place_mesh(mesh, {{0.0, 0.0, 0.04}, 0.0});
  // Reference: x_body = x + (0, 0, 40 mm); a sum of two doubles (1e-17 m).
  EXPECT_EQ(mesh.nodes(corner, 0), 0.3);
  EXPECT_EQ(mesh.nodes(corner, 1), 0.04);
  EXPECT_NEAR(mesh.nodes(corner, 2), 0.06, 1e-17);
}

TEST(PlaceMesh, LeavesConnectivityAndEverySetUnchanged) {
  testing::BoxMeshOptions box;
  box.divisions = {2, 2, 1};
  const fem::Mesh before = testing::box_mesh(box);
  fem::Mesh after = before;
  place_mesh(after, {{1.0, 2.0, 0.0}, 30 * kDeg});
  ASSERT_FALSE(after.nodes.isApprox(before.nodes));  // it did move the nodes
  ASSERT_EQ(after.blocks.size(), before.blocks.size());
  EXPECT_EQ(after.blocks.front().connectivity, before.blocks.front().connectivity);
  EXPECT_EQ(after.node_sets, before.node_sets);
  EXPECT_EQ(after.element_sets, before.element_sets);
  ASSERT_EQ(after.face_sets.size(), before.face_sets.size());
  for (const auto& [name, faces] : before.face_sets) {
    ASSERT_TRUE(after.face_sets.contains(name)) << name;
    ASSERT_EQ(after.face_sets.at(name).size(), faces.size()) << name;
    for (std::size_t k = 0; k < faces.size(); ++k)
      EXPECT_EQ(after.face_sets.at(name)[k].connectivity, faces[k].connectivity) << name;
  }
  // Distances are kept: a rigid motion (exact up to round-off, 1e-15 m).
  const double d0 = (before.nodes.row(0) - before.nodes.row(before.node_count() - 1)).norm();
  const double d1 = (after.nodes.row(0) - after.nodes.row(after.node_count() - 1)).norm();
  EXPECT_NEAR(d1, d0, 1e-15);
}

// ---- build_part_models (checks before any meshing) --------------------------

TEST(BuildPartModels, TwoPartsOnOneBodyIsAnErrorNamingTheBody) {
  PartSpec a, b;
  a.source = b.source = PartSource::Lever;
  a.attachments.body = b.attachments.body = "crank";
  a.label = "part 'crank' (first)";
  b.label = "part 'crank' (second)";
  const std::string message = error_of([&] { build_part_models({a, b}, test::steel(), {}, Log::quiet()); });
  EXPECT_TRUE(contains(message, "part 'crank' (second): body 'crank' has a second part")) << message;
}

TEST(BuildPartModels, ImpossibleLeverDimensionsNameThePart) {
  PartSpec lever;
  lever.source = PartSource::Lever;
  lever.attachments.body = "lever";
  lever.label = "part 'lever' (test)";
  lever.lever.width_m = 0.2;  // wider than the bosses (0.09 m): validate() rejects it before Gmsh runs
  const std::string message = error_of([&] { build_part_models({lever}, test::steel(), {}, Log::quiet()); });
  EXPECT_TRUE(contains(message, "part 'lever' (test): ")) << message;
  EXPECT_TRUE(contains(message, "width_m")) << message;
}

// ---- apply_mass_properties ----------------------------------------------------

TEST(ApplyMassProperties, BodyGetsTheMeshMassCentreAndInertia) {
  const BeamSize size;
  const Part part = test::beam_part("beam", test::beam_pendulum_attachments(), size);
  mech::MultibodyModel model = test::beam_pendulum();
  apply_mass_properties(model, {part}, Log::quiet());
  const mech::Body& body = *body_named(model, "beam");
  // Reference 1: fem::mass_properties of the same mesh (solver/rigid_body.hpp),
  // which the stage must pass on unchanged (1e-12 relative: round-off).
  const fem::MassProperties mp = fem::mass_properties(part.model.mesh, part.model.material);
  EXPECT_NEAR(body.mass_kg, mp.mass_kg, 1e-12 * mp.mass_kg);
  EXPECT_NEAR(body.inertia_kgm2, mp.inertia_about_com_kgm2(2, 2), 1e-12 * mp.inertia_about_com_kgm2(2, 2));
  EXPECT_NEAR((body.com_body - mp.centre_of_mass_m.head<2>()).norm(), 0.0, 1e-15);
  // Reference 2 (analytic): a homogeneous box of L x H x T, rho = 7850, centred
  // at (L/2, 0): m = rho L H T, I_zz = m (L^2 + H^2) / 12. The HEX20 Gauss
  // rules are exact for this straight-sided mesh: 1e-12 relative (round-off).
  const double rho = 7850.0, L = size.length_m, H = size.height_m, T = size.thickness_m;
  const double m = rho * L * H * T;
  EXPECT_NEAR(body.mass_kg, m, 1e-12 * m);
  EXPECT_NEAR(body.inertia_kgm2, m * (L * L + H * H) / 12.0, 1e-12 * m * (L * L + H * H) / 12.0);
  EXPECT_NEAR(body.com_body.x(), L / 2, 1e-12 * L);  // summation round-off over the elements
  EXPECT_NEAR(body.com_body.y(), 0.0, 1e-12 * L);
  // The point mass stays the model's own (added by the multibody model, not the mesh).
  ASSERT_EQ(body.point_masses.size(), 1u);
  EXPECT_EQ(body.point_masses[0].mass_kg, 2.0);
}

TEST(ApplyMassProperties, PlacedMeshMovesTheCentreOfMass) {
  // A part turned by 90 deg about the body origin: its centre of mass moves
  // from (L/2, 0) to (0, L/2); I_zz about the centre is unchanged (analytic;
  // 1e-12 relative: the sums over the elements and the turn's round-off).
  Part part = test::beam_part("beam", test::beam_pendulum_attachments());
  place_mesh(part.model.mesh, {{0.0, 0.0, 0.0}, 90 * kDeg});
  part.mass = fem::mass_properties(part.model.mesh, part.model.material);
  mech::MultibodyModel model = test::beam_pendulum();
  apply_mass_properties(model, {part}, Log::quiet());
  const mech::Body& body = *body_named(model, "beam");
  EXPECT_NEAR(body.com_body.x(), 0.0, 1e-12 * 0.3);
  EXPECT_NEAR(body.com_body.y(), 0.15, 1e-12 * 0.3);
  const double m = 7850.0 * 0.3 * 0.04 * 0.02, izz = m * (0.3 * 0.3 + 0.04 * 0.04) / 12.0;
  EXPECT_NEAR(body.inertia_kgm2, izz, 1e-12 * izz);
}

TEST(ApplyMassProperties, CaseValuesAreKeptWhenMassDoesNotComeFromTheMesh) {
  Part part = test::beam_part("beam", test::beam_pendulum_attachments());
  PartSpec spec;
  spec.mass_from_mesh = false;
  mech::MultibodyModel model = test::beam_pendulum();
  mech::Body& body = *body_named(model, "beam");
  body.mass_kg = 3.25;
  body.inertia_kgm2 = 0.0421;
  body.com_body = {0.11, 0.002};
  apply_mass_properties(model, {part}, Log::quiet(), {spec});
  EXPECT_EQ(body.mass_kg, 3.25);
  EXPECT_EQ(body.inertia_kgm2, 0.0421);
  EXPECT_EQ(body.com_body, Eigen::Vector2d(0.11, 0.002));
}

TEST(ApplyMassProperties, CaseValuesMustBeGivenWhenMassDoesNotComeFromTheMesh) {
  Part part = test::beam_part("beam", test::beam_pendulum_attachments());
  PartSpec spec;
  spec.mass_from_mesh = false;
  mech::MultibodyModel model = test::beam_pendulum();
  body_named(model, "beam")->mass_kg = 0.0;
  const std::string message = error_of([&] { apply_mass_properties(model, {part}, Log::quiet(), {spec}); });
  EXPECT_TRUE(contains(message, "part 'beam' (test beam): mass_properties = \"case\" needs the body's mass_kg > 0"))
      << message;
}

TEST(ApplyMassProperties, PartOnTheGroundWithoutFoundationIsAnErrorNamingIt) {
  const Part part = test::beam_part("frame", test::beam_pendulum_attachments());
  mech::MultibodyModel model = test::beam_pendulum();
  const std::string message = error_of([&] { apply_mass_properties(model, {part}, Log::quiet()); });
  EXPECT_TRUE(contains(message, "part 'frame' (test beam): body 'frame' is the ground: a part on it is the frame and needs held_face"))
      << message;
}

TEST(ApplyMassProperties, FramePartLeavesTheGroundOutOfTheDynamics) {
  // The ground does not move: a frame part's mass must not reach the model.
  Part part = test::beam_part("frame", test::beam_pendulum_attachments());
  part.held_face = "x0";
  mech::MultibodyModel model = test::beam_pendulum();
  const mech::MultibodyModel before = model;
  EXPECT_NO_THROW(apply_mass_properties(model, {part}, Log::quiet()));
  for (std::size_t b = 0; b < model.bodies.size(); ++b) {
    EXPECT_EQ(model.bodies[b].mass_kg, before.bodies[b].mass_kg) << model.bodies[b].name;
    EXPECT_EQ(model.bodies[b].inertia_kgm2, before.bodies[b].inertia_kgm2) << model.bodies[b].name;
  }
}

TEST(ApplyMassProperties, PartOnAMissingBodyIsAnErrorNamingIt) {
  const Part part = test::beam_part("crank", test::beam_pendulum_attachments());
  mech::MultibodyModel model = test::beam_pendulum();
  const std::string message = error_of([&] { apply_mass_properties(model, {part}, Log::quiet()); });
  EXPECT_TRUE(contains(message, "part 'crank' (test beam): the mechanism has no body 'crank'")) << message;
}

// ---- check_part_against_model ---------------------------------------------------

TEST(CheckPartAgainstModel, BeamOnItsTwoJointsPasses) {
  // The control case of the failures below: the same beam, correctly placed.
  const Part part = test::beam_part("beam", test::double_link_attachments());
  EXPECT_NO_THROW(check_part_against_model(part, test::double_link()));
}

TEST(CheckPartAgainstModel, MissingFaceSetListsTheSetsThePartHas) {
  const Part part = test::beam_part("beam", {"beam", nullptr, {{"J1", "x0"}, {"J2", "bore_B"}}});
  const std::string message = error_of([&] { check_part_against_model(part, test::double_link()); });
  EXPECT_TRUE(contains(message, "part 'beam' (test beam): joint 'J2' acts through face set 'bore_B', which the part "
                                "does not have (it has: x0, x1, y0, y1, z0, z1)"))
      << message;
}

TEST(CheckPartAgainstModel, NodeOrElementSetIsNotASurface) {
  // "boundary" is a node set only (box_mesh.hpp); "beam" an element set added here.
  for (const std::string set : {"boundary", "beam"}) {
    Part part = test::beam_part("beam", {"beam", nullptr, {{"J1", "x0"}}, {}, {{"drive", set}}});
    std::vector<fem::Index> all(std::size_t(part.model.mesh.element_count()));
    for (std::size_t e = 0; e < all.size(); ++e) all[e] = fem::Index(e);
    part.model.mesh.element_sets["beam"] = all;
    const std::string message = error_of([&] { check_part_against_model(part, test::double_link()); });
    EXPECT_TRUE(contains(message, "drive 'drive' acts through '" + set + "', which is not a surface of the part"))
        << message;
    EXPECT_TRUE(contains(message, "surface sets: x0, x1, y0, y1, z0, z1")) << message;
  }
}

TEST(CheckPartAgainstModel, JointFarFromItsBoreNamesTheJointAndTheDistance) {
  // The beam placed 30 mm off its axis: joint J1 at the body origin is 30 mm
  // from the centre of face x0 (analytic: the face's nodes are symmetric about
  // y = 0.03 after the offset), far beyond half the face's mean radius (~5 mm).
  Part part = test::beam_part("beam", test::double_link_attachments());
  place_mesh(part.model.mesh, {{0.0, 0.03, 0.0}, 0.0});
  const std::string message = error_of([&] { check_part_against_model(part, test::double_link()); });
  EXPECT_TRUE(contains(message, "part 'beam' (test beam): joint 'J1' at (0.000, 0.000) mm (body frame) lies 30.000 mm "
                                "from the centre of its face set 'x0'"))
      << message;
}

TEST(CheckPartAgainstModel, PartInTheWrongLengthUnitShowsAsASizeMismatch) {
  // The joints are 300 mm apart; the part 1000 times too small (a mm drawing
  // read as m the other way round) or too large (mm read as m).
  for (const double scale : {1e-3, 1e3}) {
    Part part = test::beam_part("beam", test::double_link_attachments());
    part.model.mesh.nodes *= scale;
    const std::string message = error_of([&] { check_part_against_model(part, test::double_link()); });
    EXPECT_TRUE(contains(message, "its load points 'J1' and 'J2' are 300 mm apart: is its length unit right?"))
        << scale << ": " << message;
  }
}

TEST(CheckPartAgainstModel, UnknownJointIsAnErrorNamingIt) {
  const Part part = test::beam_part("beam", {"beam", nullptr, {{"J1", "x0"}, {"J9", "x1"}}});
  const std::string message = error_of([&] { check_part_against_model(part, test::double_link()); });
  EXPECT_TRUE(contains(message, "the mechanism has no joint 'J9'")) << message;
}

// The SPEC §1 (lever-chain) and §2 (lever) presets meshed coarsely (20 mm,
// linear tetrahedra): every part fits its model as the preset places it.
const std::vector<Part>& preset_parts(mech::ManipulatorType type) {
  static const auto build = [](mech::ManipulatorType t) {
    meshes::MeshOptions options;
    options.element_size_m = 0.02;
    options.order = 1;
    options.optimize = false;
    return build_part_models(manipulator_parts(test::lever_chain_definition(t), {}), test::steel(), options,
                             Log::quiet());
  };
  static const std::vector<Part> chain = build(mech::ManipulatorType::LeverChain);
  static const std::vector<Part> lever = build(mech::ManipulatorType::Lever);
  return type == mech::ManipulatorType::LeverChain ? chain : lever;
}

TEST(CheckPartAgainstModel, Spec1LeverChainPresetPasses) {
  mech::MultibodyModel model = mech::make_manipulator_model(test::lever_chain_definition());
  const std::vector<Part>& parts = preset_parts(mech::ManipulatorType::LeverChain);
  ASSERT_EQ(parts.size(), 2u);
  apply_mass_properties(model, parts, Log::quiet());
  for (const Part& part : parts) EXPECT_NO_THROW(check_part_against_model(part, model)) << part.label;
}

TEST(CheckPartAgainstModel, Spec2LeverPresetPasses) {
  mech::MultibodyModel model = mech::make_manipulator_model(test::lever_chain_definition(mech::ManipulatorType::Lever));
  const std::vector<Part>& parts = preset_parts(mech::ManipulatorType::Lever);
  ASSERT_EQ(parts.size(), 3u);
  apply_mass_properties(model, parts, Log::quiet());
  for (const Part& part : parts) EXPECT_NO_THROW(check_part_against_model(part, model)) << part.label;
}

TEST(CheckPartAgainstModel, Spec1LeverTurnedByAQuarterFailsAtJointA) {
  // The lever's mesh turned by 90 deg about A0: bore A moves from (0, a) to
  // (-a, 0), so joint A at (0, a) lies a sqrt(2) = 707.107 mm from its axis.
  // The check measures from the mean of the bore's nodes, which lies within
  // the bore radius (20 mm) of the axis: the distance must be 707.107 +- 20 mm.
  const mech::MultibodyModel model = mech::make_manipulator_model(test::lever_chain_definition());
  Part lever = preset_parts(mech::ManipulatorType::LeverChain).front();
  ASSERT_EQ(lever.body(), "lever");
  place_mesh(lever.model.mesh, {{0.0, 0.0, 0.0}, 90 * kDeg});
  const std::string message = error_of([&] { check_part_against_model(lever, model); });
  const std::string head = "joint 'A' at (0.000, 500.000) mm (body frame) lies ";
  const std::size_t at = message.find(head);
  ASSERT_NE(at, std::string::npos) << message;
  EXPECT_NEAR(std::stod(message.substr(at + head.size())), 500.0 * std::numbers::sqrt2, 20.0) << message;
  EXPECT_TRUE(contains(message, "mm from the centre of its face set 'bore_A'")) << message;
}

}  // namespace
}  // namespace kinetofem::pipeline
