// The elastic assembly of one pose written as a CalculiX deck
// (structure/calculix_assembly_export.hpp) and solved by ccx where it is
// installed (skipped otherwise; `apt-get install calculix-ccx`): the SPEC §1
// lever-chain manipulator with coarse HEX20 box parts (tests/unit/structure/
// structure_fixtures.hpp), turned 20 deg, gripper and casting at H, an elastic
// chain and the lever's drive.
//
// Reference: CalculiX 2.20 on the identical deck — the same meshes, material
// and nodal loads, the distributing couplings written as their motion
// definition (*EQUATION), the joints' and drive's constraint rows, the chain
// and drive springs. It solves the full, unreduced problem with none of
// kinetofem's condensation (no 3-2-1 support, flexibility or dense pose
// system), so agreement checks the condensation, the rotation into world
// axes, the pins' offset terms and the springs.
// Tolerances: H's displacement, every part node's displacement and the
// peak von Mises stress over the integration points (C3D20: the same 27
// points as kinetofem's HEX20) within 1e-5. The comparison is asked to meet
// 0.5 %; the two programs solve the same discrete problem, so they agree to
// what ccx prints (7 significant digits in its .dat file, about 1e-7 here),
// and 1e-5 leaves a hundred times that for round-off. The peak at the
// NODES is printed, not compared: each program extrapolates the
// integration-point stresses to the nodes its own way (kinetofem a trilinear
// least-squares fit, stress_recovery.hpp), and at this coarse mesh ccx's
// nodal peaks lie 4-7 % above kinetofem's.
// Two variants: both links elastic (the arm's half at H aluminium, a solid
// of its own material) with a rigid drive; the lever elastic,
// the arm a rigid body (its interfaces tied to its node pair) and the drive
// a torsional spring (a second SPRING1 beside the chain's). And the
// two-link arm in motion (d'Alembert loads) on a column frame part held at
// its foot (the foundation as *BOUNDARY), and with its second link 40 mm
// out of the first's plane (an elastic Timoshenko pin between the bores at
// different z, a spring of S: SPRING1 terms in the deck).
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include <unistd.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/calculix_run.hpp"
#include "kinetofem/structure/calculix_assembly_export.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

namespace fs = std::filesystem;

constexpr double kChainEA = 2e6;  // N

struct ScratchDir : kinetofem::testing::CcxScratchDir {
  ScratchDir() : CcxScratchDir("kinetofem_assembly_ccx") {}
};
using kinetofem::testing::have_ccx;
using kinetofem::testing::read_text;
using kinetofem::testing::run_ccx;

size_t interface_of(const ElasticAssembly& assembly, const std::string& kind, const std::string& name) {
  const std::vector<InterfaceInfo> all = assembly.interfaces();
  for (size_t k = 0; k < all.size(); ++k)
    if (all[k].kind == kind && all[k].name == name) return k;
  ADD_FAILURE() << "no " << kind << " interface '" << name << "'";
  return 0;
}

// What ccx's solution of the deck of `pose` must agree with: the tracked
// point, every part's nodal displacements and its peak von Mises stress over
// the integration points (1e-5); the nodal peaks printed.
void expect_agreement(const std::string& what, const ElasticAssembly& assembly, const std::vector<Part>& parts,
                      const mech::MultibodyModel& model, const mech::Frame& frame, const PoseSolution& pose,
                      const std::string& point) {
  ScratchDir dir;
  AssemblyDeckOptions deck_options;
  deck_options.print_part_displacements = true;
  const AssemblyDeck deck =
      write_calculix_assembly_deck(assembly, parts, model, frame, dir.path / "pose.inp", deck_options);
  const double ccx_seconds = run_ccx(dir.path, "pose");
  ASSERT_GE(ccx_seconds, 0.0) << read_text(dir.path / "pose.log");
  const AssemblyDeckResults ccx = read_calculix_assembly_results(deck, dir.path / "pose");

  const size_t h = interface_of(assembly, "point", point);
  const Eigen::Vector3d ours = pose.point(point).displacement_m;
  const Eigen::Vector3d theirs = ccx.interface_motion[h].head<3>();
  const double du = (theirs - ours).norm() / ours.norm();
  std::printf("  %s: %lld nodes, %d equations (%lld terms), %d springs, %d held DoFs, largest dropped %.1e; "
              "ccx %.2f s\n  u_%s kinetofem (%.6e, %.6e, %.6e) m, ccx (%.6e, %.6e, %.6e) m, difference %.2e\n",
              what.c_str(), deck.node_count, deck.equations, deck.equation_terms, deck.springs, deck.boundaries,
              deck.largest_dropped, ccx_seconds, point.c_str(), ours.x(), ours.y(), ours.z(), theirs.x(),
              theirs.y(), theirs.z(), du);
  EXPECT_LT(du, 1e-5);

  for (size_t p = 0; p < parts.size(); ++p) {
    const PartField& field = pose.part(parts[p].body());
    const double nodal_ours = field.von_mises_pa.maxCoeff();
    const double nodal_theirs = ccx.nodal_von_mises_pa.at(p).maxCoeff();
    const double gauss_ours = kinetofem::testing::peak_gauss_von_mises(parts[p].model, field.displacement_m, deck.parts[p].rotation);
    const double gauss_theirs = ccx.peak_gauss_von_mises_pa.at(p);
    const double dfield = (ccx.displacement_m[p] - field.displacement_m).cwiseAbs().maxCoeff() /
                          field.displacement_m.cwiseAbs().maxCoeff();
    std::printf("  %s: peak von Mises at the integration points %.6e Pa (ccx %.6e Pa, %.2e), at the nodes %.6e Pa "
                "(ccx %.6e Pa, %.2e); largest nodal displacement difference %.2e of the largest\n",
                parts[p].body().c_str(), gauss_ours, gauss_theirs, gauss_theirs / gauss_ours - 1, nodal_ours,
                nodal_theirs, nodal_theirs / nodal_ours - 1, dfield);
    EXPECT_NEAR(gauss_theirs, gauss_ours, 1e-5 * gauss_ours) << parts[p].body();
    ASSERT_FALSE(ccx.displacement_m[p].hasNaN()) << parts[p].body();
    EXPECT_LT(dfield, 1e-5) << parts[p].body();
  }
}

// elastic_arm false: the arm is a rigid body (its tracked point and its
// joint and chain interfaces on the body itself).
void expect_lever_chain_agrees(bool elastic_arm, double drive_stiffness) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  std::vector<Part> parts = test::lever_chain_parts(def, test::steel());
  if (elastic_arm) {
    // The arm's half at H of aluminium (a solid of its own material): its
    // section written with that material.
    Part& arm = parts.back();
    std::vector<fem::Index>& tip = arm.model.mesh.element_sets["solid.tip"];
    const fem::ElementBlock& block = arm.model.mesh.blocks.front();
    for (fem::Index e = 0; e < block.size(); ++e) {
      double x = 0.0;
      for (fem::Index n : block.element(e)) x += arm.model.mesh.nodes(n, 0) / double(block.element(e).size());
      if (x < -0.5 * def.geometry.c_m) tip.push_back(e);
    }
    fem::IsotropicMaterial aluminium;
    aluminium.name = "aluminium";
    aluminium.youngs_modulus_pa = 70e9;
    aluminium.poisson_ratio = 0.33;
    aluminium.density_kg_m3 = 2700.0;
    arm.model.set_materials = {{"solid.tip", aluminium}};
    arm.mass = fem::mass_properties(arm.model.mesh, fem::element_materials(arm.model));
  } else {
    parts.pop_back();
  }
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const mech::Frame frame = pipeline::solve_static_pose(model, {20 * test::kDeg});
  AssemblyOptions options;
  options.chains = {{"chain", kChainEA}};
  if (!std::isinf(drive_stiffness)) options.drives = {{"lever_drive", drive_stiffness}};
  options.points = {{"H", "arm", "H", elastic_arm ? "x0" : ""}};
  ElasticAssembly assembly(parts, model, options);
  const PoseSolution pose = assembly.solve(frame);
  expect_agreement(fmt::format("{} arm, k_d = {:g} N m/rad", elastic_arm ? "elastic" : "rigid", drive_stiffness),
                   assembly, parts, model, frame, pose, "H");
}

TEST(AssemblyCalculix, LeverChainWithElasticPartsAndRigidDriveMatchesCcx) { expect_lever_chain_agrees(true, kRigid); }

TEST(AssemblyCalculix, LeverChainWithRigidArmAndCompliantDriveMatchesCcx) { expect_lever_chain_agrees(false, 2e4); }

}  // namespace
}  // namespace kinetofem::structure

namespace kinetofem::structure {
namespace {

// The two-link arm (structure_fixtures.hpp) in motion (d'Alembert loads of
// its kinematics at t = 0.2 s) on a column frame part held at its foot, its
// elbow drive a torsional spring: the foundation as *BOUNDARY, the ground's
// pin and drive on the column's top face.
TEST(AssemblyCalculix, TwoLinkArmOnAColumnFrameMatchesCcx) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  const test::TwoLinkArm arm;
  mech::MultibodyModel model = test::two_link_arm(arm);
  std::vector<Part> parts = test::two_link_parts(arm);
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(model), {0.0, 0.2, 0.5}).frames[1];
  parts.push_back(test::held_column_part({"frame", nullptr, {{"J1", "y1"}}, {}, {{"d1", "y1"}}}, 0.5, 0.04, 0.04, {2, 12, 2},
                              -0.5));
  AssemblyOptions options;
  options.drives = {{"d2", 3000.0}};
  options.points = {{"H", "link2", "tip", "x1"}};
  ElasticAssembly assembly(parts, model, options);
  const PoseSolution pose = assembly.solve(frame);
  expect_agreement("two-link arm on a column", assembly, parts, model, frame, pose, "H");
}

}  // namespace
}  // namespace kinetofem::structure

namespace kinetofem::structure {
namespace {

// The two-link arm with link2 in its own plane, 40 mm out of link1's along
// the pin axes: the elbow pin J2 joins bores at different z, an elastic
// (Timoshenko) pin, a spring of the assembly's S, written as such.
TEST(AssemblyCalculix, TwoLinkArmWithAnElasticPinMatchesCcx) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  const test::TwoLinkArm arm;
  mech::MultibodyModel model = test::two_link_arm(arm);
  std::vector<Part> parts = test::two_link_parts(arm);
  parts[1].model.mesh.nodes.col(2).array() += 0.04;
  parts[1].mass = fem::mass_properties(parts[1].model.mesh, fem::element_materials(parts[1].model));
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(model), {0.0, 0.2, 0.5}).frames[1];
  AssemblyOptions options;
  options.drives = {{"d2", 3000.0}};
  options.points = {{"H", "link2", "tip", "x1"}};
  options.pins = {{"J2", 0.012, {}, {}}};
  ElasticAssembly assembly(parts, model, options);
  const PoseSolution pose = assembly.solve(frame);
  ASSERT_EQ(pose.pins.size(), 1u);
  expect_agreement("two-link arm with an elastic pin", assembly, parts, model, frame, pose, "H");
}

}  // namespace
}  // namespace kinetofem::structure
