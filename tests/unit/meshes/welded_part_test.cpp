// mesh_part_file on a part welded from several solids: boxes written with
// Gmsh's OpenCASCADE API into temporary .brep files (in mm, length_unit 1e-3)
// and .step files. Touching and nearly touching boxes are welded (one
// conformal body, solid and weld sets); a gap above the tolerance and an
// overlap are errors naming both solids; [[solid]] names by file and by a
// point inside.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <gmsh.h>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/solver/element_traits.hpp"
#include "kinetofem/testing/error_message.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;
using testing::TempDir;

struct BoxMm {
  double x, y, z, dx, dy, dz;
};

// Writes the boxes (mm) as separate solids of one CAD file (.brep or .step).
void write_boxes(const std::filesystem::path& file, const std::vector<BoxMm>& boxes) {
  GmshSession session;
  session.call(file.string(), "writing the test boxes", [&] {
    gmsh::option::setString("Geometry.OCCTargetUnit", "MM");
    gmsh::model::add("boxes");
    for (const auto& b : boxes) gmsh::model::occ::addBox(b.x, b.y, b.z, b.dx, b.dy, b.dz);
    gmsh::model::occ::synchronize();
    gmsh::write(file.string());
  });
}

MeshOptions options(double size_m = 0.004) {
  MeshOptions o;
  o.element_size_m = size_m;
  o.order = 1;
  o.optimize = false;
  return o;
}

PartFileOptions in_mm() {
  PartFileOptions part;
  part.length_unit_m = 1e-3;
  return part;
}

using kinetofem::testing::message_of;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Area of a face set (corner triangles / quadrangle halves), m^2, and the sum
// of its normals (right-handed over the corners), m^2.
std::pair<double, Eigen::Vector3d> area_and_normal(const fem::Mesh& mesh, const std::string& set) {
  double area = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  for (const auto& block : mesh.face_set(set)) {
    const int corners = fem::face_facts(block.type).corners;
    for (Index f = 0; f < block.size(); ++f) {
      const auto face = block.face(f);
      const Eigen::Vector3d a = testing::node(mesh, face[0]);
      for (int k = 1; k + 1 < corners; ++k) {
        const Eigen::Vector3d n =
            0.5 * (testing::node(mesh, face[k]) - a).cross(testing::node(mesh, face[k + 1]) - a);
        normal += n;
        area += n.norm();
      }
    }
  }
  return {area, normal};
}

// Two 20 x 10 x 10 mm boxes end to end along x, the second starting at 20 + gap.
std::vector<BoxMm> two_boxes(double gap_mm) {
  return {{0, 0, 0, 20, 10, 10}, {20 + gap_mm, 0, 0, 20, 10, 10}};
}

void expect_welded_boxes(const fem::Mesh& mesh, const std::string& a, const std::string& b) {
  ASSERT_TRUE(mesh.element_sets.count("solid." + a)) << a;
  ASSERT_TRUE(mesh.element_sets.count("solid." + b)) << b;
  EXPECT_FALSE(mesh.element_sets.at("solid." + a).empty());
  EXPECT_FALSE(mesh.element_sets.at("solid." + b).empty());
  EXPECT_EQ(Index(mesh.element_sets.at("solid." + a).size() + mesh.element_sets.at("solid." + b).size()),
            mesh.element_count());
  const std::string weld = weld_set_name(a, b);
  ASSERT_TRUE(mesh.face_sets.count(weld)) << weld;
  ASSERT_TRUE(mesh.node_sets.count(weld)) << weld;
  // The seam is the 10 x 10 mm end face; the solid named first is the one
  // at x < 20 here, so its outward normal is +x.
  const auto [area, normal] = area_and_normal(mesh, weld);
  EXPECT_NEAR(area, 100e-6, 1e-9);
  EXPECT_NEAR(normal.x(), 100e-6, 1e-9);
  for (Index n : mesh.node_sets.at(weld)) EXPECT_NEAR(mesh.nodes(n, 0), 0.020, 0.06e-3);
}

TEST(WeldedPart, TwoTouchingBoxesInOneFileAreOneConformalBody) {
  TempDir dir;
  write_boxes(dir / "two.brep", two_boxes(0.0));
  const auto mesh = mesh_part_file(dir / "two.brep", in_mm(), options());
  expect_welded_boxes(mesh, "solid1", "solid2");
  EXPECT_TRUE(mesh.element_sets.count("body"));
  // Where a node lies: on the seam, and in the second box only.
  const Index on_seam = mesh.node_sets.at("weld.solid1.solid2").front();
  EXPECT_EQ(place_in_welded_part(mesh, on_seam), "solid solid1, seam weld.solid1.solid2");
  Index far = 0;
  for (Index n = 0; n < mesh.node_count(); ++n)
    if (mesh.nodes(n, 0) > mesh.nodes(far, 0)) far = n;
  EXPECT_EQ(place_in_welded_part(mesh, far), "solid solid2");
}

TEST(WeldedPart, TheMeshCacheKeyCoversEverySolidFileAndTheTolerance) {
  TempDir dir;
  write_boxes(dir / "a.brep", {two_boxes(0.0)[0]});
  write_boxes(dir / "b.brep", {two_boxes(0.0)[1]});
  auto part = in_mm();
  part.solids = {{"plate", dir / "a.brep", {}}, {"hub", dir / "b.brep", {}}};
  auto o = options();
  o.cache_dir = dir / "cache";
  auto entries = [&] {
    return std::distance(std::filesystem::directory_iterator(o.cache_dir), std::filesystem::directory_iterator());
  };
  const auto first = mesh_part_file({}, part, o);
  EXPECT_EQ(entries(), 1);
  EXPECT_EQ(mesh_part_file({}, part, o).node_count(), first.node_count());  // from the cache
  EXPECT_EQ(entries(), 1);
  // The second solid's file changes (a box twice as long): a new mesh.
  write_boxes(dir / "b.brep", {{20, 0, 0, 40, 10, 10}});
  const auto longer = mesh_part_file({}, part, o);
  EXPECT_EQ(entries(), 2);
  EXPECT_GT(longer.node_count(), first.node_count());
  part.weld_tolerance_m = 0.01e-3;
  mesh_part_file({}, part, o);
  EXPECT_EQ(entries(), 3);
}

TEST(WeldedPart, TwoFilesAreWeldedAndNamedByTheirSolids) {
  TempDir dir;
  write_boxes(dir / "a.step", {two_boxes(0.0)[0]});
  write_boxes(dir / "b.step", {two_boxes(0.0)[1]});
  PartFileOptions part;
  part.solids = {{"plate", dir / "a.step", {}}, {"hub", dir / "b.step", {}}};
  const auto mesh = mesh_part_file({}, part, options());
  // "hub" < "plate": the seam is oriented out of the hub, at x > 20 mm.
  const auto [area, normal] = area_and_normal(mesh, "weld.hub.plate");
  EXPECT_NEAR(area, 100e-6, 1e-9);
  EXPECT_NEAR(normal.x(), -100e-6, 1e-9);
  EXPECT_FALSE(mesh.element_sets.at("solid.plate").empty());
  EXPECT_FALSE(mesh.element_sets.at("solid.hub").empty());
}

TEST(WeldedPart, AGapWithinTheToleranceIsWelded) {
  TempDir dir;
  write_boxes(dir / "near.brep", two_boxes(0.02));
  auto part = in_mm();
  part.weld_tolerance_m = 0.05e-3;
  const auto mesh = mesh_part_file(dir / "near.brep", part, options());
  EXPECT_TRUE(mesh.face_sets.count("weld.solid1.solid2"));
  EXPECT_FALSE(mesh.face_set("weld.solid1.solid2").empty());
}

TEST(WeldedPart, AGapAboveTheToleranceIsAnErrorNamingBothSolidsAndTheGap) {
  TempDir dir;
  write_boxes(dir / "far.brep", two_boxes(0.5));
  auto part = in_mm();
  part.weld_tolerance_m = 0.05e-3;
  const auto message = message_of([&] { mesh_part_file(dir / "far.brep", part, options()); });
  EXPECT_TRUE(contains(message, "far.brep: solids 'solid1' and 'solid2' are not welded: their gap "
                                "is 0.5 mm, more than the weld tolerance 0.05 mm"))
      << message;
}

TEST(WeldedPart, OverlappingSolidsAreAnErrorNamingBothAndTheOverlap) {
  TempDir dir;
  write_boxes(dir / "a.brep", {{0, 0, 0, 20, 10, 10}});
  write_boxes(dir / "b.brep", {{18, 0, 0, 20, 10, 10}});
  auto part = in_mm();
  part.solids = {{"plate", dir / "a.brep", {}}, {"lug", dir / "b.brep", {}}};
  const auto message = message_of([&] { mesh_part_file({}, part, options()); });
  EXPECT_TRUE(contains(message, "solids 'lug' and 'plate' overlap (interference): 200 mm^3, 2 mm "
                                "thick, more than the weld tolerance 0.05 mm"))
      << message;
}

TEST(WeldedPart, SolidsOfOneFileAreNamedByAPointInside) {
  TempDir dir;
  write_boxes(dir / "two.brep", two_boxes(0.0));
  auto part = in_mm();
  part.solids = {{"right", {}, Eigen::Vector3d(0.030, 0.005, 0.005)},
                 {"left", {}, Eigen::Vector3d(0.005, 0.005, 0.005)}};
  const auto mesh = mesh_part_file(dir / "two.brep", part, options());
  expect_welded_boxes(mesh, "left", "right");
  for (Index e : mesh.element_sets.at("solid.right")) {
    const auto& block = mesh.blocks.front();
    ASSERT_EQ(mesh.blocks.size(), 1u);
    for (Index n : block.element(e)) EXPECT_GE(mesh.nodes(n, 0), 0.020 - 1e-9);
  }
}

TEST(WeldedPart, BadSolidEntriesAreErrors) {
  TempDir dir;
  write_boxes(dir / "two.brep", two_boxes(0.0));
  auto part = in_mm();
  part.solids = {{"hub", {}, Eigen::Vector3d(0.100, 0.005, 0.005)}};
  EXPECT_TRUE(contains(message_of([&] { mesh_part_file(dir / "two.brep", part, options()); }),
                       "[[solid]] 'hub': the point inside_mm = [100, 5, 5] lies in none of the "
                       "file's 2 solids"));
  part.solids = {{"a", {}, Eigen::Vector3d(0.005, 0.005, 0.005)},
                 {"b", {}, Eigen::Vector3d(0.006, 0.005, 0.005)}};
  EXPECT_TRUE(contains(message_of([&] { mesh_part_file(dir / "two.brep", part, options()); }),
                       "[[solid]] 'a' and 'b' name the same solid (solid 1 of the file)"));
  part.solids = {{"solid2", {}, Eigen::Vector3d(0.005, 0.005, 0.005)}};
  EXPECT_TRUE(contains(message_of([&] { mesh_part_file(dir / "two.brep", part, options()); }),
                       "the solid name 'solid2' is given twice"));
  // A [[solid]] by name only: a name by position, or one the part does not have.
  part.solids = {{"hub", {}, {}}};
  EXPECT_TRUE(contains(message_of([&] { mesh_part_file(dir / "two.brep", part, options()); }),
                       "two.brep: the part has no solid 'hub' (the file's 2 solids are solid1 to "
                       "solid2 by position)"));
  part.solids = {{"solid3", {}, {}}};
  EXPECT_TRUE(contains(message_of([&] { mesh_part_file(dir / "two.brep", part, options()); }),
                       "the part has no solid 'solid3'"));
  part.solids = {{"solid2", {}, {}}};
  EXPECT_FALSE(mesh_part_file(dir / "two.brep", part, options()).element_sets.at("solid.solid2").empty());
  part.solids = {{"a b", {}, {}}};
  EXPECT_TRUE(contains(message_of([&] { mesh_part_file(dir / "two.brep", part, options()); }),
                       "[[solid]] name 'a b' must be"));
}

TEST(WeldedPart, OneSolidWithoutSolidEntriesHasNoSolidOrWeldSets) {
  TempDir dir;
  write_boxes(dir / "one.brep", {{0, 0, 0, 20, 10, 10}});
  const auto mesh = mesh_part_file(dir / "one.brep", in_mm(), options());
  for (const auto& [name, set] : mesh.element_sets) EXPECT_EQ(name, "body");
  for (const auto& [name, set] : mesh.face_sets) ADD_FAILURE() << name;
  // Named by a [[solid]] without a file or point: its set is the whole part.
  auto part = in_mm();
  part.solids = {{"plate", {}, {}}};
  const auto named = mesh_part_file(dir / "one.brep", part, options());
  EXPECT_EQ(named.element_sets.at("solid.plate"), named.element_sets.at("body"));
  EXPECT_EQ(named.node_count(), mesh.node_count());
}

}  // namespace
}  // namespace kinetofem::meshes
