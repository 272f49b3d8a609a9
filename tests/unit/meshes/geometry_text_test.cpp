// Geometry compiled into the program (geometry_text.hpp): the embedded texts
// are the source files byte for byte, meshing a text writes it to a
// temporary file that is removed afterwards (also on error), and the mesh
// cache key of a text is that of the file itself.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geometry_text.hpp"
#include "kinetofem/verification/verification_geometry.hpp"
#include "mesh_test_helpers.hpp"
#include "kinetofem/testing/scoped_tmpdir.hpp"

namespace kinetofem::meshes {
namespace {

namespace fs = std::filesystem;

// The tests run from the source root (kinetofem_test_dir).
std::string source_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  EXPECT_TRUE(bool(in)) << file;
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t entries(const fs::path& dir) {
  return std::size_t(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

using kinetofem::testing::ScopedTmpdir;

MeshOptions coarse() {
  MeshOptions options;
  options.element_size_m = 0.02;
  return options;
}

TEST(GeometryText, EmbeddedTextsAreTheSourceFiles) {
  EXPECT_EQ(lever_geometry_text(), source_text("meshes/geometry/lever.geo"));
  EXPECT_EQ(arm_geometry_text(), source_text("meshes/geometry/arm.geo"));
  EXPECT_EQ(verification::bar_geometry_text(), source_text("verification/geometry/bar.geo"));
  EXPECT_EQ(verification::beam_link_geometry_text(), source_text("verification/geometry/beam_link.geo"));
}

TEST(GeometryText, TemporaryFileIsRemovedAfterMeshingAndAfterAnError) {
  const testing::TempDir temp;
  const fs::path tmp = temp / "tmp";
  fs::create_directories(tmp);
  const ScopedTmpdir tmpdir(tmp);
  const fem::Mesh mesh = mesh_geometry_text("lever.geo", lever_geometry_text(), coarse());
  EXPECT_GT(mesh.element_count(), 0);
  EXPECT_EQ(entries(tmp), 0u) << "temporary geometry left in " << tmp;
  try {
    mesh_geometry_text("broken.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0;\n", coarse());
    ADD_FAILURE() << "a broken geometry text was meshed";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("broken.geo"), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(tmp), 0u) << "temporary geometry left in " << tmp;
  EXPECT_THROW(mesh_geometry_text("sub/lever.geo", lever_geometry_text(), coarse()), Error);
}

TEST(GeometryText, CacheKeyIsThatOfTheFile) {
  const testing::TempDir temp;
  MeshOptions options = coarse();
  options.cache_dir = temp / "cache";
  const fem::Mesh from_text = mesh_geometry_text("lever.geo", lever_geometry_text(), options);
  ASSERT_EQ(entries(options.cache_dir), 1u);
  const fs::path entry = fs::directory_iterator(options.cache_dir)->path();
  EXPECT_EQ(entry.filename().string().rfind("lever_", 0), 0u) << entry;
  // The source file with the same text hits the same cache entry.
  const fem::Mesh from_file = mesh_geometry("meshes/geometry/lever.geo", options);
  EXPECT_EQ(entries(options.cache_dir), 1u);
  EXPECT_EQ(from_file.node_count(), from_text.node_count());
  EXPECT_EQ((from_file.nodes - from_text.nodes).cwiseAbs().maxCoeff(), 0.0);
}

}  // namespace
}  // namespace kinetofem::meshes
