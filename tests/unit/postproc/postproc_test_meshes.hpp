#pragma once
// Single quadratic elements for the results-file tests, built from the node
// definitions in solver/include/kinetofem/solver/mesh.hpp (Gmsh order): the
// corners are a distorted element, each mid-edge node lies exactly at the
// midpoint of its Gmsh edge. All midpoints are distinct, so a wrong reordering
// puts some node at the wrong place.
#include <array>
#include <filesystem>
#include <string>
#include <utility>

#include <unistd.h>

#include <gtest/gtest.h>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::post::testing {

// Gmsh's mid-edge nodes, in node order (mesh.hpp).
inline constexpr std::array<std::pair<int, int>, 6> kGmshTet10Edges = {
    {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};
inline constexpr std::array<std::pair<int, int>, 12> kGmshHex20Edges = {
    {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3}, {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}}};

inline fem::Mesh single_tet10() {
  const double corners[4][3] = {
      {0.00, 0.00, 0.00}, {0.10, 0.01, 0.00}, {0.02, 0.11, 0.005}, {0.01, 0.02, 0.09}};
  fem::Mesh mesh;
  mesh.nodes.resize(10, 3);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) mesh.nodes(i, c) = corners[i][c];
  for (int k = 0; k < 6; ++k)
    mesh.nodes.row(4 + k) =
        0.5 * (mesh.nodes.row(kGmshTet10Edges[k].first) + mesh.nodes.row(kGmshTet10Edges[k].second));
  fem::ElementBlock block;
  block.type = fem::ElementType::Tet10;
  for (int i = 0; i < 10; ++i) block.connectivity.push_back(i);
  mesh.blocks.push_back(block);
  mesh.node_sets["base"] = {0, 1, 2, 4, 5, 6};
  mesh.element_sets["all"] = {0};
  fem::FaceBlock face;
  face.type = fem::FaceType::Tri6;
  face.connectivity = {0, 2, 1, 6, 5, 4};
  mesh.face_sets["bottom"] = {face};
  return mesh;
}

inline fem::Mesh single_hex20() {
  // Reference corners (+-1)^3 in Gmsh order, mapped to a sheared, tapered brick (m).
  const int signs[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                           {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  fem::Mesh mesh;
  mesh.nodes.resize(20, 3);
  for (int i = 0; i < 8; ++i) {
    const double xi = signs[i][0], eta = signs[i][1], zeta = signs[i][2];
    mesh.nodes(i, 0) = 0.05 * (xi + 1) + 0.004 * eta * zeta + 0.001 * i;
    mesh.nodes(i, 1) = 0.03 * (eta + 1) * (1.0 - 0.1 * xi) + 0.002 * zeta;
    mesh.nodes(i, 2) = 0.02 * (zeta + 1) + 0.003 * xi * eta;
  }
  for (int k = 0; k < 12; ++k)
    mesh.nodes.row(8 + k) =
        0.5 * (mesh.nodes.row(kGmshHex20Edges[k].first) + mesh.nodes.row(kGmshHex20Edges[k].second));
  fem::ElementBlock block;
  block.type = fem::ElementType::Hex20;
  for (int i = 0; i < 20; ++i) block.connectivity.push_back(i);
  mesh.blocks.push_back(block);
  mesh.node_sets["clamp"] = {0, 3, 4, 7, 9, 10, 15, 17};
  mesh.element_sets["lever"] = {0};
  fem::FaceBlock face;
  face.type = fem::FaceType::Quad8;
  face.connectivity = {1, 2, 6, 5, 11, 14, 18, 12};
  mesh.face_sets["pin"] = {face};
  return mesh;
}

// A fresh directory for one test, removed afterwards.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("kinetofem_postproc_" + std::to_string(::getpid()) + "_" + info->test_suite_name() +
             "_" + info->name());
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TemporaryDirectory() {
    std::error_code ec;
    std::filesystem::permissions(path_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace kinetofem::post::testing
