// Unit tests of the CalculiX deck exporter and result readers
// (solver/include/kinetofem/solver/calculix_export.hpp). The last tests run
// ccx itself and are skipped when it is not installed (CI does not install
// it; `apt-get install calculix-ccx`).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
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

// A scratch folder removed at the end of the test.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    path = fs::temp_directory_path() /
           ("kinetofem_ccx_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() { fs::remove_all(path); }
};

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

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

bool have_ccx() { return std::system("command -v ccx > /dev/null 2>&1") == 0; }

// Runs ccx on `job`.inp in `dir`; true when it finished.
bool run_ccx(const fs::path& dir, const std::string& job) {
  const std::string command = "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 ccx -i " + job +
                              " > " + job + ".log 2>&1";
  return std::system(command.c_str()) == 0 && fs::exists(dir / (job + ".dat"));
}

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
