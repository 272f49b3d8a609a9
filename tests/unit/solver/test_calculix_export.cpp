// Unit tests of the CalculiX deck exporter and result readers
// (solver/include/kinetofem/solver/calculix_export.hpp). The last tests run
// ccx itself and are skipped when it is not installed (CI does not install
// it; `apt-get install calculix-ccx`).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <unistd.h>

#include <Eigen/Geometry>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/calculix_export.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/box_mesh.hpp"
#include "kinetofem/testing/calculix_run.hpp"

namespace kinetofem::fem {
namespace {

namespace fs = std::filesystem;

// Abaqus/CalculiX mid-edge corner pairs, 1-based, as the CalculiX manual
// draws C3D10 and C3D20 — written out here independently of the exporter.
const std::vector<std::array<int, 2>> kC3D10Edges = {{1, 2}, {2, 3}, {3, 1},
                                                     {1, 4}, {2, 4}, {3, 4}};
const std::vector<std::array<int, 2>> kC3D20Edges = {{1, 2}, {2, 3}, {3, 4}, {4, 1},
                                                     {5, 6}, {6, 7}, {7, 8}, {8, 5},
                                                     {1, 5}, {2, 6}, {3, 7}, {4, 8}};

using ScratchDir = kinetofem::testing::CcxScratchDir;
using kinetofem::testing::read_text;

// Element connectivity as written in the deck: element lines (with
// continuation lines joined) under the *ELEMENT keyword.
std::vector<std::vector<long long>> deck_elements(const std::string& deck) {
  std::vector<std::vector<long long>> out;
  std::istringstream in(deck);
  std::string line;
  bool in_elements = false, continued = false;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '*') {
      in_elements = line.rfind("*ELEMENT", 0) == 0;
      continued = false;
      continue;
    }
    if (!in_elements) continue;
    if (!continued) out.emplace_back();
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ','))
      if (field.find_first_not_of(' ') != std::string::npos) out.back().push_back(std::stoll(field));
    continued = !line.empty() && line.back() == ',';
  }
  return out;
}

FeModel small_cantilever(ElementType type, std::array<int, 3> divisions) {
  testing::BoxMeshOptions options;
  options.length_m = {0.4, 0.1, 0.1};
  options.divisions = divisions;
  options.type = type;
  options.random_perturbation = 0.1;  // distorted cells: node order mistakes show
  FeModel model;
  model.mesh = testing::box_mesh(options);
  model.supports = {{"clamp", model.mesh.node_set("x0"), {true, true, true}, Eigen::Vector3d::Zero()}};
  return model;
}

LoadCase end_load(double angle) {
  LoadCase load;
  load.tractions = {{"x1", 1e6 * Eigen::Vector3d(0.2, std::cos(angle), std::sin(angle))}};
  return load;
}

// Each exported mid-edge node must lie at the midpoint of the two corners
// that the Abaqus convention pairs with its position (box meshes have straight
// edges, so mid-edge nodes sit at the exact midpoints).
void expect_midpoints(ElementType type, const std::vector<std::array<int, 2>>& abaqus_edges) {
  ScratchDir dir;
  const FeModel model = small_cantilever(type, {2, 1, 1});
  write_calculix_deck(model, std::vector<LoadCase>{end_load(0.0)}, dir.path / "m.inp");
  const auto elements = deck_elements(read_text(dir.path / "m.inp"));
  ASSERT_EQ(Index(elements.size()), model.mesh.element_count());
  const int corners = corner_nodes(type);
  for (const auto& element : elements) {
    ASSERT_EQ(int(element.size()), 1 + nodes_per_element(type));
    auto x = [&](int position_1based) {
      return Eigen::Vector3d(model.mesh.nodes.row(element[size_t(position_1based)] - 1));
    };
    for (size_t k = 0; k < abaqus_edges.size(); ++k) {
      const int position = corners + 1 + int(k);
      const Eigen::Vector3d mid = 0.5 * (x(abaqus_edges[k][0]) + x(abaqus_edges[k][1]));
      EXPECT_LT((x(position) - mid).norm(), 1e-12)
          << name_of(type) << " element " << element[0] << " position " << position;
    }
  }
}

TEST(CalculixExport, C3D10MidEdgeNodesSitAtTheirAbaqusCornerPairs) {
  expect_midpoints(ElementType::Tet10, kC3D10Edges);
}

TEST(CalculixExport, C3D20MidEdgeNodesSitAtTheirAbaqusCornerPairs) {
  expect_midpoints(ElementType::Hex20, kC3D20Edges);
}

TEST(CalculixExport, CornerOrientationIsAbaqus) {
  // Abaqus: C3D4/C3D10 nodes 1-2-3 counter-clockwise seen from node 4;
  // C3D8/C3D20 face 1-2-3-4 counter-clockwise seen from face 5-6-7-8. In
  // reference coordinates both give a positive triple product.
  for (ElementType type : {ElementType::Tet10, ElementType::Hex8, ElementType::Hex20}) {
    const std::vector<int> order = calculix_node_order(type);
    const Eigen::MatrixXd ref = reference_nodes(type);
    auto x = [&](int position_1based) { return Eigen::Vector3d(ref.row(order[size_t(position_1based - 1)])); };
    const bool tet = corner_nodes(type) == 4;
    const Eigen::Vector3d a = x(2) - x(1), b = x(tet ? 3 : 4) - x(1), c = x(tet ? 4 : 5) - x(1);
    EXPECT_GT(a.cross(b).dot(c), 0.0) << name_of(type);
  }
}

TEST(CalculixExport, DeckHasKeywordsCountsAndOneStepPerLoadCase) {
  ScratchDir dir;
  FeModel model = small_cantilever(ElementType::Hex20, {3, 1, 1});
  model.supports.push_back({"pull", {model.mesh.node_set("x1").front()}, {true, false, false},
                            Eigen::Vector3d(1e-4, 0, 0)});
  const std::vector<LoadCase> cases = {end_load(0.0), end_load(1.0), end_load(2.0)};
  CalculixDeckOptions options;
  options.file_stresses = true;
  write_calculix_deck(model, cases, dir.path / "d.inp", options);
  const std::string deck = read_text(dir.path / "d.inp");
  auto count = [&](const std::string& what) {
    size_t n = 0;
    for (size_t at = deck.find(what); at != std::string::npos; at = deck.find(what, at + 1)) ++n;
    return n;
  };
  for (const char* keyword : {"*NODE, NSET=NALL", "*ELEMENT, TYPE=C3D20, ELSET=E1",
                              "*MATERIAL, NAME=MAT1", "*ELASTIC", "*SOLID SECTION, ELSET=E1",
                              "*BOUNDARY", "*STATIC", "*CLOAD, OP=NEW", "*NODE PRINT, NSET=NALL",
                              "*EL FILE"})
    EXPECT_NE(deck.find(keyword), std::string::npos) << keyword;
  EXPECT_EQ(count("*STEP"), cases.size());
  EXPECT_EQ(count("*END STEP"), cases.size());
  EXPECT_EQ(Index(deck_elements(deck).size()), model.mesh.element_count());

  // Node lines: between *NODE and the next keyword.
  const size_t node_start = deck.find('\n', deck.find("*NODE, NSET=NALL")) + 1;
  const size_t node_end = deck.find("\n*", node_start);
  size_t node_lines = 0;
  for (size_t at = node_start; at <= node_end; at = deck.find('\n', at) + 1) ++node_lines;
  EXPECT_EQ(Index(node_lines), model.mesh.node_count());

  // Boundary lines: every prescribed DoF once, the pulled one with its value
  // (in the first step: ccx wants homogeneous ones only in the model data).
  const DofMap dofs(model.mesh.node_count(), model.supports);
  size_t b_lines = 0;
  for (size_t b = deck.find("*BOUNDARY"); b != std::string::npos; b = deck.find("*BOUNDARY", b + 1)) {
    const size_t b_start = deck.find('\n', b) + 1;
    const size_t b_end = deck.find("\n*", b_start);
    for (size_t at = b_start; at <= b_end; at = deck.find('\n', at) + 1) ++b_lines;
  }
  EXPECT_EQ(Index(b_lines), dofs.prescribed_count());
  const std::string pulled = fmt::format("\n{}, 1, 1, 1.000000000000e-04", model.mesh.node_set("x1").front() + 1);
  EXPECT_GT(deck.find(pulled), deck.find("*STEP"));
}

TEST(CalculixExport, WrongForceBlockSizeIsAnError) {
  ScratchDir dir;
  const FeModel model = small_cantilever(ElementType::Hex8, {2, 1, 1});
  EXPECT_THROW(write_calculix_deck(model, Eigen::MatrixXd::Zero(5, 1), dir.path / "x.inp"), Error);
}

using kinetofem::testing::have_ccx;

// Runs ccx on `job`.inp in `dir`; true when it finished.
bool run_ccx(const fs::path& dir, const std::string& job) { return kinetofem::testing::run_ccx(dir, job) >= 0.0; }

// A few elements with two load cases and a prescribed nonzero displacement,
// solved by ccx from the exported deck and by kinetofem: the same discrete
// problem, so the displacements agree to the printing precision of the .dat
// file (7 significant digits).
void expect_ccx_agrees(ElementType type, std::array<int, 3> divisions) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  ScratchDir dir;
  FeModel model = small_cantilever(type, divisions);
  model.supports.push_back({"pull", {model.mesh.node_set("x1").front()}, {true, false, false},
                            Eigen::Vector3d(2e-5, 0, 0)});
  const std::vector<LoadCase> cases = {end_load(0.3), end_load(2.0)};
  CalculixDeckOptions options;
  options.file_stresses = true;
  write_calculix_deck(model, cases, dir.path / "job.inp", options);
  ASSERT_TRUE(run_ccx(dir.path, "job")) << read_text(dir.path / "job.log");

  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const std::vector<DisplacementField> ours = analysis.solve(cases);
  const std::vector<DisplacementField> theirs =
      read_calculix_dat_displacements(dir.path / "job.dat", model.mesh.node_count());
  ASSERT_EQ(theirs.size(), cases.size());
  for (size_t k = 0; k < cases.size(); ++k) {
    ASSERT_FALSE(theirs[k].hasNaN());
    const double scale = ours[k].cwiseAbs().maxCoeff();
    // 1e-6 of the largest displacement: the .dat file prints 7 digits.
    EXPECT_LT((theirs[k] - ours[k]).cwiseAbs().maxCoeff(), 1e-6 * scale) << name_of(type) << " case " << k;
  }
  // Nodal stresses of ccx's .frd (6 digits) are at least of the same size
  // (extrapolation differs between the programs; the bench compares them).
  const std::vector<StressField> stress =
      read_calculix_frd_stresses(dir.path / "job.frd", model.mesh.node_count());
  ASSERT_EQ(stress.size(), cases.size());
  EXPECT_FALSE(stress[0].hasNaN());
}

// The cantilever as two solids of different materials: x < 0.2 m steel
// (the model's material), the rest aluminium (element set "solid.b").
FeModel two_material_cantilever(ElementType type, std::array<int, 3> divisions) {
  FeModel model = small_cantilever(type, divisions);
  model.material = IsotropicMaterial{"steel", 210e9, 0.3, 7850.0};
  Index first = 0;
  for (const auto& block : model.mesh.blocks) {
    for (Index e = 0; e < block.size(); ++e) {
      double x = 0.0;
      for (int k = 0; k < corner_nodes(block.type); ++k)
        x += model.mesh.nodes(block.element(e)[size_t(k)], 0) / corner_nodes(block.type);
      if (x > 0.2) model.mesh.element_sets["solid.b"].push_back(first + e);
    }
    first += block.size();
  }
  model.set_materials = {{"solid.b", IsotropicMaterial{"aluminium", 70e9, 0.33, 2700.0}}};
  return model;
}

// Element ids (1-based) listed under each "*ELSET, ELSET=<name>" of a deck.
std::map<std::string, std::vector<long long>> deck_element_sets(const std::string& deck) {
  std::map<std::string, std::vector<long long>> out;
  std::istringstream in(deck);
  std::string line;
  std::vector<long long>* current = nullptr;
  while (std::getline(in, line)) {
    if (line.rfind("*ELSET, ELSET=", 0) == 0) {
      current = &out[line.substr(14)];
      continue;
    }
    if (line.empty() || line[0] == '*') {
      current = nullptr;
      continue;
    }
    if (!current) continue;
    std::istringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ','))
      if (field.find_first_not_of(' ') != std::string::npos) current->push_back(std::stoll(field));
  }
  return out;
}

TEST(CalculixExport, TwoMaterialsGiveTwoSectionsOverTheirElements) {
  ScratchDir dir;
  const FeModel model = two_material_cantilever(ElementType::Hex20, {4, 1, 1});
  write_calculix_deck(model, std::vector<LoadCase>{end_load(0.0)}, dir.path / "two.inp");
  const std::string deck = read_text(dir.path / "two.inp");
  for (const char* text : {"*MATERIAL, NAME=MAT1\n*ELASTIC\n2.100000000000e+11, 3.000000000000e-01\n",
                           "*MATERIAL, NAME=MAT2\n*ELASTIC\n7.000000000000e+10, 3.300000000000e-01\n",
                           "*SOLID SECTION, ELSET=M1, MATERIAL=MAT1\n", "*SOLID SECTION, ELSET=M2, MATERIAL=MAT2\n"})
    EXPECT_NE(deck.find(text), std::string::npos) << text;
  EXPECT_EQ(deck.find("ELSET=E1, MATERIAL"), std::string::npos);  // no section per block
  // Every element in exactly one section: solid.b's elements in M2, the rest in M1.
  const auto sets = deck_element_sets(deck);
  ASSERT_EQ(sets.size(), 2u);
  std::vector<long long> expected_b;
  for (Index e : model.mesh.element_sets.at("solid.b")) expected_b.push_back(e + 1);
  EXPECT_EQ(sets.at("M2"), expected_b);
  EXPECT_EQ(Index(sets.at("M1").size() + sets.at("M2").size()), model.mesh.element_count());

  // A one-material model's deck has no per-material sets.
  FeModel one = model;
  one.set_materials.clear();
  write_calculix_deck(one, std::vector<LoadCase>{end_load(0.0)}, dir.path / "one.inp");
  EXPECT_EQ(read_text(dir.path / "one.inp").find("*ELSET"), std::string::npos);
}

TEST(CalculixExport, CcxSolvesTheSameTwoMaterialProblem) {
  if (!have_ccx()) GTEST_SKIP() << "ccx not found (apt-get install calculix-ccx)";
  ScratchDir dir;
  const FeModel model = two_material_cantilever(ElementType::Hex20, {8, 2, 2});
  const std::vector<LoadCase> cases = {end_load(0.3)};
  write_calculix_deck(model, cases, dir.path / "job.inp");
  ASSERT_TRUE(run_ccx(dir.path, "job")) << read_text(dir.path / "job.log");
  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const DisplacementField ours = analysis.solve(cases).front();
  const std::vector<DisplacementField> theirs =
      read_calculix_dat_displacements(dir.path / "job.dat", model.mesh.node_count());
  ASSERT_EQ(theirs.size(), 1u);
  ASSERT_FALSE(theirs[0].hasNaN());
  // The same discrete problem in both programs: 1e-6 of the largest
  // displacement, the .dat file's 7 printed digits.
  const double scale = ours.cwiseAbs().maxCoeff();
  EXPECT_LT((theirs[0] - ours).cwiseAbs().maxCoeff(), 1e-6 * scale);
  // And not the one-material problem: aluminium makes the tip visibly softer.
  FeModel steel_only = model;
  steel_only.set_materials.clear();
  LinearStaticAnalysis steel_analysis(steel_only, log);
  EXPECT_GT((steel_analysis.solve(cases).front() - ours).cwiseAbs().maxCoeff(), 0.1 * scale);
}

TEST(CalculixExport, CcxSolvesTheSameTet10Problem) {
  expect_ccx_agrees(ElementType::Tet10, {2, 1, 1});
}
TEST(CalculixExport, CcxSolvesTheSameHex20Problem) {
  expect_ccx_agrees(ElementType::Hex20, {3, 1, 1});
}
TEST(CalculixExport, CcxSolvesTheSameHex8Problem) {
  expect_ccx_agrees(ElementType::Hex8, {4, 2, 2});
}

}  // namespace
}  // namespace kinetofem::fem
