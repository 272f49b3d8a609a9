// mesh_part_file: a user's CAD part (STEP, BREP, .geo, .msh) meshed in metres
// with face sets by bounding box; the unit checks, the errors, the cache, and
// the bundled parts of cases/slider_crank_parts.
//
// Test geometry: a crank-like link written with Gmsh's OpenCASCADE API into a
// temporary directory: bosses of diameter 40 mm and length 30 mm (|z| <= 15)
// about (0, 0) and (100, 0) mm with bores of diameter 20 mm, joined by a
// plate 25 mm wide (y) and 12 mm thick (z): the crank of
// cases/slider_crank_parts/parts/make_parts.geo.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>

#include <gmsh.h>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/testing/error_message.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;
using testing::TempDir;

struct LinkMm {  // dimensions of a link, mm
  double length = 100, boss_d = 40, bore_d = 20, boss_l = 30, width = 25, thickness = 12;

  // Exact volume, mm^3 (the formula of LeverDimensions::volume_m3): plate,
  // plus both bosses, minus the plate inside the bosses (t S, S = the disc of
  // radius R within |y| <= w/2, half at each end), minus both bores.
  double volume() const {
    const double R = boss_d / 2, r = bore_d / 2, c = width / 2;
    const double S = 2 * (c * std::sqrt(R * R - c * c) + R * R * std::asin(c / R));
    return width * length * thickness + 2 * M_PI * R * R * boss_l - thickness * S -
           2 * M_PI * r * r * boss_l;
  }
};

// Builds the link in Gmsh's current model, coordinates scaled by k (1 for
// mm, 1e-3 for m).
void build_link(const LinkMm& d, double k) {
  namespace occ = gmsh::model::occ;
  const int boss_0 = occ::addCylinder(0, 0, -d.boss_l / 2 * k, 0, 0, d.boss_l * k, d.boss_d / 2 * k);
  const int boss_1 =
      occ::addCylinder(d.length * k, 0, -d.boss_l / 2 * k, 0, 0, d.boss_l * k, d.boss_d / 2 * k);
  const int plate = occ::addBox(0, -d.width / 2 * k, -d.thickness / 2 * k, d.length * k,
                                d.width * k, d.thickness * k);
  gmsh::vectorpair solid, part;
  std::vector<gmsh::vectorpair> map;
  occ::fuse({{3, boss_0}}, {{3, boss_1}, {3, plate}}, solid, map);
  const int bore_0 = occ::addCylinder(0, 0, -d.boss_l * k, 0, 0, 2 * d.boss_l * k, d.bore_d / 2 * k);
  const int bore_1 =
      occ::addCylinder(d.length * k, 0, -d.boss_l * k, 0, 0, 2 * d.boss_l * k, d.bore_d / 2 * k);
  occ::cut(solid, {{3, bore_0}, {3, bore_1}}, part, map);
  occ::synchronize();
}

// Writes the link as a CAD file (.step in mm; .brep in units of 1/k mm).
void write_link(const std::filesystem::path& file, double k = 1.0, const LinkMm& d = {}) {
  GmshSession session;
  session.call(file.string(), "writing the test part", [&] {
    // The numbers are mm for the STEP writer (its target unit is process-wide
    // OpenCASCADE state that an earlier import in metres may have changed).
    gmsh::option::setString("Geometry.OCCTargetUnit", "MM");
    gmsh::model::add("link");
    build_link(d, k);
    gmsh::write(file.string());
  });
}

// Meshes the link with Gmsh in mm (TET4, with all its geometric entities)
// and writes it as .msh 4.1.
void write_link_msh(const std::filesystem::path& file) {
  GmshSession session;
  session.call(file.string(), "writing the test mesh", [&] {
    gmsh::model::add("link");
    build_link({}, 1.0);
    gmsh::option::setNumber("Mesh.MeshSizeMax", 8.0);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 12);
    gmsh::model::mesh::generate(3);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::write(file.string());
  });
}

// The same link as a .geo script in mm (OpenCASCADE), with optional extra lines.
std::string link_geo(const std::string& extra = "") {
  return R"(SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -15, 0, 0, 30, 20};
Cylinder(2) = {100, 0, -15, 0, 0, 30, 20};
Box(3) = {0, -12.5, -6, 100, 25, 12};
BooleanUnion(4) = { Volume{1}; Delete; }{ Volume{2, 3}; Delete; };
Cylinder(5) = {0, 0, -30, 0, 0, 60, 10};
Cylinder(6) = {100, 0, -30, 0, 0, 60, 10};
BooleanDifference(7) = { Volume{4}; Delete; }{ Volume{5, 6}; Delete; };
)" + extra;
}

MeshOptions options_m(double size_m = 0.006) {
  MeshOptions options;
  options.element_size_m = size_m;
  options.order = 2;
  return options;
}

double mesh_volume(const fem::Mesh& mesh) {
  double volume = 0;
  for (const auto& block : mesh.blocks) {
    EXPECT_EQ(block.type, fem::ElementType::Tet10);
    for (Index e = 0; e < block.size(); ++e) volume += testing::tet10_volume(mesh, block.element(e));
  }
  return volume;
}

// The volume tolerance. With elements_per_circle = 16 a quadratic arc over
// 1/16 of a circle deviates radially by at most 4.6e-5 R (lever_test.cpp);
// over the link's curved surfaces (bosses R = 20 mm, about 6 900 mm^2 outside
// the plate; bores r = 10 mm, 3 770 mm^2) that bounds the volume error by
// 6.3 + 1.7 mm^3 = 1.1e-4 of the 75 384 mm^3. The leading term of the
// interpolation error, (s)(s - h/2)(s - h) along a segment of length h, is odd
// about the mid-node and integrates to zero, so the volume error is of higher
// order: measured 1.4e-6 .. 4.9e-6 at 6 and 4 mm. Hence 1e-4.
constexpr double volume_tolerance = 1e-4;

// The nodes' bounding box of a link in metres: x in [-R, length + R], |y| <= R,
// |z| <= L/2. The planes z = +-L/2 carry nodes; the extremes in x and y lie on
// the bosses' circles, which hold a node at least every 1/16 of a turn: the
// box is exact within R (1 - cos(pi/16)) = 0.38 mm for R = 20 mm.
void expect_link_box(const fem::Mesh& mesh, const LinkMm& d = {}) {
  const Eigen::Vector3d lo = mesh.nodes.colwise().minCoeff(), hi = mesh.nodes.colwise().maxCoeff();
  const double R = d.boss_d / 2e3, slack = R * (1 - std::cos(M_PI / 16)) + 1e-9;
  EXPECT_NEAR(lo.x(), -R, slack);
  EXPECT_LE(lo.x(), -R + slack);
  EXPECT_GE(lo.x(), -R - 1e-9);
  EXPECT_GE(hi.x(), d.length / 1e3 + R - slack);
  EXPECT_LE(hi.x(), d.length / 1e3 + R + 1e-9);
  EXPECT_GE(lo.y(), -R - 1e-9);
  EXPECT_LE(lo.y(), -R + slack);
  EXPECT_LE(hi.y(), R + 1e-9);
  EXPECT_GE(hi.y(), R - slack);
  EXPECT_NEAR(lo.z(), -d.boss_l / 2e3, 1e-9);
  EXPECT_NEAR(hi.z(), d.boss_l / 2e3, 1e-9);
}

FaceSelection selection_mm(const std::string& name, Eigen::Vector3d lo, Eigen::Vector3d hi) {
  return {name, lo * 1e-3, hi * 1e-3};
}

// A box 0.5 mm larger than the bore of diameter d_mm and length l_mm about (x_mm, 0).
FaceSelection bore_box(const std::string& name, double x_mm, double d_mm = 20, double l_mm = 30) {
  const double e = 0.5, r = d_mm / 2;
  return selection_mm(name, {x_mm - r - e, -r - e, -l_mm / 2 - e}, {x_mm + r + e, r + e, l_mm / 2 + e});
}

// Face set `name` is the bore of radius r about (x_axis, 0) and nothing else:
// its node set holds exactly the mesh nodes on that cylinder (|r' - r| <=
// 1e-9 r and |z| <= L/2), its faces cover 2 pi r L and point to the axis.
void expect_bore_set(const fem::Mesh& mesh, const std::string& name, double x_axis, double r,
                     double length) {
  ASSERT_TRUE(mesh.face_sets.count(name)) << name;
  const auto& nodes = mesh.node_set(name);
  ASSERT_FALSE(nodes.empty()) << name;
  auto radius = [&](Index v) { return std::hypot(mesh.nodes(v, 0) - x_axis, mesh.nodes(v, 1)); };
  double worst = 0;
  for (Index v : nodes) worst = std::max(worst, std::abs(radius(v) - r) / r);
  EXPECT_LE(worst, 1e-9) << name << ": a node off the bore radius";
  std::vector<Index> on_cylinder;
  for (Index v = 0; v < mesh.node_count(); ++v)
    if (std::abs(radius(v) - r) <= 1e-9 * r && std::abs(mesh.nodes(v, 2)) <= length / 2 + 1e-12)
      on_cylinder.push_back(v);
  EXPECT_EQ(nodes, on_cylinder) << name << ": the set is not exactly the nodes on the bore";
  const auto& faces = mesh.face_set(name);
  double area = 0;
  for (const auto& block : faces) {
    ASSERT_EQ(block.type, fem::FaceType::Tri6);
    for (Index f = 0; f < block.size(); ++f) {
      const auto face = block.face(f);
      const Eigen::Vector3d normal = testing::face_normal(mesh, face);
      area += normal.norm() / 2;  // of the corner triangle
      Eigen::Vector3d to_axis = -testing::face_centroid(mesh, face, 3);
      to_axis.x() += x_axis;
      to_axis.z() = 0;
      EXPECT_GT(normal.dot(to_axis), 0.0) << name << " face " << f << " points into the material";
    }
  }
  // Flat corner triangles: chords of the 16+ per circle arcs, area within 1.3%.
  EXPECT_NEAR(area / (2 * M_PI * r * length), 1.0, 0.013) << name;
}

using kinetofem::testing::message_of;

// ---- units and sizes -----------------------------------------------------------

TEST(MeshPartFile, StepInMillimetresMeshesInMetres) {
  TempDir dir;
  write_link(dir / "crank.step");
  EXPECT_EQ(cad_file_length_unit_m(dir / "crank.step"), 1e-3);
  const auto mesh = mesh_part_file(dir / "crank.step", {}, options_m());
  expect_link_box(mesh);
  EXPECT_NEAR(mesh_volume(mesh) / (LinkMm{}.volume() * 1e-9), 1.0, volume_tolerance);
  // The imported solid is the set "body" (as for mesh_geometry).
  EXPECT_EQ(mesh.element_sets.at("body").size(), std::size_t(mesh.element_count()));
  // The same with the agreeing length unit given.
  PartFileOptions part;
  part.length_unit_m = 1e-3;
  const auto checked = mesh_part_file(dir / "crank.step", part, options_m());
  testing::expect_same_mesh(checked, mesh, 0.0);
}

TEST(MeshPartFile, BrepAndGeoInMillimetresWithLengthUnitMeshInMetres) {
  TempDir dir;
  PartFileOptions part;
  part.length_unit_m = 1e-3;
  const double exact_m3 = LinkMm{}.volume() * 1e-9;

  write_link(dir / "link_mm.brep", 1.0);
  const auto brep = mesh_part_file(dir / "link_mm.brep", part, options_m());
  expect_link_box(brep);
  EXPECT_NEAR(mesh_volume(brep) / exact_m3, 1.0, volume_tolerance);

  testing::write_text(dir / "link_mm.geo", link_geo());
  const auto geo = mesh_part_file(dir / "link_mm.geo", part, options_m());
  expect_link_box(geo);
  EXPECT_NEAR(mesh_volume(geo) / exact_m3, 1.0, volume_tolerance);

  // The element size is in metres whatever the file's unit: the part drawn
  // in metres gets (nearly) the same mesh. Without the conversion the mm part
  // would be meshed with 6 mm = 0.006 file units (1e9 times more elements)
  // or the m part with 6 m (curvature-limited only).
  write_link(dir / "link_m.brep", 1e-3);
  PartFileOptions metres;
  metres.length_unit_m = 1.0;
  const auto in_m = mesh_part_file(dir / "link_m.brep", metres, options_m());
  expect_link_box(in_m);
  EXPECT_NEAR(double(in_m.node_count()) / double(brep.node_count()), 1.0, 0.05);
}

TEST(MeshPartFile, MshInMillimetresIsScaledAndCanTakeFaceSelections) {
  TempDir dir;
  write_link_msh(dir / "link_mm.msh");
  PartFileOptions part;
  part.length_unit_m = 1e-3;
  const auto mesh = mesh_part_file(dir / "link_mm.msh", part, options_m());
  const auto raw = read_msh(dir / "link_mm.msh");
  ASSERT_EQ(mesh.node_count(), raw.node_count());
  EXPECT_LE((mesh.nodes - raw.nodes * 1e-3).cwiseAbs().maxCoeff(), 1e-18);
  EXPECT_EQ(mesh.blocks[0].connectivity, raw.blocks[0].connectivity);
  EXPECT_NEAR(mesh.nodes.col(2).maxCoeff(), 0.015, 1e-12);
  EXPECT_NEAR(mesh.nodes.col(0).minCoeff(), -0.020, 0.0004);

  // Gmsh's surfaces of the .msh (its $Entities) can be selected as well.
  part.face_sets = {bore_box("bore_O", 0.0)};
  const auto named = mesh_part_file(dir / "link_mm.msh", part, options_m());
  ASSERT_EQ(named.node_count(), raw.node_count());
  const auto& nodes = named.node_set("bore_O");
  ASSERT_FALSE(nodes.empty());
  for (Index v : nodes)
    EXPECT_NEAR(std::hypot(named.nodes(v, 0), named.nodes(v, 1)), 0.010, 1e-11) << v;
  ASSERT_EQ(named.face_set("bore_O").size(), 1u);
  EXPECT_EQ(named.face_set("bore_O")[0].type, fem::FaceType::Tri3);

  // No unit: an error (the .msh carries none).
  EXPECT_NE(message_of([&] { mesh_part_file(dir / "link_mm.msh", {}, options_m()); })
                .find("carry no length unit"),
            std::string::npos);
}

// ---- face selections -------------------------------------------------------

TEST(MeshPartFile, FaceSelectionPicksExactlyTheBoreSurface) {
  TempDir dir;
  write_link(dir / "crank.step");
  PartFileOptions part;
  part.face_sets = {bore_box("bore_O", 0.0), bore_box("bore_B", 100.0)};
  const auto mesh = mesh_part_file(dir / "crank.step", part, options_m());
  expect_bore_set(mesh, "bore_O", 0.0, 0.010, 0.030);
  expect_bore_set(mesh, "bore_B", 0.100, 0.010, 0.030);
  // The two sets do not share a node.
  std::vector<Index> common;
  std::set_intersection(mesh.node_set("bore_O").begin(), mesh.node_set("bore_O").end(),
                        mesh.node_set("bore_B").begin(), mesh.node_set("bore_B").end(),
                        std::back_inserter(common));
  EXPECT_TRUE(common.empty());

  // The same selection on the part as BREP and .geo in mm (boxes in m).
  part.length_unit_m = 1e-3;
  write_link(dir / "crank.brep");
  const auto brep = mesh_part_file(dir / "crank.brep", part, options_m());
  expect_bore_set(brep, "bore_O", 0.0, 0.010, 0.030);
  expect_bore_set(brep, "bore_B", 0.100, 0.010, 0.030);
  testing::write_text(dir / "crank.geo", link_geo());
  const auto geo = mesh_part_file(dir / "crank.geo", part, options_m());
  expect_bore_set(geo, "bore_O", 0.0, 0.010, 0.030);
}

TEST(MeshPartFile, BoxAroundAWholeEndSelectsAllItsSurfaces) {
  // A box around the whole boss at O holds the faces that lie within the
  // boss: its bore, its two annular ends and its outer cylinder; the plate's
  // faces run on to the other boss and are not inside.
  TempDir dir;
  write_link(dir / "crank.step");
  PartFileOptions part;
  part.face_sets = {selection_mm("boss_O", {-21, -21, -16}, {21, 21, 16})};
  const auto mesh = mesh_part_file(dir / "crank.step", part, options_m());
  const auto& nodes = mesh.node_set("boss_O");
  ASSERT_FALSE(nodes.empty());
  for (Index v : nodes) EXPECT_LE(std::hypot(mesh.nodes(v, 0), mesh.nodes(v, 1)), 0.020 + 1e-9);
  // It holds the bore (the node at the bore radius on the plane z = 0, at least).
  EXPECT_TRUE(std::any_of(nodes.begin(), nodes.end(), [&](Index v) {
    return std::abs(std::hypot(mesh.nodes(v, 0), mesh.nodes(v, 1)) - 0.010) < 1e-11;
  }));
}

// ---- errors ------------------------------------------------------------------

TEST(MeshPartFile, MissingFileAndUnknownExtensionAreErrors) {
  TempDir dir;
  const auto missing = message_of([&] { mesh_part_file(dir / "nope.step", {}, options_m()); });
  EXPECT_NE(missing.find("nope.step: no such part file"), std::string::npos) << missing;
  testing::write_text(dir / "part.stl", "solid x\nendsolid x\n");
  const auto unknown = message_of([&] { mesh_part_file(dir / "part.stl", {}, options_m()); });
  EXPECT_NE(unknown.find("part.stl: unknown part file type '.stl' (expected one of .step, .stp, "
                         ".iges, .igs, .brep, .geo, .msh)"),
            std::string::npos)
      << unknown;
}

TEST(MeshPartFile, UnreadableFilesAreErrorsNamingTheFile) {
  TempDir dir;
  testing::write_text(dir / "bad.step", "ISO-10303-21;\nthis is not a STEP file\n");
  const auto step = message_of([&] { mesh_part_file(dir / "bad.step", {}, options_m()); });
  EXPECT_NE(step.find("bad.step: importing the shape failed"), std::string::npos) << step;
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  testing::write_text(dir / "bad.brep", "not a brep\n");
  const auto brep = message_of([&] { mesh_part_file(dir / "bad.brep", mm, options_m()); });
  EXPECT_NE(brep.find("bad.brep: OpenCASCADE read no shape from the file"), std::string::npos) << brep;
  testing::write_text(dir / "bad.geo", "Point(1) = {0, 0, 0;\n");
  const auto geo = message_of([&] { mesh_part_file(dir / "bad.geo", mm, options_m()); });
  EXPECT_NE(geo.find("bad.geo: gmsh::open failed"), std::string::npos) << geo;
  testing::write_text(dir / "bad.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2\n");
  const auto msh = message_of([&] { mesh_part_file(dir / "bad.msh", mm, options_m()); });
  EXPECT_NE(msh.find("bad.msh"), std::string::npos) << msh;
}

TEST(MeshPartFile, AGeometryGmshCannotMeshIsAnError) {
  // A volume whose surface loop is open (a tetrahedron missing a face).
  TempDir dir;
  testing::write_text(dir / "open.geo", R"(Point(1) = {0, 0, 0}; Point(2) = {10, 0, 0};
Point(3) = {0, 10, 0}; Point(4) = {0, 0, 10};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1}; Line(4) = {1, 4}; Line(5) = {2, 4};
Line(6) = {3, 4};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Curve Loop(2) = {1, 5, -4}; Plane Surface(2) = {2};
Curve Loop(3) = {2, 6, -5}; Plane Surface(3) = {3};
Surface Loop(1) = {1, 2, 3};
Volume(1) = {1};
)");
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  const auto message = message_of([&] { mesh_part_file(dir / "open.geo", mm, options_m(0.004)); });
  EXPECT_NE(message.find("open.geo: meshing failed"), std::string::npos) << message;
}

TEST(MeshPartFile, PartsWithoutVolumesAreErrors) {
  TempDir dir;
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  // A surface only.
  testing::write_text(dir / "plate.geo", "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0, 0, 0, 10, 5};\n");
  const auto geo = message_of([&] { mesh_part_file(dir / "plate.geo", mm, options_m()); });
  EXPECT_NE(geo.find("plate.geo: the geometry has no volumes to mesh"), std::string::npos) << geo;
  // A surface mesh.
  {
    GmshSession session;
    session.call("surface.msh", "writing", [&] {
      gmsh::model::add("s");
      gmsh::model::occ::addRectangle(0, 0, 0, 10, 5);
      gmsh::model::occ::synchronize();
      gmsh::option::setNumber("Mesh.MeshSizeMax", 2.0);
      gmsh::model::mesh::generate(2);
      gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
      gmsh::write((dir / "surface.msh").string());
    });
  }
  const auto msh = message_of([&] { mesh_part_file(dir / "surface.msh", mm, options_m()); });
  EXPECT_NE(msh.find("surface.msh: the mesh has no volume elements"), std::string::npos) << msh;
}

TEST(MeshPartFile, LengthUnitErrors) {
  TempDir dir;
  write_link(dir / "crank.step");
  write_link(dir / "crank.brep");
  // Required for .brep / .geo / .msh.
  const auto none = message_of([&] { mesh_part_file(dir / "crank.brep", {}, options_m()); });
  EXPECT_NE(none.find("crank.brep: .brep files carry no length unit: give length_unit"),
            std::string::npos)
      << none;
  // Positive.
  PartFileOptions part;
  part.length_unit_m = -1e-3;
  const auto negative = message_of([&] { mesh_part_file(dir / "crank.brep", part, options_m()); });
  EXPECT_NE(negative.find("must be positive"), std::string::npos) << negative;
  part.length_unit_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mesh_part_file(dir / "crank.brep", part, options_m()), Error);
  // A STEP in mm given as metres.
  part.length_unit_m = 1.0;
  const auto disagree = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(disagree.find("crank.step: length_unit = 1 m per file unit disagrees with the file's "
                          "own unit, 0.001 m"),
            std::string::npos)
      << disagree;
}

TEST(MeshPartFile, BadBoxesAreErrorsNamingTheSelection) {
  TempDir dir;
  write_link(dir / "crank.step");
  PartFileOptions part;
  part.face_sets = {selection_mm("bore_O", {10.5, -10.5, -15.5}, {-10.5, 10.5, 15.5})};
  const auto inverted = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(inverted.find("face set 'bore_O' of "), std::string::npos) << inverted;
  EXPECT_NE(inverted.find("crank.step: the box [10.5, -10.5, -15.5, -10.5, 10.5, 15.5] mm has "
                          "min > max in x (10.5 > -10.5 mm)"),
            std::string::npos)
      << inverted;

  part.face_sets = {selection_mm("bore_O", {-10.5, -10.5, -15.5}, {10.5, 10.5, 15.5})};
  part.face_sets[0].box_max_m.y() = std::numeric_limits<double>::infinity();
  const auto infinite = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(infinite.find("face set 'bore_O' of "), std::string::npos) << infinite;
  EXPECT_NE(infinite.find("has a corner that is not finite"), std::string::npos) << infinite;
  part.face_sets[0].box_min_m.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(mesh_part_file(dir / "crank.step", part, options_m()), Error);

  // Nothing inside: the box and the part's extent in mm.
  part.face_sets = {selection_mm("bore_O", {200, 200, 200}, {210, 210, 210})};
  const auto empty = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(empty.find("face set 'bore_O' of "), std::string::npos) << empty;
  EXPECT_NE(empty.find("crank.step: no surface lies inside box [200, 200, 200, 210, 210, 210] mm; "
                       "the part spans [-20, -20, -15, 120, 20, 15] mm"),
            std::string::npos)
      << empty;
  // Too small a box: it says that it cuts through faces.
  part.face_sets = {selection_mm("bore_O", {-9, -9, -14}, {9, 9, 14})};
  const auto small = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(small.find("no surface lies inside box [-9, -9, -14, 9, 9, 14] mm"), std::string::npos)
      << small;
  EXPECT_NE(small.find("partly inside: the box must hold a whole face"), std::string::npos) << small;
  // A box in metres given where mm were meant (1000 times too small) holds nothing.
  part.face_sets = {selection_mm("bore_O", {-0.0105, -0.0105, -0.0155}, {0.0105, 0.0105, 0.0155})};
  EXPECT_THROW(mesh_part_file(dir / "crank.step", part, options_m()), Error);
}

TEST(MeshPartFile, SelectionNamesMustBeNewAndDistinct) {
  TempDir dir;
  write_link(dir / "crank.step");
  PartFileOptions part;
  // "body" is the group of the imported solid.
  part.face_sets = {bore_box("body", 0.0)};
  const auto body = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(body.find("face set 'body' of "), std::string::npos) << body;
  EXPECT_NE(body.find("crank.step: the file already has a physical group of that name (dimension 3)"),
            std::string::npos)
      << body;
  // A group of a .geo file.
  testing::write_text(dir / "named.geo",
                      link_geo("Physical Surface(\"bore_O\") = Surface In BoundingBox{-10.5, "
                               "-10.5, -15.5, 10.5, 10.5, 15.5};\nPhysical Volume(\"crank\") = "
                               "{7};\n"));
  PartFileOptions geo;
  geo.length_unit_m = 1e-3;
  geo.face_sets = {bore_box("bore_O", 0.0)};
  const auto group = message_of([&] { mesh_part_file(dir / "named.geo", geo, options_m()); });
  EXPECT_NE(group.find("face set 'bore_O' of "), std::string::npos) << group;
  EXPECT_NE(group.find("named.geo: the file already has a physical group of that name (dimension 2)"),
            std::string::npos)
      << group;
  // Without the clash the file's own groups come through, with the selection.
  geo.face_sets = {bore_box("bore_B", 100.0)};
  const auto mesh = mesh_part_file(dir / "named.geo", geo, options_m());
  expect_bore_set(mesh, "bore_O", 0.0, 0.010, 0.030);
  expect_bore_set(mesh, "bore_B", 0.100, 0.010, 0.030);
  EXPECT_EQ(mesh.element_sets.at("crank").size(), std::size_t(mesh.element_count()));
  // Twice the same name, or none.
  part.face_sets = {bore_box("bore_O", 0.0), bore_box("bore_O", 100.0)};
  const auto twice = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(twice.find("face set 'bore_O' of "), std::string::npos) << twice;
  EXPECT_NE(twice.find("the name is given to two selections"), std::string::npos) << twice;
  part.face_sets = {bore_box("", 0.0)};
  const auto empty = message_of([&] { mesh_part_file(dir / "crank.step", part, options_m()); });
  EXPECT_NE(empty.find("a face set selection has an empty name"), std::string::npos) << empty;
}

// ---- units declared by STEP / IGES files ---------------------------------------

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (auto at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

TEST(CadFileLengthUnit, ReadsStepAndIgesUnits) {
  TempDir dir;
  write_link(dir / "mm.step");
  EXPECT_EQ(cad_file_length_unit_m(dir / "mm.step"), 1e-3);
  std::ifstream in(dir / "mm.step");
  const std::string step((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_NE(step.find("SI_UNIT(.MILLI.,.METRE.)"), std::string::npos);
  // The same file declaring metres: the unit check rejects length_unit = mm.
  testing::write_text(dir / "m.stp", replace_all(step, "SI_UNIT(.MILLI.,.METRE.)", "SI_UNIT($,.METRE.)"));
  EXPECT_EQ(cad_file_length_unit_m(dir / "m.stp"), 1.0);
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  const auto disagree = message_of([&] { mesh_part_file(dir / "m.stp", mm, options_m()); });
  EXPECT_NE(disagree.find("m.stp: length_unit = 0.001 m per file unit disagrees with the file's own "
                          "unit, 1 m"),
            std::string::npos)
      << disagree;
  // Inches, as CAD programs write them (a conversion-based unit over mm).
  testing::write_text(dir / "inch.step", R"(ISO-10303-21;
HEADER; FILE_NAME('a;b','',(''),(''),'','',''); ENDSEC;
DATA;
#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );
#2 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4),#1);
#3 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);
#4 = ( CONVERSION_BASED_UNIT('INCH',#2) LENGTH_UNIT() NAMED_UNIT(#3) );
#5 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );
/* a comment; with a semicolon */
#6 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) GLOBAL_UNIT_ASSIGNED_CONTEXT((#4,#5))
  REPRESENTATION_CONTEXT('Context #1','3D Context; with unit and uncertainty') );
ENDSEC;
END-ISO-10303-21;
)");
  EXPECT_NEAR(*cad_file_length_unit_m(dir / "inch.step"), 0.0254, 1e-15);
  // No unit at all.
  testing::write_text(dir / "none.step", "ISO-10303-21;\nDATA;\n#1 = CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\n");
  EXPECT_FALSE(cad_file_length_unit_m(dir / "none.step").has_value());
  const auto unknown = message_of([&] { mesh_part_file(dir / "none.step", mm, options_m()); });
  EXPECT_NE(unknown.find("none.step: cannot read the file's length unit"), std::string::npos) << unknown;

  // IGES: the units flag, field 14 of the global section (2 = mm, 1 = inch),
  // and with flag 3 the units name, field 15.
  auto iges = [](const std::string& flag, const std::string& name) {
    std::string global = "1H,,1H;,4HPART,8Hpart.igs,4Htest,4Htest,32,38,6,308,15,4HPART,1.," + flag +
                         "," + name + ",1,0.01,15H20240101.120000,1E-07,100.,,,11,0,;";
    std::string text = fmt::format("{:<72}S{:>7}\n", "test part", 1);
    for (std::size_t k = 0; k * 72 < global.size(); ++k)
      text += fmt::format("{:<72}G{:>7}\n", global.substr(k * 72, 72), k + 1);
    return text;
  };
  testing::write_text(dir / "mm.igs", iges("2", "2HMM"));
  EXPECT_EQ(cad_file_length_unit_m(dir / "mm.igs"), 1e-3);
  testing::write_text(dir / "inch.iges", iges("1", "4HINCH"));
  EXPECT_EQ(cad_file_length_unit_m(dir / "inch.iges"), 0.0254);
  testing::write_text(dir / "named.igs", iges("3", "1HM"));
  EXPECT_EQ(cad_file_length_unit_m(dir / "named.igs"), 1.0);
  PartFileOptions metres;
  metres.length_unit_m = 1.0;
  const auto igs = message_of([&] { mesh_part_file(dir / "mm.igs", metres, options_m()); });
  EXPECT_NE(igs.find("mm.igs: length_unit = 1 m per file unit disagrees"), std::string::npos) << igs;

  EXPECT_THROW(cad_file_length_unit_m(dir / "x.brep"), Error);
  EXPECT_THROW(cad_file_length_unit_m(dir / "missing.step"), Error);
}

// ---- cache ---------------------------------------------------------------------

TEST(MeshPartFile, CacheKeysOnUnitAndSelections) {
  TempDir dir;
  write_link(dir / "crank.brep");
  MeshOptions options = options_m();
  options.cache_dir = dir / "cache";
  auto entries = [&] {
    return std::distance(std::filesystem::directory_iterator(options.cache_dir),
                         std::filesystem::directory_iterator());
  };
  PartFileOptions part;
  part.length_unit_m = 1e-3;
  part.face_sets = {bore_box("bore_O", 0.0)};
  const auto first = mesh_part_file(dir / "crank.brep", part, options);
  ASSERT_EQ(entries(), 1);
  const auto second = mesh_part_file(dir / "crank.brep", part, options);  // from the cache
  EXPECT_EQ(entries(), 1);
  testing::expect_same_mesh(second, first, 0.0);
  // Another name, another box, another unit: new entries.
  part.face_sets[0].name = "pivot";
  mesh_part_file(dir / "crank.brep", part, options);
  EXPECT_EQ(entries(), 2);
  part.face_sets[0] = bore_box("pivot", 100.0);
  const auto moved = mesh_part_file(dir / "crank.brep", part, options);
  EXPECT_EQ(entries(), 3);
  EXPECT_GT(moved.nodes(moved.node_set("pivot").front(), 0), 0.08);
  part.length_unit_m = 1.2e-3;  // the same file read in units of 1.2 mm: 1.2 times larger
  part.face_sets[0] = bore_box("pivot", 120.0, 24, 36);
  const auto larger = mesh_part_file(dir / "crank.brep", part, options);
  EXPECT_EQ(entries(), 4);
  EXPECT_NEAR(larger.nodes.col(2).maxCoeff(), 0.018, 1e-9);
  expect_bore_set(larger, "pivot", 0.120, 0.012, 0.036);
}

TEST(MeshPartFile, CacheKeysOnTheFilesAGeoReads) {
  // A .geo that imports a STEP (the name_faces.geo pattern of
  // cases/slider_crank_parts): the STEP changed, the mesh must change; both
  // unchanged, the cached mesh is used.
  TempDir dir;
  write_link(dir / "link.step");
  testing::write_text(dir / "part.geo", "SetFactory(\"OpenCASCADE\");\nGeometry.OCCTargetUnit = \"MM\";\n"
                                        "v() = ShapeFromFile(\"link.step\");\n");
  MeshOptions options = options_m();
  options.cache_dir = dir / "cache";
  auto entries = [&] {
    return std::distance(std::filesystem::directory_iterator(options.cache_dir),
                         std::filesystem::directory_iterator());
  };
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  const auto first = mesh_part_file(dir / "part.geo", mm, options);
  EXPECT_NEAR(mesh_volume(first) / (LinkMm{}.volume() * 1e-9), 1.0, volume_tolerance);
  const auto again = mesh_part_file(dir / "part.geo", mm, options);
  ASSERT_EQ(entries(), 1);
  testing::expect_same_mesh(again, first, 0.0);

  LinkMm longer;
  longer.length = 150;
  write_link(dir / "link.step", 1.0, longer);
  const auto second = mesh_part_file(dir / "part.geo", mm, options);
  EXPECT_EQ(entries(), 2);
  EXPECT_NEAR(mesh_volume(second) / (longer.volume() * 1e-9), 1.0, volume_tolerance);
  EXPECT_NEAR(second.nodes.col(0).maxCoeff(), 0.170, 1e-6);  // the far boss, r = 20 mm about x = 150 mm
}

// ---- OpenCASCADE's unit state between calls --------------------------------------

TEST(MeshPartFile, GeoMergingAStepAfterAStepImportStillReadsMillimetres) {
  // OpenCASCADE keeps the STEP target unit process-wide; after a STEP import
  // in metres a .geo's Merge of a STEP must still come in mm (its default).
  TempDir dir;
  write_link(dir / "crank.step");
  mesh_part_file(dir / "crank.step", {}, options_m());  // imports in metres
  testing::write_text(dir / "merge.geo",
                      "SetFactory(\"OpenCASCADE\");\nMerge \"crank.step\";\n");
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  const auto mesh = mesh_part_file(dir / "merge.geo", mm, options_m());
  expect_link_box(mesh);
}

// ---- the bundled parts of cases/slider_crank_parts -------------------------------

const std::filesystem::path parts_dir = "cases/slider_crank_parts/parts";  // tests run from the source root

TEST(SliderCrankParts, CrankAndRodStepMeshWithTheirBores) {
  // The face set boxes of cases/slider_crank_parts/README.md.
  PartFileOptions crank;
  crank.length_unit_m = 1e-3;
  crank.face_sets = {bore_box("bore_O", 0.0), bore_box("bore_B", 100.0)};
  const auto c = mesh_part_file(parts_dir / "crank.step", crank, options_m(0.004));
  expect_link_box(c);
  EXPECT_NEAR(mesh_volume(c) / (LinkMm{}.volume() * 1e-9), 1.0, volume_tolerance);
  expect_bore_set(c, "bore_O", 0.0, 0.010, 0.030);
  expect_bore_set(c, "bore_B", 0.100, 0.010, 0.030);

  const LinkMm rod{300, 36, 16, 24, 20, 10};
  PartFileOptions r;
  r.face_sets = {bore_box("bore_B", 0.0, 16, 24), bore_box("bore_C", 300.0, 16, 24)};
  const auto m = mesh_part_file(parts_dir / "rod.step", r, options_m(0.004));
  expect_link_box(m, rod);
  EXPECT_NEAR(mesh_volume(m) / (rod.volume() * 1e-9), 1.0, volume_tolerance);
  expect_bore_set(m, "bore_B", 0.0, 0.008, 0.024);
  expect_bore_set(m, "bore_C", 0.300, 0.008, 0.024);
}

TEST(SliderCrankParts, NameFacesGeoGivesTheBoreSets) {
  PartFileOptions mm;
  mm.length_unit_m = 1e-3;
  const auto mesh = mesh_part_file(parts_dir / "name_faces.geo", mm, options_m());
  expect_link_box(mesh);
  expect_bore_set(mesh, "bore_O", 0.0, 0.010, 0.030);
  expect_bore_set(mesh, "bore_B", 0.100, 0.010, 0.030);
  EXPECT_EQ(mesh.element_sets.at("crank").size(), std::size_t(mesh.element_count()));
}

}  // namespace
}  // namespace kinetofem::meshes
