// The as-built lever-chain manipulator (cases/lever_chain_manipulator_as_built)
// with every solid, pin and the frame made rigid and only the chain elastic:
// H's deflection in the elastic assembly must be the hand formula of the
// chain's stretch. This checks the layout of the as-built model as a whole
// (the welded parts placed in their planes, the pins between bores at their
// own z, the frame's foundation, the chain on the roller, the gripper fixed
// to the arm) against geometry alone.
//
// Hand formula (docs/elastic_assembly.md, the chain member): the chain from
// its hinge B0 to its tangent point T on the roller stretches by
//     e = N L / (EA),   L = |B0 - T|,  N its tension (the multibody statics),
// which lets T move by e away from B0 along the chain (unit d, T -> B0):
//     u_T . d = -e.
// With the lever, the frame and the pins rigid and the drive rigid, the roller
// centre A stays, and the arm with the gripper fixed to it turns about A by
//     theta = -e / ((e_z x (T - A)) . d),   u_H = theta e_z x (H - A).
//
// And the same model in steel, in its design pose, written as a CalculiX deck
// (structure/calculix_assembly_export.hpp) and solved by ccx where it is
// installed (skipped otherwise): H's displacement and every part's peak von
// Mises stress over the integration points agree.
//
// And both as-built cases (this one and the four-bar) through the whole
// chain at a coarse mesh, the fatigue on the assembly's stress.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <algorithm>
#include <filesystem>

#include <Eigen/Geometry>

#include "kinetofem/app/assembly_keys.hpp"
#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/app/part_keys.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/structure/calculix_assembly_export.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/testing/calculix_run.hpp"
#include "kinetofem/testing/linkage_run.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

// The as-built lever-chain read from its bundled case file at a coarse mesh:
// the model, the part specs, the assembly's options and the case's material.
struct AsBuiltCase {
  mech::MultibodyModel model;
  std::vector<pipeline::PartSpec> specs;
  structure::AssemblyOptions options;
  fem::IsotropicMaterial material;
  meshes::MeshOptions mesh;
};

AsBuiltCase read_as_built_lever_chain(const std::vector<std::string>& overrides, const fs::path& dir) {
  const CaseFile c =
      CaseFile::load("cases/lever_chain_manipulator_as_built/case.toml", linkage_schema(), false, overrides);
  AsBuiltCase a;
  a.model = read_linkage_model(c);
  a.specs = read_parts(c, a.model);
  std::vector<std::string> bodies;
  for (const auto& s : a.specs) bodies.push_back(s.attachments.body);
  a.options = read_linkage_assembly(c, a.model, bodies).value();
  a.material = read_material(c);
  a.mesh = read_part_mesh_options(c, dir);
  return a;
}

TEST(AsBuiltLeverChain, RigidSolidsAndAnElasticChainGiveTheHandFormulaAtH) {
  const fs::path dir = fs::temp_directory_path() / "kinetofem_as_built_rigid";
  fs::remove_all(dir);
  // A coarse linear mesh: with the solids rigid the mesh size does not enter
  // H's deflection (the couplings are exact rigid-body maps).
  AsBuiltCase a = read_as_built_lever_chain({"mesh.element_size_mm=25", "mesh.order=1"}, dir);
  mech::MultibodyModel& model = a.model;
  std::vector<pipeline::PartSpec>& specs = a.specs;
  structure::AssemblyOptions* options = &a.options;

  // Rigid: E x 1e9 for the case's material, every solid's own and every pin's.
  // (Not 1e6: at steel the parts, pins and frame give most of H's deflection,
  // so at 1e6 their residual compliance is still 1.7e-6 of the chain's share
  // (measured), above the tolerance below; at 1e9 it is 1.7e-9.)
  constexpr double kStiffer = 1e9;
  fem::IsotropicMaterial material = a.material;
  material.youngs_modulus_pa *= kStiffer;
  for (auto& spec : specs)
    for (auto& solid : spec.solid_materials)
      if (solid.youngs_modulus_pa) *solid.youngs_modulus_pa *= kStiffer;
  for (auto& pin : options->pins)
    if (pin.youngs_modulus_pa) *pin.youngs_modulus_pa *= kStiffer;
  options->unit_load_split = true;
  options->recover_stress = false;

  const std::vector<pipeline::Part> parts =
      pipeline::build_part_models(specs, material, a.mesh, Log::quiet());
  pipeline::apply_mass_properties(model, parts, Log::quiet(), specs);
  const mech::Frame frame = pipeline::solve_static_pose(model, {0.0});

  structure::ElasticAssembly assembly(parts, model, *options);
  const structure::PoseSolution pose = assembly.solve(frame);
  ASSERT_EQ(pose.pins.size(), 2u);  // A0 and A: bores at different z

  const structure::ChainResult& chain = pose.chain("chain");
  const double tension_n = frame.chains.at(0).tension_N;
  const Eigen::Vector2d hinge_2d = model.bodies.at(0).points.at("B0");  // the frame body is the world
  const Eigen::Vector3d hinge(hinge_2d.x(), hinge_2d.y(), 0.0);
  const Eigen::Vector3d tangent(chain.tangent_point_m.x(), chain.tangent_point_m.y(), 0.0);
  const double span_m = (hinge - tangent).norm();
  const double ea_n = 5.0e6;  // the case's ea_per_strand_n x strands
  const double stretch_m = tension_n * span_m / ea_n;
  const Eigen::Vector3d d = (hinge - tangent).normalized();

  const auto arm = std::find_if(frame.bodies.begin(), frame.bodies.end(), [](const auto& b) { return b.name == "arm"; });
  ASSERT_NE(arm, frame.bodies.end());
  const Eigen::Vector3d roller_centre(arm->q.x(), arm->q.y(), 0.0);  // the arm's origin A
  const Eigen::Vector3d ez = Eigen::Vector3d::UnitZ();
  const double theta = -stretch_m / ez.cross(tangent - roller_centre).dot(d);
  const structure::PointResult& h = pose.point("H");
  const Eigen::Vector3d h_in_plane(h.position_m.x(), h.position_m.y(), 0.0);
  const Eigen::Vector3d expected = theta * ez.cross(h_in_plane - roller_centre);

  std::printf("  chain: tension %.6f N (multibody %.6f N), span %.6f mm, stretch %.6e mm\n", chain.tension_n, tension_n,
              span_m * 1e3, stretch_m * 1e3);
  std::printf("  H: assembly (%.9e, %.9e, %.9e) mm, hand formula (%.9e, %.9e, %.9e) mm\n", h.displacement_m.x() * 1e3,
              h.displacement_m.y() * 1e3, h.displacement_m.z() * 1e3, expected.x() * 1e3, expected.y() * 1e3,
              expected.z() * 1e3);
  const double error = (h.displacement_m - expected).norm() / expected.norm();
  std::printf("  relative difference %.2e\n", error);
  // The lever-chain is statically determinate in the plane: the chain's
  // tension is the multibody one whatever the stiffnesses (1e-8, round-off of
  // the dense pose system).
  EXPECT_NEAR(chain.tension_n, tension_n, 1e-8 * tension_n);
  // Reference: the hand formula above; 1e-6 relative (the parts' residual
  // compliance at E x 1e9 is about 2e-9 of the chain's share).
  EXPECT_LT(error, 1e-6);
  EXPECT_GT(expected.norm(), 0.0);
  fs::remove_all(dir);
}

// Both bundled as-built cases (the lever-chain and the four-bar) through the
// whole chain at a coarse mesh: their parts sit in several planes, so the
// fatigue check takes every part's stress from the elastic assembly and says
// so; the welded parts' `solid` cell field is on their assembly bodies too.
class AsBuiltWholeChain : public ::testing::TestWithParam<const char*> {};

TEST_P(AsBuiltWholeChain, RunsWithTheFatigueOnTheAssemblysStress) {
  const std::string name = GetParam();
  const auto [output_dir, run] =
      testing::run_linkage_quietly("cases/" + name + "/case.toml", "kinetofem_whole_chain_" + name,
                                   {"mesh.element_size_mm=25", "mesh.order=1", "simulation.output_times=11"});
  ASSERT_TRUE(run.assembly.has_value());
  ASSERT_TRUE(run.vibration.has_value());
  ASSERT_EQ(run.fatigue.size(), run.parts.size());
  for (const auto& f : run.fatigue) {
    EXPECT_EQ(f.stress_source, pipeline::StressHistorySource::ElasticAssembly) << f.body;
    EXPECT_TRUE(std::isfinite(f.max_utilization)) << f.body;
  }
  const auto lever = std::find_if(run.fatigue.begin(), run.fatigue.end(), [](const auto& f) { return f.body == "lever"; });
  ASSERT_NE(lever, run.fatigue.end());
  EXPECT_GT(lever->max_utilization, 0.0);

  const auto results = post::ResultsFile::open(run.results_file);
  for (const char* body : {"lever", "assembly.lever"}) {
    const fem::Mesh mesh = results.read_mesh(body);
    const post::FieldData solid = results.read_element_field(body, post::layout::kSolid);
    EXPECT_EQ(solid.values.rows(), mesh.element_count()) << body;
    EXPECT_GT(solid.values.maxCoeff(), 0.0) << body << ": a welded part has several solids";
  }
  fs::remove_all(output_dir);
}

INSTANTIATE_TEST_SUITE_P(Cases, AsBuiltWholeChain,
                         ::testing::Values("lever_chain_manipulator_as_built", "lever_manipulator_as_built"));

TEST(AsBuiltLeverChain, CalculixSolvesTheDesignPoseAlike) {
  if (!kinetofem::testing::have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  kinetofem::testing::CcxScratchDir dir("kinetofem_as_built_ccx");
  // Coarse: SPOOLES orders the dense coupling equations slowly.
  AsBuiltCase a = read_as_built_lever_chain({"mesh.element_size_mm=25"}, dir.path / "mesh");
  const std::vector<pipeline::Part> parts = pipeline::build_part_models(a.specs, a.material, a.mesh, Log::quiet());
  pipeline::apply_mass_properties(a.model, parts, Log::quiet(), a.specs);
  const mech::Frame frame = pipeline::solve_static_pose(a.model, {0.0});
  structure::ElasticAssembly assembly(parts, a.model, a.options);
  const structure::PoseSolution pose = assembly.solve(frame);

  const structure::AssemblyDeck deck =
      structure::write_calculix_assembly_deck(assembly, parts, a.model, frame, dir.path / "pose.inp");
  const double ccx_seconds = kinetofem::testing::run_ccx(dir.path, "pose");
  ASSERT_GE(ccx_seconds, 0.0) << kinetofem::testing::read_text(dir.path / "pose.log");
  const structure::AssemblyDeckResults ccx = structure::read_calculix_assembly_results(deck, dir.path / "pose");

  const std::vector<structure::InterfaceInfo> interfaces = assembly.interfaces();
  const auto h = std::find_if(interfaces.begin(), interfaces.end(),
                              [](const auto& i) { return i.kind == "point" && i.name == "H"; });
  ASSERT_NE(h, interfaces.end());
  const Eigen::Vector3d ours = pose.point("H").displacement_m;
  const Eigen::Vector3d theirs = ccx.interface_motion.at(size_t(h - interfaces.begin())).head<3>();
  const double du = (theirs - ours).norm() / ours.norm();
  std::printf("  deck: %lld nodes, %lld solid elements, %d equations, %d springs, %d held DoFs; ccx %.1f s\n"
              "  H: kinetofem (%.6e, %.6e, %.6e) mm, ccx (%.6e, %.6e, %.6e) mm, difference %.2e\n",
              deck.node_count, deck.solid_elements, deck.equations, deck.springs, deck.boundaries, ccx_seconds,
              ours.x() * 1e3, ours.y() * 1e3, ours.z() * 1e3, theirs.x() * 1e3, theirs.y() * 1e3, theirs.z() * 1e3, du);
  // Reference: CalculiX 2.20 on the identical deck; 0.5 % (ccx prints 7
  // digits; the two solve the same discrete problem).
  EXPECT_LT(du, 5e-3);
  for (size_t p = 0; p < parts.size(); ++p) {
    const structure::PartField& field = pose.part(parts[p].body());
    const double peak_ours =
        kinetofem::testing::peak_gauss_von_mises(parts[p].model, field.displacement_m, deck.parts[p].rotation);
    const double peak_theirs = ccx.peak_gauss_von_mises_pa.at(p);
    std::printf("  %s: peak von Mises at the integration points %.4f MPa, ccx %.4f MPa (%.2e)\n",
                parts[p].body().c_str(), peak_ours * 1e-6, peak_theirs * 1e-6, peak_theirs / peak_ours - 1);
    EXPECT_NEAR(peak_theirs, peak_ours, 5e-3 * peak_ours) << parts[p].body();  // CalculiX 2.20, 0.5 %
  }
}

}  // namespace
}  // namespace kinetofem::app
