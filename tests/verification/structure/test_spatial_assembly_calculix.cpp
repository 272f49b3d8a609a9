// The spatial elastic assembly of one pose written as a CalculiX deck
// (structure/calculix_assembly_export.hpp, the same writer as the planar
// assembly's) and solved by ccx where it is installed (skipped otherwise;
// `apt-get install calculix-ccx`):
//   1. the spatial two-link arm of test_spatial_assembly.cpp (a revolute
//      about the vertical, then one about link1's own y axis, so link2
//      pitches out of any plane; rigid motion drives; a payload with rotary
//      inertia; gravity) at t = 0.3 s of its motion (d'Alembert loads), its
//      tip tracked on link2's end face;
//   2. the SPEC §1 lever-chain manipulator with box parts lifted into the
//      spatial core, its chain a tension member of EA = 2e6 N (a SPRING1 of
//      the deck), the gripper point H tracked on the arm;
//   3. the same with the arm a rigid body (its interfaces tied to its node
//      pair, the multibody frame's loads on it);
//   4. an arm on the two lands of a sleeve fixed to the ground (axis oblique),
//      half way out: the slide's rows, each land on the two stations of the
//      arm that bracket it.
//
// Reference: CalculiX on the identical deck — the same meshes (the parts'
// 3-2-1-supported models, whose support the deck leaves out), material and
// nodal loads (SpatialElasticAssembly::part_loads, body_loads), the
// distributing couplings written as their motion definition (*EQUATION),
// the joints' and drives' rows (interface_structure) and the chain's spring.
// ccx solves the full, unreduced problem with none of kinetofem's
// condensation (no 3-2-1 support, flexibility or dense pose system), so
// agreement checks the condensation, the rotations into world axes (about
// every axis here, not only z) and the chain's spring.
// Tolerances, as the planar comparison (test_assembly_calculix.cpp) and for
// its reasons: the tracked point's displacement, every part node's
// displacement and the peak von Mises stress over the integration points
// (C3D20: the same 27 points as kinetofem's HEX20) within 1e-5, and the
// chain's tension (sqrt(k u^T S u) from ccx's interface motions) within
// 1e-5. The two programs solve the same discrete problem, so they agree to
// what ccx prints (7 significant digits in its .dat file, about 1e-7), and
// 1e-5 leaves a hundred times that for round-off. The peak at the NODES is
// printed, not compared: each program extrapolates the integration-point
// stresses to the nodes its own way (kinetofem a trilinear least-squares
// fit, stress_recovery.hpp; 1-12 % apart at these coarse meshes).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "../../unit/structure/spatial_fixtures.hpp"
#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/loads/slide_stations.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/from_planar.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/testing/calculix_run.hpp"
#include "kinetofem/structure/calculix_assembly_export.hpp"
#include "kinetofem/structure/spatial_elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

namespace sp = mech::spatial;
using kinetofem::testing::have_ccx;
using kinetofem::testing::read_text;
using kinetofem::testing::run_ccx;
using test::BarSize;
using test::kDeg;
using test::give_mass_of;
using test::slide_model;
using test::spatial_arm;
using test::spatial_bar;
using test::SlideModel;
using test::SpatialArm;

constexpr double kChainEA = 2e6;  // N

struct ScratchDir : kinetofem::testing::CcxScratchDir {
  ScratchDir() : CcxScratchDir("kinetofem_spatial_assembly_ccx") {}
};

size_t interface_named(const SpatialElasticAssembly& assembly, const std::string& name) {
  const std::vector<SpatialInterfaceInfo> all = assembly.interfaces();
  for (size_t k = 0; k < all.size(); ++k)
    if (all[k].name == name) return k;
  ADD_FAILURE() << "no interface " << name;
  return 0;
}

// What ccx's solution of the deck of `pose` must agree with: the tracked
// point, every part's nodal displacements and its peak von Mises stress over
// the integration points, each chain's tension (1e-5); the nodal peaks
// printed.
void expect_agreement(const std::string& what, const SpatialElasticAssembly& assembly, const sp::Model& model,
                      const sp::Frame& frame, const SpatialPoseSolution& pose, const std::string& point) {
  ScratchDir dir;
  AssemblyDeckOptions deck_options;
  deck_options.heading = "kinetofem spatial elastic assembly: " + what;
  deck_options.print_part_displacements = true;
  const AssemblyDeck deck = write_calculix_assembly_deck(assembly, model, frame, dir.path / "pose.inp", deck_options);
  const double ccx_seconds = run_ccx(dir.path, "pose");
  ASSERT_GE(ccx_seconds, 0.0) << read_text(dir.path / "pose.log");
  const AssemblyDeckResults ccx = read_calculix_assembly_results(deck, dir.path / "pose");

  const size_t h = interface_named(assembly, "point '" + point + "'");
  const Eigen::Vector3d ours = pose.point(point).displacement_m;
  const Eigen::Vector3d theirs = ccx.interface_motion.at(h).head<3>();
  const double du = (theirs - ours).norm() / ours.norm();
  std::printf(
      "  %s: %lld nodes, %d equations (%lld terms), %d springs, %d held DoFs, largest dropped %.1e; ccx %.2f s\n"
      "  u_%s kinetofem (%.6e, %.6e, %.6e) m, ccx (%.6e, %.6e, %.6e) m, difference %.2e\n",
      what.c_str(), deck.node_count, deck.equations, deck.equation_terms, deck.springs, deck.boundaries,
      deck.largest_dropped, ccx_seconds, point.c_str(), ours.x(), ours.y(), ours.z(), theirs.x(), theirs.y(),
      theirs.z(), du);
  EXPECT_GT(ours.norm(), 1e-7);
  EXPECT_LT(du, 1e-5);

  const std::vector<SpatialPart>& parts = assembly.parts();
  ASSERT_EQ(deck.parts.size(), parts.size());
  for (size_t p = 0; p < parts.size(); ++p) {
    const PartField& field = pose.part(parts[p].body());
    const double nodal_ours = field.von_mises_pa.maxCoeff();
    const double nodal_theirs = ccx.nodal_von_mises_pa.at(p).maxCoeff();
    const double gauss_ours = kinetofem::testing::peak_gauss_von_mises(assembly.supported_model(parts[p].body()),
                                                                       field.displacement_m, deck.parts[p].rotation);
    const double gauss_theirs = ccx.peak_gauss_von_mises_pa.at(p);
    ASSERT_FALSE(ccx.displacement_m[p].hasNaN()) << parts[p].body();
    const double dfield = (ccx.displacement_m[p] - field.displacement_m).cwiseAbs().maxCoeff() /
                          field.displacement_m.cwiseAbs().maxCoeff();
    std::printf(
        "  %s: peak von Mises at the integration points %.6e Pa (ccx %.6e Pa, %.2e), at the nodes %.6e Pa "
        "(ccx %.6e Pa, %.2e); largest nodal displacement difference %.2e of the largest\n",
        parts[p].body().c_str(), gauss_ours, gauss_theirs, gauss_theirs / gauss_ours - 1, nodal_ours, nodal_theirs,
        nodal_theirs / nodal_ours - 1, dfield);
    EXPECT_NEAR(gauss_theirs, gauss_ours, 1e-5 * gauss_ours) << parts[p].body();
    EXPECT_LT(dfield, 1e-5) << parts[p].body();
  }

  // A chain's tension from ccx's interface motions: its spring is k g^T g,
  // so u^T S u = k e^2 and N = k e = sqrt(k u^T S u) (one chain here).
  if (!pose.chains.empty()) {
    ASSERT_EQ(pose.chains.size(), 1u);
    const InterfaceStructure structure = assembly.interface_structure(frame);
    Eigen::VectorXd u(6 * Eigen::Index(ccx.interface_motion.size()));
    for (size_t k = 0; k < ccx.interface_motion.size(); ++k)
      u.segment<6>(6 * Eigen::Index(k)) = ccx.interface_motion[k];
    const ChainResult& chain = pose.chains.front();
    const double tension_ccx = std::sqrt(chain.stiffness_n_per_m * u.dot(structure.springs * u));
    std::printf("  chain '%s': tension %.6e N (ccx %.6e N, %.2e)\n", chain.chain.c_str(), chain.tension_n, tension_ccx,
                tension_ccx / chain.tension_n - 1);
    EXPECT_NEAR(tension_ccx, chain.tension_n, 1e-5 * chain.tension_n);
  }
}

// --- 1. The spatial two-link arm (test_spatial_assembly.cpp's) ---------------

TEST(SpatialAssemblyCalculix, SpatialTwoLinkArmInMotionMatchesCcx) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  const SpatialArm arm = spatial_arm();
  const sp::Frame frame = sp::run_kinematics(sp::System(arm.model), {0.3}).frames.at(0);
  SpatialAssemblyOptions options;
  options.points = {{"tip", "link2", "tip", "x1"}};
  SpatialElasticAssembly assembly(arm.parts, arm.model, options);
  const SpatialPoseSolution pose = assembly.solve(frame);
  expect_agreement("spatial two-link arm at t = 0.3 s", assembly, arm.model, frame, pose, "tip");
}

// --- 2, 3. The lever-chain manipulator lifted, its chain a spring ------------

void expect_lifted_lever_chain_agrees(bool elastic_arm) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  if (!elastic_arm) parts.pop_back();  // the arm a rigid body (its mass properties kept)
  const sp::Model lifted = sp::from_planar(model);
  const sp::Frame frame = sp::run_kinematics(sp::System(lifted), {0.6}).frames.at(0);
  std::vector<SpatialPart> spatial_parts;
  for (const pipeline::Part& part : parts) spatial_parts.push_back(spatial_part_of(part));
  SpatialAssemblyOptions options;
  options.chains = {{"chain", kChainEA}};
  options.points = {{"H", "arm", "H", elastic_arm ? "x0" : ""}};
  SpatialElasticAssembly assembly(spatial_parts, lifted, options);
  const SpatialPoseSolution pose = assembly.solve(frame);
  expect_agreement(elastic_arm ? "lifted lever-chain, elastic arm" : "lifted lever-chain, rigid arm", assembly, lifted,
                   frame, pose, "H");
}

TEST(SpatialAssemblyCalculix, LiftedLeverChainWithElasticPartsMatchesCcx) { expect_lifted_lever_chain_agrees(true); }

TEST(SpatialAssemblyCalculix, LiftedLeverChainWithRigidArmMatchesCcx) { expect_lifted_lever_chain_agrees(false); }

// --- 4. A slide (test_spatial_assembly.cpp's) -------------------------------

// Half way out: each land between two of the slider's stations (weighted
// rows), the stations away from the lands tied but unloaded.
TEST(SpatialAssemblyCalculix, ArmOnTheLandsOfASlideMatchesCcx) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  const SlideModel slide = slide_model(0.1);
  const sp::Frame frame = sp::run_kinematics(sp::System(slide.model), {0.5}).frames.at(0);
  SpatialAssemblyOptions options;
  options.points = {{"tip", "arm", "tip", "x1"}};
  SpatialElasticAssembly assembly(slide.parts, slide.model, options);
  const SpatialPoseSolution pose = assembly.solve(frame);
  expect_agreement("arm on a slide at t = 0.5 s", assembly, slide.model, frame, pose, "tip");
}

}  // namespace
}  // namespace kinetofem::structure
