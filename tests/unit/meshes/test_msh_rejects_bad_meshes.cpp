// read_msh rejects a mesh with an inverted element or a non-finite
// coordinate with an Error that names the file (hand-written 6-tet cubes of
// the robustness catalogue, tests/data/robustness/; the valid one reads).
// Tests run in the source root (ctest WORKING_DIRECTORY).
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/msh_io.hpp"

namespace kinetofem::meshes {
namespace {

std::string read_error(const std::string& file) {
  try {
    read_msh(file);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ReadMshBadMeshes, ValidCubeReads) {
  const fem::Mesh mesh = read_msh("tests/data/robustness/valid_cube/cube.msh");
  EXPECT_EQ(mesh.node_count(), 8);
  EXPECT_EQ(mesh.element_count(), 6);
  EXPECT_EQ(mesh.face_sets.count("fixed"), 1u);
  EXPECT_EQ(mesh.face_sets.count("loaded"), 1u);
}

TEST(ReadMshBadMeshes, InvertedTetIsAnErrorNamingTheFile) {
  const std::string file = "tests/data/robustness/50_msh_inverted_tet/cube.msh";
  const std::string what = read_error(file);
  EXPECT_EQ(what.rfind(file + ": element 2 (TET4) is inverted or degenerate", 0), 0u) << what;
}

TEST(ReadMshBadMeshes, NanCoordinateIsAnErrorNamingTheFile) {
  const std::string file = "tests/data/robustness/53_msh_nan_coordinate/cube.msh";
  const std::string what = read_error(file);
  EXPECT_EQ(what.rfind(file + ": mesh node 1 has a non-finite coordinate", 0), 0u) << what;
}

}  // namespace
}  // namespace kinetofem::meshes
