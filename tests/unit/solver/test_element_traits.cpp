// Unit tests of the element table (element_traits.hpp): every element and
// face type has facts, and the facts agree with each other and with the
// element library's reference geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <string>

#include <Eigen/Geometry>

#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/element_traits.hpp"

namespace kinetofem::fem {
namespace {

bool is_permutation_of_nodes(std::span<const int> order, int nodes) {
  std::vector<int> sorted(order.begin(), order.end());
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> expected(static_cast<std::size_t>(nodes));
  std::iota(expected.begin(), expected.end(), 0);
  return sorted == expected;
}

TEST(ElementTraits, EveryTypeHasConsistentCounts) {
  for (ElementType type : all_element_types) {
    const ElementFacts& f = element_facts(type);
    SCOPED_TRACE(f.name);
    EXPECT_EQ(f.dimension, 3);
    EXPECT_EQ(int(f.edges.size()), f.nodes - f.corners);
    EXPECT_EQ(f.corners, f.shape == ElementShape::Tetrahedron ? 4 : 8);
    EXPECT_EQ(f.face_count, f.shape == ElementShape::Tetrahedron ? 4 : 6);
    const FaceFacts& face = face_facts(f.face_type);
    EXPECT_EQ(int(f.face_nodes.size()), f.face_count * face.nodes);
    // A linear element has linear faces, a quadratic one quadratic faces.
    EXPECT_EQ(f.nodes == f.corners, face.nodes == face.corners);
  }
  for (FaceType type : all_face_types) {
    const FaceFacts& f = face_facts(type);
    SCOPED_TRACE(f.name);
    EXPECT_TRUE(f.corners == 3 || f.corners == 4);
    EXPECT_TRUE(f.nodes == f.corners || f.nodes == 2 * f.corners);
  }
}

TEST(ElementTraits, FacesAreClosedOutwardAndUseTheEdges) {
  for (ElementType type : all_element_types) {
    const ElementFacts& f = element_facts(type);
    SCOPED_TRACE(f.name);
    const Eigen::MatrixXd X = reference_nodes(type);
    const Eigen::Vector3d centre = X.topRows(f.corners).colwise().mean().transpose();
    const int face_corners = face_facts(f.face_type).corners;
    std::multiset<std::pair<int, int>> edges;  // each corner edge lies on exactly two faces
    for (int k = 0; k < f.face_count; ++k) {
      const auto nodes = f.face(k);
      for (int n : nodes) {
        EXPECT_GE(n, 0);
        EXPECT_LT(n, f.nodes);
      }
      for (int c = 0; c < face_corners; ++c) EXPECT_LT(nodes[size_t(c)], f.corners);
      // Outward: the corners' normal (Newell) points away from the centre.
      Eigen::Vector3d normal = Eigen::Vector3d::Zero(), mid = Eigen::Vector3d::Zero();
      for (int c = 0; c < face_corners; ++c) {
        const Eigen::Vector3d a = X.row(nodes[size_t(c)]).transpose();
        const Eigen::Vector3d b = X.row(nodes[size_t((c + 1) % face_corners)]).transpose();
        normal += a.cross(b);
        mid += a / face_corners;
      }
      EXPECT_GT(normal.dot(mid - centre), 0.0) << "face " << k;
      for (int c = 0; c < face_corners; ++c) {
        const int a = nodes[size_t(c)], b = nodes[size_t((c + 1) % face_corners)];
        edges.insert({std::min(a, b), std::max(a, b)});
        // A quadratic face's mid-edge node c is the element's node on that edge.
        if (int(nodes.size()) > face_corners) {
          const auto ends = edge_corners(type, nodes[size_t(face_corners + c)]);
          EXPECT_EQ(std::min(ends[0], ends[1]), std::min(a, b));
          EXPECT_EQ(std::max(ends[0], ends[1]), std::max(a, b));
        }
      }
    }
    for (const auto& e : edges) EXPECT_EQ(edges.count(e), 2u);
  }
}

TEST(ElementTraits, NodeOrdersArePermutations) {
  for (ElementType type : all_element_types) {
    const ElementFacts& f = element_facts(type);
    SCOPED_TRACE(f.name);
    EXPECT_EQ(int(f.vtk_from_gmsh.size()), f.nodes);
    EXPECT_EQ(int(f.calculix_from_gmsh.size()), f.nodes);
    EXPECT_TRUE(is_permutation_of_nodes(f.vtk_from_gmsh, f.nodes));
    EXPECT_TRUE(is_permutation_of_nodes(f.calculix_from_gmsh, f.nodes));
    // Corners keep their place in every format.
    for (int c = 0; c < f.corners; ++c) {
      EXPECT_EQ(f.vtk_from_gmsh[size_t(c)], c);
      EXPECT_EQ(f.calculix_from_gmsh[size_t(c)], c);
    }
  }
}

TEST(ElementTraits, CodesAndNamesAreUniqueAndRoundTrip) {
  std::set<int> gmsh, xdmf;
  std::set<std::string> names, calculix, topology;
  for (ElementType type : all_element_types) {
    const ElementFacts& f = element_facts(type);
    EXPECT_TRUE(gmsh.insert(f.gmsh_code).second) << f.name;
    EXPECT_TRUE(xdmf.insert(f.xdmf_mixed_code).second) << f.name;
    EXPECT_TRUE(names.insert(f.name).second);
    EXPECT_TRUE(calculix.insert(f.calculix_name).second);
    EXPECT_TRUE(topology.insert(f.xdmf_topology).second);
    // The Gmsh code finds the type back.
    const auto back = std::find_if(all_element_types.begin(), all_element_types.end(),
                                   [&](ElementType t) { return element_facts(t).gmsh_code == f.gmsh_code; });
    EXPECT_EQ(*back, type);
  }
  for (FaceType type : all_face_types) {
    const FaceFacts& f = face_facts(type);
    EXPECT_TRUE(gmsh.insert(f.gmsh_code).second) << f.name;  // distinct from the volume codes too
    EXPECT_TRUE(names.insert(f.name).second);
  }
}

TEST(ElementTraits, TableIsUsableAtCompileTime) {
  static_assert(element_facts(ElementType::Tet10).nodes == 10);
  static_assert(element_facts(ElementType::Hex20).face(5).size() == 8);
  static_assert(face_facts(FaceType::Quad8).corners == 4);
  SUCCEED();
}

}  // namespace
}  // namespace kinetofem::fem
