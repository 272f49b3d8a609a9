// read_msh / write_msh: Gmsh-written files (ASCII and binary) read the same,
// write/read round trips, Gmsh node ordering, and bad files.
#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>

#include <gmsh.h>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/meshes/msh_io.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;
using testing::TempDir;
using testing::write_text;

// A 1 x 0.5 x 0.25 m box; faces and the origin picked by bounding box. The
// free point 100 is in no element: read_msh must drop its node.
constexpr const char* box_geo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.5, 0.25};
e = 1e-6;
Point(100) = {5, 5, 5};
Physical Volume("body") = {1};
Physical Surface("left") = Surface In BoundingBox{-e, -e, -e, e, 0.5 + e, 0.25 + e};
Physical Surface("right") = Surface In BoundingBox{1 - e, -e, -e, 1 + e, 0.5 + e, 0.25 + e};
Physical Point("origin") = Point In BoundingBox{-e, -e, -e, e, e, e};
Physical Point("free") = {100};
)";

// Meshes `geo` with Gmsh itself (as a user would) and writes it as ASCII
// and binary .msh 4.1.
void gmsh_mesh_and_write(const std::filesystem::path& geo, int dim, int order,
                         const std::vector<std::pair<std::filesystem::path, bool>>& outputs) {
  GmshSession session;
  session.call(geo.string(), "meshing", [&] {
    gmsh::open(geo.string());
    gmsh::option::setNumber("Mesh.MeshSizeMax", 0.2);
    gmsh::option::setNumber("Mesh.ElementOrder", order);
    gmsh::model::mesh::generate(dim);
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    for (const auto& [file, binary] : outputs) {
      gmsh::option::setNumber("Mesh.Binary", binary ? 1 : 0);
      gmsh::write(file.string());
    }
  });
}

void expect_error_naming(const std::filesystem::path& file, const std::string& also = "") {
  try {
    read_msh(file);
    ADD_FAILURE() << "no Error for " << file;
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(file.string()), std::string::npos) << message;
    if (!also.empty()) {
      EXPECT_NE(message.find(also), std::string::npos) << message;
    }
  }
}

TEST(ReadMsh, GmshWrittenAsciiAndBinaryGiveTheSameMesh) {
  TempDir dir;
  write_text(dir / "box.geo", box_geo);
  gmsh_mesh_and_write(dir / "box.geo", 3, 1, {{dir / "ascii.msh", false}, {dir / "binary.msh", true}});
  const auto ascii = read_msh(dir / "ascii.msh");
  const auto binary = read_msh(dir / "binary.msh");
  // Gmsh writes ASCII coordinates with 16 significant digits: 1e-15 m here.
  testing::expect_same_mesh(ascii, binary, 1e-15);

  ASSERT_EQ(ascii.blocks.size(), 1u);
  EXPECT_EQ(ascii.blocks[0].type, fem::ElementType::Tet4);
  const Index elements = ascii.element_count();
  std::vector<Index> all(static_cast<std::size_t>(elements));
  for (Index e = 0; e < elements; ++e) all[std::size_t(e)] = e;
  EXPECT_EQ(ascii.element_sets.at("body"), all);

  // Every node is used by an element (the free point 100 is dropped).
  std::set<Index> used(ascii.blocks[0].connectivity.begin(), ascii.blocks[0].connectivity.end());
  EXPECT_EQ(Index(used.size()), ascii.node_count());
  EXPECT_TRUE(ascii.node_sets.at("free").empty());
  EXPECT_LE(ascii.nodes.maxCoeff(), 1.0);

  // Node sets hold their faces' nodes, at the right place; the origin is one node.
  for (Index v : ascii.node_set("left")) EXPECT_NEAR(ascii.nodes(v, 0), 0.0, 1e-12);
  for (Index v : ascii.node_set("right")) EXPECT_NEAR(ascii.nodes(v, 0), 1.0, 1e-12);
  EXPECT_EQ(ascii.node_set("left"), fem::nodes_of_faces(ascii.face_set("left")));
  ASSERT_EQ(ascii.node_set("origin").size(), 1u);
  EXPECT_LE(testing::node(ascii, ascii.node_set("origin")[0]).norm(), 1e-12);
  EXPECT_EQ(ascii.node_set("body").size(), std::size_t(ascii.node_count()));

  // Face sets: TRI3, normals out of the box (-x on the left, +x on the right),
  // and their total area is the face area 0.5 x 0.25.
  for (const auto& [name, sign] : {std::pair{"left", -1.0}, {"right", 1.0}}) {
    const auto& faces = ascii.face_set(name);
    ASSERT_EQ(faces.size(), 1u);
    EXPECT_EQ(faces[0].type, fem::FaceType::Tri3);
    double area = 0;
    for (Index f = 0; f < faces[0].size(); ++f) {
      const auto normal = testing::face_normal(ascii, faces[0].face(f));
      EXPECT_GT(sign * normal.x(), 0.0) << name << " face " << f;
      area += normal.norm() / 2;
    }
    EXPECT_NEAR(area, 0.5 * 0.25, 1e-12) << name;
  }
  // Positive (Gmsh) orientation of every tetrahedron; volumes add up to the box's.
  double volume = 0;
  for (Index e = 0; e < elements; ++e) {
    const double v = testing::corner_tet_volume(ascii, ascii.blocks[0].element(e));
    EXPECT_GT(v, 0.0) << "element " << e;
    volume += v;
  }
  EXPECT_NEAR(volume, 1.0 * 0.5 * 0.25, 1e-12);
}

TEST(ReadMsh, Tet10MidEdgeNodesFollowTheGmshOrdering) {
  // mesh.hpp: TET10 mid-edge nodes 4 (0-1), 5 (1-2), 6 (2-0), 7 (3-0), 8 (3-2),
  // 9 (3-1). On a box all edges are straight, so each mid node is exactly the
  // midpoint of its corner pair (to rounding, 1e-12 m).
  TempDir dir;
  write_text(dir / "box.geo", box_geo);
  gmsh_mesh_and_write(dir / "box.geo", 3, 2, {{dir / "tet10.msh", true}});
  const auto mesh = read_msh(dir / "tet10.msh");
  ASSERT_EQ(mesh.blocks.size(), 1u);
  ASSERT_EQ(mesh.blocks[0].type, fem::ElementType::Tet10);
  const int pairs[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  double volume = 0;
  for (Index e = 0; e < mesh.blocks[0].size(); ++e) {
    const auto element = mesh.blocks[0].element(e);
    for (int m = 0; m < 6; ++m) {
      const Eigen::Vector3d midpoint =
          (testing::node(mesh, element[pairs[m][0]]) + testing::node(mesh, element[pairs[m][1]])) / 2;
      EXPECT_LE((testing::node(mesh, element[4 + m]) - midpoint).norm(), 1e-12)
          << "element " << e << " node " << 4 + m;
    }
    volume += testing::tet10_volume(mesh, element);
  }
  EXPECT_NEAR(volume, 1.0 * 0.5 * 0.25, 1e-12);
  // TRI6 faces: mid nodes 3 (0-1), 4 (1-2), 5 (2-0).
  for (const auto& block : mesh.face_set("left")) {
    ASSERT_EQ(block.type, fem::FaceType::Tri6);
    for (Index f = 0; f < block.size(); ++f) {
      const auto face = block.face(f);
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d midpoint =
            (testing::node(mesh, face[k]) + testing::node(mesh, face[(k + 1) % 3])) / 2;
        EXPECT_LE((testing::node(mesh, face[3 + k]) - midpoint).norm(), 1e-12);
      }
    }
  }
}

TEST(WriteMsh, AsciiAndBinaryRoundTripsGiveTheSameMesh) {
  TempDir dir;
  write_text(dir / "box.geo", box_geo);
  MeshOptions options;
  options.element_size_m = 0.2;
  options.order = 2;
  auto mesh = mesh_geometry(dir / "box.geo", options);
  // Sets a .msh file must carry beyond Gmsh's own groups: overlapping element
  // sets and a node set of its own.
  mesh.element_sets["first_half"] = {};
  for (Index e = 0; e < mesh.element_count() / 2; ++e) mesh.element_sets["first_half"].push_back(e);
  mesh.element_sets["every_third"] = {};
  for (Index e = 0; e < mesh.element_count(); e += 3) mesh.element_sets["every_third"].push_back(e);
  mesh.node_sets["a_few_nodes"] = {0, 5, 7};
  // The element sets' node sets, as read_msh derives them from the groups.
  for (const std::string name : {"first_half", "every_third"}) {
    std::vector<Index> nodes;
    for (Index e : mesh.element_sets[name])
      for (Index v : mesh.blocks[0].element(e)) nodes.push_back(v);
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    mesh.node_sets[name] = nodes;
  }
  write_msh(mesh, dir / "ascii.msh", MshEncoding::Ascii);
  write_msh(mesh, dir / "binary.msh", MshEncoding::Binary);
  testing::expect_same_mesh(read_msh(dir / "binary.msh"), mesh, 0.0);
  testing::expect_same_mesh(read_msh(dir / "ascii.msh"), mesh, 1e-15);
}

TEST(WriteMsh, HexahedralMeshRoundTrips) {
  TempDir dir;
  write_text(dir / "box.geo", box_geo);
  MeshOptions options;
  options.element_size_m = 0.25;
  options.order = 2;
  options.family = ElementFamily::Hexahedra;
  const auto mesh = mesh_geometry(dir / "box.geo", options);
  ASSERT_EQ(mesh.blocks.size(), 1u);
  ASSERT_EQ(mesh.blocks[0].type, fem::ElementType::Hex20);
  // HEX20 mid-edge nodes per mesh.hpp, at the midpoints of their straight
  // edges (1e-12 m); the trilinear corner hexahedra fill the box exactly.
  const int pairs[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                            {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
  double volume = 0;
  for (Index e = 0; e < mesh.blocks[0].size(); ++e) {
    const auto element = mesh.blocks[0].element(e);
    for (int m = 0; m < 12; ++m) {
      const Eigen::Vector3d midpoint =
          (testing::node(mesh, element[pairs[m][0]]) + testing::node(mesh, element[pairs[m][1]])) / 2;
      EXPECT_LE((testing::node(mesh, element[8 + m]) - midpoint).norm(), 1e-12);
    }
    const double v = testing::hex8_volume(mesh, element);
    EXPECT_GT(v, 0.0);
    volume += v;
  }
  EXPECT_NEAR(volume, 1.0 * 0.5 * 0.25, 1e-12);
  ASSERT_EQ(mesh.face_set("left").size(), 1u);
  EXPECT_EQ(mesh.face_set("left")[0].type, fem::FaceType::Quad8);
  for (Index f = 0; f < mesh.face_set("left")[0].size(); ++f)
    EXPECT_LT(testing::face_normal(mesh, mesh.face_set("left")[0].face(f)).x(), 0.0);
  write_msh(mesh, dir / "hex.msh", MshEncoding::Binary);
  testing::expect_same_mesh(read_msh(dir / "hex.msh"), mesh, 0.0);
}

TEST(ReadMsh, BadFilesThrowErrorNamingTheFile) {
  TempDir dir;
  expect_error_naming(dir / "missing.msh", "no such");
  write_text(dir / "empty.msh", "");
  expect_error_naming(dir / "empty.msh", "empty");
  write_text(dir / "garbage.msh", "this is not a mesh\n\x01\x02\x03 at all\n");
  expect_error_naming(dir / "garbage.msh");
  write_text(dir / "garbage_header.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\nnonsense\n$EndNodes\n");
  expect_error_naming(dir / "garbage_header.msh");

  write_text(dir / "box.geo", box_geo);
  gmsh_mesh_and_write(dir / "box.geo", 3, 1, {{dir / "ascii.msh", false}, {dir / "binary.msh", true}});
  for (const std::string name : {"ascii", "binary"}) {
    std::ifstream in(dir / (name + ".msh"), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (double fraction : {0.1, 0.5, 0.9}) {
      const auto cut = dir / fmt::format("{}_cut_{}.msh", name, int(fraction * 100));
      write_text(cut, bytes.substr(0, std::size_t(double(bytes.size()) * fraction)));
      expect_error_naming(cut);
    }
    // Cut just before the closing "$EndElements": Gmsh itself reads this.
    const auto cut = dir / (name + "_cut_end.msh");
    write_text(cut, bytes.substr(0, bytes.rfind("$EndElements") - 2));
    expect_error_naming(cut, "truncated");
  }
}

// Overwrites the 8-byte size_t at `offset` of a binary .msh.
void poke_size_t(std::string& bytes, std::size_t offset, std::uint64_t value) {
  std::memcpy(bytes.data() + offset, &value, sizeof value);
}

TEST(ReadMsh, CorruptCountsAndTagsAreRejectedBeforeGmshReadsThem) {
  // Gmsh 4.8 trusts the file's counts and tags (fuzz findings: a SEGV for an
  // element naming a missing node, a 2e18-byte allocation for a huge count);
  // read_msh's structural check of MSH 4.1 must reject both kinds, naming
  // the file and the section, in ASCII and binary.
  TempDir dir;
  write_text(dir / "box.geo", box_geo);
  gmsh_mesh_and_write(dir / "box.geo", 3, 1, {{dir / "ascii.msh", false}, {dir / "binary.msh", true}});
  const auto bytes_of = [&](const std::string& name) {
    std::ifstream in(dir / name, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  EXPECT_NO_THROW(read_msh(dir / "ascii.msh"));
  EXPECT_NO_THROW(read_msh(dir / "binary.msh"));

  // Binary: the first node of the first element -> a tag the file lacks.
  std::string binary = bytes_of("binary.msh");
  const std::size_t elements = binary.find("$Elements\n") + std::strlen("$Elements\n");
  std::string bad = binary;
  poke_size_t(bad, elements + 4 * 8 + 3 * 4 + 8 + 8, 999999);
  write_text(dir / "missing_node.msh", bad);
  expect_error_naming(dir / "missing_node.msh", "$Elements: element");
  expect_error_naming(dir / "missing_node.msh", "refers to node 999999, which the file does not hold");
  // Binary: the number of nodes -> 2^60.
  bad = binary;
  poke_size_t(bad, binary.find("$Nodes\n") + std::strlen("$Nodes\n") + 8, std::uint64_t(1) << 60);
  write_text(dir / "huge_count.msh", bad);
  expect_error_naming(dir / "huge_count.msh", "$Nodes: the number of nodes = 1152921504606846976 is more than");

  // ASCII: an element type kinetofem does not know; a node tag given twice.
  std::string ascii = bytes_of("ascii.msh");
  const std::size_t block = ascii.find('\n', ascii.find("$Elements\n") + 10) + 1;  // first block header
  const std::size_t type_end = ascii.find(' ', ascii.find(' ', block) + 1);
  const std::size_t type_start = ascii.find(' ', type_end + 1);
  bad = ascii.substr(0, type_end) + " 99" + ascii.substr(type_start);
  write_text(dir / "bad_type.msh", bad);
  expect_error_naming(dir / "bad_type.msh", "element type 99, which kinetofem does not read");
  const std::size_t nodes = ascii.find("$Nodes\n");
  const std::size_t first_tag = ascii.find('\n', ascii.find('\n', nodes + 7) + 1) + 1;
  const std::size_t first_tag_end = ascii.find('\n', first_tag);
  const std::size_t second_tag_end = ascii.find('\n', first_tag_end + 1);
  // Only when the first block holds two nodes (tags on consecutive lines).
  ASSERT_EQ(ascii.substr(first_tag, first_tag_end - first_tag).find(' '), std::string::npos);
  bad = ascii.substr(0, first_tag_end + 1) + ascii.substr(first_tag, first_tag_end - first_tag) +
        ascii.substr(second_tag_end);
  write_text(dir / "twice.msh", bad);
  expect_error_naming(dir / "twice.msh", "$Nodes:");

  // The fuzz findings themselves (tests/data/meshes/fuzz_findings/).
  expect_error_naming("tests/data/meshes/fuzz_findings/gmsh_segv_element_names_missing_node.msh");
  expect_error_naming("tests/data/meshes/fuzz_findings/gmsh_huge_entity_count.msh");
  expect_error_naming("tests/data/meshes/fuzz_findings/gmsh_segv_msh22.msh", "kinetofem reads MSH 4.1 only");
  // Node tags up to 7.8e11 for 8 nodes: the check must not allocate by the tag range.
  expect_error_naming("tests/data/meshes/fuzz_findings/sparse_node_tag_range.msh");
}

TEST(ReadMsh, PrismsAndSurfaceOnlyMeshesAreRejected) {
  TempDir dir;
  write_text(dir / "prisms.geo", R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
Extrude {0, 0, 0.5} { Surface{1}; Layers{2}; Recombine; }
Physical Volume("slab") = {1};
)");
  gmsh_mesh_and_write(dir / "prisms.geo", 3, 1, {{dir / "prisms.msh", false}});
  expect_error_naming(dir / "prisms.msh", "Prism");

  write_text(dir / "plate.geo", R"(SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 1, 1};
Physical Surface("plate") = {1};
)");
  gmsh_mesh_and_write(dir / "plate.geo", 2, 1, {{dir / "plate.msh", false}});
  expect_error_naming(dir / "plate.msh", "no volume elements");
}

TEST(GmshSession, OnlyOneAtATimeAndGmshErrorsBecomeErrors) {
  GmshSession session;
  EXPECT_THROW(GmshSession second, Error);
  try {
    session.call("context.geo", "gmsh::model::getBoundingBox", [] {
      double x0, y0, z0, x1, y1, z1;
      gmsh::model::getBoundingBox(3, 12345, x0, y0, z0, x1, y1, z1);
    });
    ADD_FAILURE() << "no Error";
  } catch (const Error& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("context.geo"), std::string::npos) << message;
    EXPECT_NE(message.find("getBoundingBox"), std::string::npos) << message;
  }
  // The session still works after an error.
  EXPECT_NO_THROW(session.call("context.geo", "gmsh::clear", [] { gmsh::clear(); }));
}

}  // namespace
}  // namespace kinetofem::meshes
