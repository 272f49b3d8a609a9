// The stress picture draws the boundary of every element type: each face is
// split into flat triangles by its face type (TRI3, TRI6, QUAD4, QUAD8), so a
// mesh of any type gives a picture with a coloured surface and its peak.
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/postproc/png_plots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/results_writer.hpp"
#include "png_inspect.hpp"
#include "post_test_results.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::inspect;
using testing::PngStats;

// The corners of the single TET10, as a TET4.
fem::Mesh single_tet4() {
  const fem::Mesh tet10 = testing::single_tet10();
  fem::Mesh mesh;
  mesh.nodes = tet10.nodes.topRows(4);
  fem::ElementBlock block;
  block.type = fem::ElementType::Tet4;
  block.connectivity = {0, 1, 2, 3};
  mesh.blocks.push_back(block);
  return mesh;
}

// A static results file of one body: von Mises growing along x + y + z, a small displacement along x.
std::filesystem::path write_static(const std::filesystem::path& dir, const fem::Mesh& mesh) {
  const std::filesystem::path path = dir / "static.h5";
  Provenance provenance;
  provenance.case_path = "element_types";
  ResultsWriter writer(path, provenance);
  BodyWriter& body = writer.add_body("part", mesh);
  const fem::Index n = mesh.node_count();
  FieldMatrix vm(n, 1), u(n, 3);
  for (fem::Index i = 0; i < n; ++i) {
    vm(i, 0) = 10e6 * (1.0 + 10.0 * mesh.nodes.row(i).sum());
    u.row(i) << 1e-6, 0.0, 0.0;
  }
  body.write_static("von_mises", "Pa", vm);
  body.write_static("displacement", "m", u, kVectorComponents);
  writer.commit();
  return path;
}

struct ElementCase {
  std::string name;
  fem::Mesh mesh;
};

TEST(PngElementTypes, StressPictureOfEveryElementType) {
  const ElementCase cases[] = {
      {"TET4", single_tet4()},
      {"TET10", testing::single_tet10()},
      {"HEX8", testing::hex_grid(3, 2, 2, 0.02)},
      {"HEX20", testing::single_hex20()},
  };
  for (const ElementCase& c : cases) {
    testing::TemporaryDirectory dir;
    const ResultsFile results = ResultsFile::open(write_static(dir.path(), c.mesh));
    StressPictureOptions options;
    options.width_px = 600;
    options.height_px = 400;
    const StressPictureInfo info = write_stress_picture(results, dir / "vm.png", options);
    EXPECT_EQ(info.peak_body, "part") << c.name;
    const PngStats s = inspect(dir / "vm.png");
    EXPECT_EQ(s.width, 600) << c.name;
    EXPECT_EQ(s.height, 400) << c.name;
    EXPECT_GT(s.colours, 100u) << c.name;  // the shaded, coloured surface, not only text and axes
    EXPECT_GT(s.ink, 0.05) << c.name;
  }
}

}  // namespace
}  // namespace kinetofem::post
