// The scan of a .geo script before Gmsh reads it (geo_file_scan.hpp): the
// commands found through comments and strings, the refusals (one line with
// file, line and command), the folders a script may read from, and that a
// trusted script passes. Through mesh_part_file: a refused command never runs.
#include <filesystem>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geo_file_scan.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/testing/error_message.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using Kind = GeoCommand::Kind;
using testing::TempDir;

using kinetofem::testing::message_of;

TEST(GeoCommands, CommentsStringsAndOptionsAreNotCommands) {
  const auto commands = geo_commands(R"(// SystemCall "rm -rf x"; Exit;
/* Exit;
   Save "a.msh"; */
Printf("SystemCall Exit Save");
Physical Surface("Merge") = {1};
Mesh.SaveAll = 0; General.Terminal = 1;
Save = 3; x = Save + 1; System[0] = 2;
s = 'Include "x.geo";';
)");
  EXPECT_TRUE(commands.empty()) << commands.front().command << " on line " << commands.front().line;
}

TEST(GeoCommands, FindsEveryCommandThatReachesOutsideGeometry) {
  const auto commands = geo_commands(R"(SetFactory("OpenCASCADE");
SystemCall "touch a";
System "touch b"; NonBlockingSystemCall "touch c";
OnelabRun("client", "touch d");
Exit;
Save "m.msh"; Save View[0] "v.pos"; Print "p.png";
Printf("x = %g", 1) > "out.txt"; Printf("more") >> "out.txt";
CreateDir "folder";
)");
  const std::vector<std::pair<std::string, int>> expected = {
      {"SystemCall", 2}, {"System", 3},  {"NonBlockingSystemCall", 3}, {"OnelabRun", 4},
      {"Exit", 5},       {"Save", 6},    {"Save View", 6},             {"Print", 6},
      {"Printf >", 7},   {"Printf >>", 7}, {"CreateDir", 8}};
  ASSERT_EQ(commands.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(commands[i].command, expected[i].first);
    EXPECT_EQ(commands[i].line, expected[i].second) << commands[i].command;
    EXPECT_NE(commands[i].kind, Kind::ReadsData);
    EXPECT_NE(commands[i].kind, Kind::ReadsScript);
  }
  EXPECT_EQ(commands[8].file_name.value_or(""), "out.txt");
}

TEST(GeoCommands, ReadsWithTheirFileNames) {
  const auto commands = geo_commands(R"(Include "common.geo";
Merge "crank.step";
Merge 'extra.geo';
v() = ShapeFromFile("rod.stp");
x() = ListFromFile("values.txt");
Merge StrCat("a", ".step");
)");
  ASSERT_EQ(commands.size(), 6u);
  EXPECT_EQ(commands[0].kind, Kind::ReadsScript);
  EXPECT_EQ(commands[0].file_name.value_or(""), "common.geo");
  EXPECT_EQ(commands[1].kind, Kind::ReadsData);
  EXPECT_EQ(commands[2].kind, Kind::ReadsScript);  // a merged .geo is parsed
  EXPECT_EQ(commands[3].kind, Kind::ReadsData);
  EXPECT_EQ(commands[3].file_name.value_or(""), "rod.stp");
  EXPECT_EQ(commands[4].file_name.value_or(""), "values.txt");
  EXPECT_FALSE(commands[5].file_name.has_value());
  EXPECT_EQ(commands[5].line, 6);
}

TEST(ScanGeoFile, RefusesWithFileLineAndCommandUnlessTrusted) {
  TempDir dir;
  testing::write_text(dir / "part.geo", "// a part\n\nSystemCall \"touch x\";\n");
  const auto message = message_of([&] { scan_geo_file(dir / "part.geo", {}); });
  EXPECT_NE(message.find("part.geo:3: 'SystemCall' runs a program"), std::string::npos) << message;
  EXPECT_NE(message.find("--trust-part-files"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos);
  GeoScanPolicy trusted;
  trusted.trusted = true;
  EXPECT_NO_THROW(scan_geo_file(dir / "part.geo", trusted));
}

TEST(ScanGeoFile, ReadsOnlyInsideTheAllowedFolders) {
  TempDir dir;
  std::filesystem::create_directories(dir / "case" / "parts");
  testing::write_text(dir / "case" / "common.geo", "h = 1;\n");
  testing::write_text(dir / "outside.geo", "h = 2;\n");
  testing::write_text(dir / "case" / "parts" / "up.geo", "Include \"../common.geo\";\n");
  // From the case folder's parts/: the case folder is allowed when given.
  EXPECT_NE(message_of([&] { scan_geo_file(dir / "case" / "parts" / "up.geo", {}); })
                .find("up.geo:1: 'Include' reads \"../common.geo\", outside the case folder"),
            std::string::npos);
  GeoScanPolicy in_case;
  in_case.read_roots = {dir / "case"};
  const auto scan = scan_geo_file(dir / "case" / "parts" / "up.geo", in_case);
  ASSERT_EQ(scan.files_read.size(), 1u);
  EXPECT_EQ(scan.files_read[0].filename(), "common.geo");

  testing::write_text(dir / "case" / "parts" / "far.geo", "Include \"../../outside.geo\";\n");
  EXPECT_THROW(scan_geo_file(dir / "case" / "parts" / "far.geo", in_case), Error);
  testing::write_text(dir / "case" / "abs.geo", "Merge \"" + (dir / "outside.geo").string() + "\";\n");
  EXPECT_THROW(scan_geo_file(dir / "case" / "abs.geo", in_case), Error);
  // A link inside the folder that leads out of it.
  std::filesystem::create_symlink(dir / "outside.geo", dir / "case" / "link.geo");
  testing::write_text(dir / "case" / "via_link.geo", "Include \"link.geo\";\n");
  EXPECT_THROW(scan_geo_file(dir / "case" / "via_link.geo", in_case), Error);
  // A file name made by an expression cannot be checked.
  testing::write_text(dir / "case" / "expr.geo", "Merge StrCat(\"com\", \"mon.geo\");\n");
  EXPECT_NE(message_of([&] { scan_geo_file(dir / "case" / "expr.geo", in_case); })
                .find("expr.geo:1: 'Merge' names its file by an expression"),
            std::string::npos);
}

TEST(ScanGeoFile, ScansIncludedScriptsAndOptionFiles) {
  TempDir dir;
  testing::write_text(dir / "part.geo", "x = 1;\nInclude \"inner.geo\";\n");
  testing::write_text(dir / "inner.geo", "y = 2;\n\nExit;\n");
  EXPECT_NE(message_of([&] { scan_geo_file(dir / "part.geo", {}); })
                .find("inner.geo:3: 'Exit' ends the program"),
            std::string::npos);
  // Gmsh merges "<file>.opt" after opening a file: a script too.
  testing::write_text(dir / "inner.geo", "y = 2;\n");
  testing::write_text(dir / "part.geo.opt", "Printf(\"x\") > \"/tmp/written\";\n");
  EXPECT_NE(message_of([&] { scan_geo_file(dir / "part.geo", {}); })
                .find("part.geo.opt:1: 'Printf >' writes a file"),
            std::string::npos);
  std::filesystem::remove(dir / "part.geo.opt");
  const auto scan = scan_geo_file(dir / "part.geo", {});
  ASSERT_EQ(scan.files_read.size(), 1u);
  EXPECT_TRUE(scan.all_files_known);
}

TEST(MeshPartFile, RefusedCommandNeverRuns) {
  TempDir dir;
  const auto marker = dir / "ran";
  testing::write_text(dir / "part.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 10, 10, 10};\n"
                                        "SystemCall \"touch " + marker.string() + "\";\n");
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  MeshOptions options;
  options.element_size_m = 0.005;
  const auto message = message_of([&] { mesh_part_file(dir / "part.geo", mm, options); });
  EXPECT_NE(message.find("part.geo:3: 'SystemCall' runs a program"), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(marker));
  mm.trusted = true;  // the user's decision: the command runs
  mesh_part_file(dir / "part.geo", mm, options);
  EXPECT_TRUE(std::filesystem::exists(marker));
}

TEST(MeshPartFile, TwoSeparateSolidsAreRefused) {
  TempDir dir;
  testing::write_text(dir / "two.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 10, 10, 10};\n"
                                       "Box(2) = {20, 0, 0, 10, 10, 10};\n");
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  MeshOptions options;
  options.element_size_m = 0.005;
  const auto message = message_of([&] { mesh_part_file(dir / "two.geo", mm, options); });
  EXPECT_NE(message.find("two.geo: the part is 2 separate solids"), std::string::npos) << message;
  // Two volumes that share a face (fragments) are one body.
  testing::write_text(dir / "glued.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 10, 10, 10};\n"
                                         "Box(2) = {10, 0, 0, 10, 10, 10};\n"
                                         "BooleanFragments{ Volume{1}; Delete; }{ Volume{2}; Delete; }\n");
  EXPECT_NO_THROW(mesh_part_file(dir / "glued.geo", mm, options));
}

}  // namespace
}  // namespace kinetofem::meshes
