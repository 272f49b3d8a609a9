// Unit tests of the elastic assembly's CalculiX deck
// (structure/calculix_assembly_export.hpp) that need no ccx: what ccx
// demands of the equations and what the deck must hold. The comparison with
// ccx's solution is tests/verification/structure/test_assembly_calculix.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <unistd.h>

#include "structure_fixtures.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/structure/calculix_assembly_export.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

namespace fs = std::filesystem;

struct Equation {
  std::vector<std::pair<long long, int>> dofs;  // (node, DoF), the dependent one first
  std::vector<double> coefficients;
};

struct ParsedDeck {
  std::vector<Equation> equations;
  std::set<std::pair<long long, int>> held;  // *BOUNDARY
  std::map<std::string, int> keywords;       // keyword line (up to the first comma) -> count
  std::set<long long> printed;               // NSET NPRINT
  int longest_equation_line = 0;             // entries on one data line of an *EQUATION
};

std::vector<std::string> fields_of(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  std::string f;
  while (std::getline(s, f, ',')) {
    f.erase(0, f.find_first_not_of(' '));
    if (!f.empty()) out.push_back(f);
  }
  return out;
}

ParsedDeck parse(const fs::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(bool(in)) << path;
  ParsedDeck deck;
  std::string line, keyword;
  long long terms_left = -1;
  while (std::getline(in, line)) {
    if (line.rfind("**", 0) == 0) continue;
    if (line.rfind("*", 0) == 0) {
      keyword = line.substr(0, line.find(','));
      ++deck.keywords[keyword];
      if (keyword == "*NSET" && line.find("NPRINT") == std::string::npos) keyword = "*NSET other";
      terms_left = -1;
      continue;
    }
    const std::vector<std::string> f = fields_of(line);
    if (keyword == "*EQUATION") {
      if (terms_left < 0) {
        terms_left = std::stoll(f.at(0));
        deck.equations.emplace_back();
        continue;
      }
      deck.longest_equation_line = std::max(deck.longest_equation_line, int(f.size()));
      for (size_t k = 0; k + 2 < f.size(); k += 3) {
        deck.equations.back().dofs.emplace_back(std::stoll(f[k]), std::stoi(f[k + 1]));
        deck.equations.back().coefficients.push_back(std::stod(f[k + 2]));
        --terms_left;
      }
    } else if (keyword == "*BOUNDARY") {
      deck.held.emplace(std::stoll(f.at(0)), std::stoi(f.at(1)));
    } else if (keyword == "*NSET") {
      for (const std::string& id : f) deck.printed.insert(std::stoll(id));
    }
  }
  return deck;
}

struct Scratch {
  fs::path path = fs::temp_directory_path() / ("kinetofem_assembly_deck_" + std::to_string(::getpid()) + "_" +
                                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  Scratch() { fs::create_directories(path); }
  ~Scratch() { fs::remove_all(path); }
};

// The lever-chain (box parts), turned 20 deg, the lever's drive compliant.
struct LeverChainPose {
  mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  std::vector<Part> parts = test::lever_chain_parts(def, test::steel());
  mech::Frame frame;
  std::unique_ptr<ElasticAssembly> assembly;
  LeverChainPose() {
    pipeline::apply_mass_properties(model, parts, Log::quiet());
    frame = pipeline::solve_static_pose(model, {20 * test::kDeg});
    AssemblyOptions options;
    options.chains = {{"chain", 2e6}};
    options.drives = {{"lever_drive", 2e4}};
    options.points = {{"H", "arm", "H", "x0"}};
    assembly = std::make_unique<ElasticAssembly>(parts, model, options);
  }
};

TEST(CalculixAssemblyExport, EachDependentDofIsInOneEquationAndHeldNowhere) {
  const LeverChainPose lc;
  Scratch dir;
  const AssemblyDeck deck =
      write_calculix_assembly_deck(*lc.assembly, lc.parts, lc.model, lc.frame, dir.path / "pose.inp");
  const ParsedDeck parsed = parse(dir.path / "pose.inp");
  ASSERT_EQ(int(parsed.equations.size()), deck.equations);
  // ccx reads at most 12 entries (4 terms) on an equation's data line.
  EXPECT_LE(parsed.longest_equation_line, 12);
  std::map<std::pair<long long, int>, int> appearances;
  for (const Equation& e : parsed.equations)
    for (const auto& d : e.dofs) ++appearances[d];
  for (const Equation& e : parsed.equations) {
    ASSERT_GE(e.dofs.size(), 2u);
    EXPECT_EQ(e.coefficients.front(), 1.0);
    EXPECT_EQ(appearances[e.dofs.front()], 1) << "node " << e.dofs.front().first << " DoF " << e.dofs.front().second;
    EXPECT_FALSE(parsed.held.count(e.dofs.front()));
  }
}

TEST(CalculixAssemblyExport, DeckHoldsThePartsInterfacesSpringsAndLoads) {
  const LeverChainPose lc;
  Scratch dir;
  const AssemblyDeck deck =
      write_calculix_assembly_deck(*lc.assembly, lc.parts, lc.model, lc.frame, dir.path / "pose.inp");
  const ParsedDeck parsed = parse(dir.path / "pose.inp");
  const std::vector<InterfaceInfo> interfaces = lc.assembly->interfaces();
  ASSERT_EQ(deck.parts.size(), 2u);
  EXPECT_EQ(deck.parts[0].first_node, 1);
  EXPECT_EQ(deck.parts[1].first_node, 1 + lc.parts[0].model.mesh.node_count());
  EXPECT_EQ(deck.solid_elements, lc.parts[0].model.mesh.element_count() + lc.parts[1].model.mesh.element_count());
  ASSERT_EQ(deck.translation_node.size(), interfaces.size());
  for (size_t k = 0; k < interfaces.size(); ++k) {
    EXPECT_TRUE(parsed.printed.count(deck.translation_node[k]));
    EXPECT_TRUE(parsed.printed.count(deck.rotation_node[k]));
  }
  // The chain and the compliant drive: two rank-one springs.
  EXPECT_EQ(deck.springs, 2);
  EXPECT_EQ(parsed.keywords.at("*SPRING"), 2);
  // Six ties per interface and the joints' and drives' rows (A0 5, A 5):
  // every relation is an equation or, left with one term, a held DoF (the
  // springs' nodes hold their DoFs 2 and 3).
  const InterfaceStructure structure = lc.assembly->interface_structure(lc.frame);
  EXPECT_EQ(structure.constraints.rows(), 10);
  EXPECT_EQ(deck.equations + deck.boundaries - 2 * deck.springs,
            6 * int(interfaces.size()) + int(structure.constraints.rows()) + deck.springs);
  EXPECT_LT(deck.largest_dropped, 1e-13);
  EXPECT_GT(deck.loads, 0);
  EXPECT_EQ(parsed.keywords.at("*STEP"), 1);
}

TEST(CalculixAssemblyExport, PartsOfAnotherAssemblyAreAnError) {
  const LeverChainPose lc;
  Scratch dir;
  std::vector<Part> other = lc.parts;
  test::BarSize size;
  other[1] = test::bar_part("arm", other[1].attachments, size);  // another mesh of the arm
  const std::string what =
      test::error_of([&] { write_calculix_assembly_deck(*lc.assembly, other, lc.model, lc.frame, dir.path / "x.inp"); });
  EXPECT_NE(what.find("is not the part the assembly was built with"), std::string::npos) << what;
}

}  // namespace
}  // namespace kinetofem::structure

namespace kinetofem::structure {
namespace {

TEST(CalculixAssemblyExport, RigidBoreCouplingsAreAnError) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  std::vector<Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const mech::Frame frame = pipeline::solve_static_pose(model, {0.0});
  AssemblyOptions options;
  options.coupling = BoreCoupling::RigidBore;
  options.chains = {{"chain", 2e6}};
  const ElasticAssembly assembly(parts, model, options);
  Scratch dir;
  const std::string what =
      test::error_of([&] { write_calculix_assembly_deck(assembly, parts, model, frame, dir.path / "x.inp"); });
  EXPECT_NE(what.find("distributing couplings' equations only"), std::string::npos) << what;
}

}  // namespace
}  // namespace kinetofem::structure
