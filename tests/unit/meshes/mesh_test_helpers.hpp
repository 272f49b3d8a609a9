#pragma once
// Helpers for the meshes unit tests: temporary files, element volumes and
// Jacobians from the node ordering of solver/include/kinetofem/solver/mesh.hpp.
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>

#include <unistd.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes::testing {

// A fresh directory under the system temp dir, removed at scope exit.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::temp_directory_path() /
            ("kinetofem_meshes_" + std::string(info->test_suite_name()) + "_" + info->name() +
             "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

inline Eigen::Vector3d node(const fem::Mesh& mesh, fem::Index i) {
  return mesh.nodes.row(i).transpose();
}

// det J of a TET10 at barycentric point (L1, L2, L3) = (xi, eta, zeta);
// N corner i = Li (2 Li - 1), N mid(i,j) = 4 Li Lj with the Gmsh edge list.
inline double tet10_det_j(const fem::Mesh& mesh, std::span<const fem::Index> e, double xi,
                          double eta, double zeta) {
  const double l[4] = {1 - xi - eta - zeta, xi, eta, zeta};
  const Eigen::Vector3d dl[4] = {{-1, -1, -1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  static const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  for (int a = 0; a < 4; ++a) j += node(mesh, e[a]) * ((4 * l[a] - 1) * dl[a]).transpose();
  for (int m = 0; m < 6; ++m) {
    const int p = edges[m][0], q = edges[m][1];
    j += node(mesh, e[4 + m]) * (4 * (l[p] * dl[q] + l[q] * dl[p])).transpose();
  }
  return j.determinant();
}

// Volume of a TET10 by the degree-3 five-point rule (det J is cubic, so exact).
inline double tet10_volume(const fem::Mesh& mesh, std::span<const fem::Index> e) {
  const double a = 0.5, b = 1.0 / 6.0;
  double v = -0.8 * tet10_det_j(mesh, e, 0.25, 0.25, 0.25);
  v += 0.45 * (tet10_det_j(mesh, e, b, b, b) + tet10_det_j(mesh, e, a, b, b) +
               tet10_det_j(mesh, e, b, a, b) + tet10_det_j(mesh, e, b, b, a));
  return v / 6.0;
}

// Volume of the corner tetrahedron (signed: > 0 for Gmsh's positive ordering).
inline double corner_tet_volume(const fem::Mesh& mesh, std::span<const fem::Index> e) {
  const Eigen::Vector3d x0 = node(mesh, e[0]);
  return (node(mesh, e[1]) - x0).cross(node(mesh, e[2]) - x0).dot(node(mesh, e[3]) - x0) / 6.0;
}

// Volume of the trilinear hexahedron on the 8 corners (2x2x2 Gauss, exact).
inline double hex8_volume(const fem::Mesh& mesh, std::span<const fem::Index> e) {
  static const double s[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                 {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  const double g = 1 / std::sqrt(3.0);
  double v = 0;
  for (double xi : {-g, g})
    for (double eta : {-g, g})
      for (double zeta : {-g, g}) {
        Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
        for (int a = 0; a < 8; ++a) {
          const Eigen::Vector3d dn(s[a][0] * (1 + s[a][1] * eta) * (1 + s[a][2] * zeta) / 8,
                                   s[a][1] * (1 + s[a][0] * xi) * (1 + s[a][2] * zeta) / 8,
                                   s[a][2] * (1 + s[a][0] * xi) * (1 + s[a][1] * eta) / 8);
          j += node(mesh, e[a]) * dn.transpose();
        }
        v += j.determinant();
      }
  return v;
}

// Unnormalized normal of a face by the right-hand rule on its first three corners.
inline Eigen::Vector3d face_normal(const fem::Mesh& mesh, std::span<const fem::Index> f) {
  const Eigen::Vector3d x0 = node(mesh, f[0]);
  return (node(mesh, f[1]) - x0).cross(node(mesh, f[2]) - x0);
}

inline Eigen::Vector3d face_centroid(const fem::Mesh& mesh, std::span<const fem::Index> f,
                                     int corners) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = 0; k < corners; ++k) c += node(mesh, f[k]);
  return c / corners;
}

inline void expect_same_mesh(const fem::Mesh& a, const fem::Mesh& b, double coordinate_tol) {
  ASSERT_EQ(a.node_count(), b.node_count());
  EXPECT_LE((a.nodes - b.nodes).cwiseAbs().maxCoeff(), coordinate_tol);
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t k = 0; k < a.blocks.size(); ++k) {
    EXPECT_EQ(a.blocks[k].type, b.blocks[k].type);
    EXPECT_EQ(a.blocks[k].connectivity, b.blocks[k].connectivity);
  }
  EXPECT_EQ(a.node_sets, b.node_sets);
  EXPECT_EQ(a.element_sets, b.element_sets);
  ASSERT_EQ(a.face_sets.size(), b.face_sets.size());
  for (const auto& [name, blocks] : a.face_sets) {
    ASSERT_TRUE(b.face_sets.count(name)) << name;
    const auto& other = b.face_sets.at(name);
    ASSERT_EQ(blocks.size(), other.size()) << name;
    for (std::size_t k = 0; k < blocks.size(); ++k) {
      EXPECT_EQ(blocks[k].type, other[k].type) << name;
      EXPECT_EQ(blocks[k].connectivity, other[k].connectivity) << name;
    }
  }
}

}  // namespace kinetofem::meshes::testing
