// mesh_lever: the lever of SPEC §1 meshed with TET10 at a coarse size: valid
// elements, the analytic volume, bore sets on their cylinders, parameter
// overrides reaching lever.geo.
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;

MeshOptions coarse() {
  MeshOptions options;
  options.element_size_m = 0.02;  // coarse: about 0.3 s per mesh
  options.order = 2;
  return options;
}

double mesh_volume(const fem::Mesh& mesh) {
  double volume = 0;
  for (const auto& block : mesh.blocks)
    for (Index e = 0; e < block.size(); ++e) volume += testing::tet10_volume(mesh, block.element(e));
  return volume;
}

// Every node of the bore set lies on the bore cylinder about (0, y_axis),
// within |z| <= L/2, and every face normal points into the hole (out of the
// material, towards the axis).
void expect_bore(const fem::Mesh& mesh, const std::string& name, double y_axis,
                 const LeverDimensions& d) {
  const auto& nodes = mesh.node_set(name);
  ASSERT_FALSE(nodes.empty()) << name;
  for (Index v : nodes) {
    const double radius = std::hypot(mesh.nodes(v, 0), mesh.nodes(v, 1) - y_axis);
    // Nodes are placed on the OpenCASCADE surface: 1e-7 m is its tolerance.
    EXPECT_NEAR(radius, d.bore_diameter_m / 2, 1e-7) << name << " node " << v;
    EXPECT_LE(std::abs(mesh.nodes(v, 2)), d.boss_length_m / 2 + 1e-7);
  }
  const auto& faces = mesh.face_set(name);
  ASSERT_EQ(faces.size(), 1u);
  EXPECT_EQ(faces[0].type, fem::FaceType::Tri6);
  for (Index f = 0; f < faces[0].size(); ++f) {
    const auto face = faces[0].face(f);
    Eigen::Vector3d to_axis = -testing::face_centroid(mesh, face, 3);
    to_axis.y() += y_axis;
    to_axis.z() = 0;
    EXPECT_GT(testing::face_normal(mesh, face).dot(to_axis), 0.0) << name << " face " << f;
  }
}

TEST(MeshLever, Order2MeshIsValidAndHasTheAnalyticVolume) {
  const LeverDimensions d;
  const auto mesh = mesh_lever(d, coarse());
  ASSERT_EQ(mesh.blocks.size(), 1u);
  ASSERT_EQ(mesh.blocks[0].type, fem::ElementType::Tet10);
  EXPECT_EQ(mesh.element_sets.at("lever").size(), std::size_t(mesh.element_count()));

  // det J > 0 at the corners, the mid-edge points and the centroid of every TET10.
  const double points[][3] = {{0, 0, 0},     {1, 0, 0},     {0, 1, 0},       {0, 0, 1},
                              {0.5, 0, 0},   {0.5, 0.5, 0}, {0, 0.5, 0},     {0, 0, 0.5},
                              {0, 0.5, 0.5}, {0.5, 0, 0.5}, {0.25, 0.25, 0.25}};
  for (Index e = 0; e < mesh.blocks[0].size(); ++e)
    for (const auto& p : points)
      ASSERT_GT(testing::tet10_det_j(mesh, mesh.blocks[0].element(e), p[0], p[1], p[2]), 0.0)
          << "element " << e;

  // Reference: LeverDimensions::volume_m3 (exact solid). The quadratic mesh
  // differs only where it approximates the curved boss and bore surfaces: a
  // quadratic arc over 1/16 of a circle (elements_per_circle = 16) deviates
  // radially by at most 4.6e-5 R, i.e. 2.1e-6 m for R = 45 mm, over curved
  // surfaces of about 0.04 m^2: < 8.5e-8 m^3 = 6.3e-5 of the volume. Hence 1e-4.
  EXPECT_NEAR(mesh_volume(mesh) / d.volume_m3(), 1.0, 1e-4);

  expect_bore(mesh, "bore_A0", 0.0, d);
  expect_bore(mesh, "bore_A", d.length_m, d);
  for (const std::string name : {"boss_ends_A0", "boss_ends_A"}) {
    ASSERT_FALSE(mesh.node_set(name).empty()) << name;
    for (Index v : mesh.node_set(name))
      EXPECT_NEAR(std::abs(mesh.nodes(v, 2)), d.boss_length_m / 2, 1e-7) << name;
  }
}

TEST(MeshLever, DimensionsReachTheGeometryFile) {
  LeverDimensions d;
  d.length_m = 0.65;
  d.thickness_m = 0.03;
  d.bore_diameter_m = 0.05;
  d.boss_diameter_m = 0.1;
  const auto mesh = mesh_lever(d, coarse());
  // Extent along the lever: -D/2 .. a + D/2 (boss circles; nodes lie on them
  // only up to the chord of the coarse mesh, so 2 mm).
  EXPECT_NEAR(mesh.nodes.col(1).minCoeff(), -d.boss_diameter_m / 2, 2e-3);
  EXPECT_NEAR(mesh.nodes.col(1).maxCoeff(), d.length_m + d.boss_diameter_m / 2, 2e-3);
  EXPECT_NEAR(mesh_volume(mesh) / d.volume_m3(), 1.0, 1e-4);  // as above
  expect_bore(mesh, "bore_A", d.length_m, d);
}

TEST(MeshLever, VolumeFormulaOfTheDefaultLever) {
  // V = w a t + 2 pi R^2 L - t S - 2 pi r^2 L with the README's numbers:
  // 0.08*0.5*0.025 + 2 pi 0.045^2 0.05 - 0.025 S - 2 pi 0.02^2 0.05,
  // S = 2 (0.04 sqrt(0.045^2 - 0.04^2) + 0.045^2 asin(0.04/0.045)).
  const double pi = std::acos(-1.0);
  const double s = 2 * (0.04 * std::sqrt(0.045 * 0.045 - 0.04 * 0.04) +
                        0.045 * 0.045 * std::asin(0.04 / 0.045));
  const double v = 0.08 * 0.5 * 0.025 + 2 * pi * 0.045 * 0.045 * 0.05 - 0.025 * s -
                   2 * pi * 0.02 * 0.02 * 0.05;
  EXPECT_NEAR(LeverDimensions{}.volume_m3(), v, 1e-15);
}

TEST(MeshLever, InvalidDimensionsAndOptionsThrow) {
  LeverDimensions d;
  d.bore_diameter_m = 0.085;  // wider than the plate
  EXPECT_THROW(mesh_lever(d, coarse()), Error);
  d = {};
  d.length_m = 0.05;  // bosses overlap
  EXPECT_THROW(mesh_lever(d, coarse()), Error);
  MeshOptions options = coarse();
  options.order = 3;
  EXPECT_THROW(mesh_lever({}, options), Error);
  options = coarse();
  options.element_size_m = -1;
  EXPECT_THROW(mesh_lever({}, options), Error);
}

TEST(MeshGeometry, MissingAndUnknownFilesThrowNamingTheFile) {
  try {
    mesh_geometry("/nonexistent/lever.geo", coarse());
    ADD_FAILURE();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("/nonexistent/lever.geo"), std::string::npos);
  }
  EXPECT_THROW(mesh_geometry("meshes/geometry/README.md", coarse()), Error);  // run from the source root
}

}  // namespace
}  // namespace kinetofem::meshes

namespace kinetofem::meshes {
namespace {

TEST(MeshCache, SecondMeshingOfTheSameGeometryIsReadFromTheCache) {
  const auto dir = std::filesystem::temp_directory_path() / "kinetofem_mesh_cache_test";
  std::filesystem::remove_all(dir);
  MeshOptions options;
  options.element_size_m = 0.02;
  options.cache_dir = dir;
  LeverDimensions d;
  const fem::Mesh first = mesh_lever(d, options);
  ASSERT_TRUE(std::filesystem::exists(dir)) << "no cache directory made";
  ASSERT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  const fem::Mesh second = mesh_lever(d, options);  // from the cache
  EXPECT_EQ(second.node_count(), first.node_count());
  EXPECT_EQ(second.element_count(), first.element_count());
  EXPECT_EQ((second.nodes - first.nodes).cwiseAbs().maxCoeff(), 0.0);  // binary .msh: exact
  EXPECT_EQ(second.face_set("bore_A").front().connectivity, first.face_set("bore_A").front().connectivity);
  // A changed dimension or size is a new entry.
  d.thickness_m = 0.03;
  mesh_lever(d, options);
  options.element_size_m = 0.025;
  mesh_lever(d, options);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 3);
  // A damaged entry is meshed again, not an error.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) std::ofstream(entry.path()) << "garbage";
  EXPECT_EQ(mesh_lever(d, options).element_count() > 0, true);
}

}  // namespace
}  // namespace kinetofem::meshes
