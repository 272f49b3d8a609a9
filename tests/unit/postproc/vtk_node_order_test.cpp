// Gmsh -> VTK/XDMF node order of quadratic elements.
//
// Reference: VTK's cell definitions (vtkQuadraticTetra, vtkQuadraticHexahedron):
// a VTK mid-edge node lies at the midpoint of its VTK edge, listed below
// independently of the conversion table under test. The elements come from
// Gmsh's definitions (postproc_test_meshes.hpp), so a node that lands at its
// VTK edge's midpoint proves the conversion right.
#include <gtest/gtest.h>

#include "kinetofem/postproc/vtk_node_order.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

constexpr std::pair<int, int> kVtkTet10Edges[] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
constexpr std::pair<int, int> kVtkHex20Edges[] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                                  {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};

// Max distance (m) of VTK mid-edge node k from the midpoint of VTK edge k.
template <size_t N>
double worst_midpoint_error(const fem::Mesh& mesh, const std::vector<fem::Index>& vtk, int corners,
                            const std::pair<int, int> (&edges)[N]) {
  double worst = 0.0;
  for (size_t k = 0; k < N; ++k) {
    const auto mid = mesh.nodes.row(vtk[size_t(corners) + k]);
    const auto expected =
        0.5 * (mesh.nodes.row(vtk[size_t(edges[k].first)]) + mesh.nodes.row(vtk[size_t(edges[k].second)]));
    worst = std::max(worst, (mid - expected).norm());
  }
  return worst;
}

TEST(VtkNodeOrder, Tet10MidEdgeNodesLieAtTheirVtkEdgeMidpoints) {
  const fem::Mesh mesh = testing::single_tet10();
  const auto vtk = vtk_connectivity(mesh.blocks.front());
  ASSERT_EQ(vtk.size(), 10u);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(vtk[size_t(c)], c) << "corner " << c << " must not move";
  // Midpoints are computed the same way in the mesh and here: exact up to rounding.
  EXPECT_LT(worst_midpoint_error(mesh, vtk, 4, kVtkTet10Edges), 1e-15);
  // Without the conversion, Gmsh order would put nodes 8 and 9 on the wrong edges.
  const std::vector<fem::Index> gmsh(mesh.blocks.front().connectivity);
  EXPECT_GT(worst_midpoint_error(mesh, gmsh, 4, kVtkTet10Edges), 1e-3);
}

TEST(VtkNodeOrder, Hex20MidEdgeNodesLieAtTheirVtkEdgeMidpoints) {
  const fem::Mesh mesh = testing::single_hex20();
  const auto vtk = vtk_connectivity(mesh.blocks.front());
  ASSERT_EQ(vtk.size(), 20u);
  for (int c = 0; c < 8; ++c) EXPECT_EQ(vtk[size_t(c)], c) << "corner " << c << " must not move";
  EXPECT_LT(worst_midpoint_error(mesh, vtk, 8, kVtkHex20Edges), 1e-15);
  const std::vector<fem::Index> gmsh(mesh.blocks.front().connectivity);
  EXPECT_GT(worst_midpoint_error(mesh, gmsh, 8, kVtkHex20Edges), 1e-3);
}

TEST(VtkNodeOrder, ConversionIsAPermutationForEveryType) {
  for (auto type : {fem::ElementType::Tet4, fem::ElementType::Tet10, fem::ElementType::Hex8,
                    fem::ElementType::Hex20}) {
    const auto order = vtk_from_gmsh(type);
    ASSERT_EQ(int(order.size()), fem::nodes_per_element(type)) << fem::name_of(type);
    std::vector<int> sorted(order.begin(), order.end());
    std::sort(sorted.begin(), sorted.end());
    for (size_t k = 0; k < sorted.size(); ++k) EXPECT_EQ(sorted[k], int(k)) << fem::name_of(type);
  }
}

TEST(VtkNodeOrder, XdmfNamesAndMixedCodes) {
  EXPECT_STREQ(xdmf_topology_name(fem::ElementType::Tet4), "Tetrahedron");
  EXPECT_STREQ(xdmf_topology_name(fem::ElementType::Tet10), "Tetrahedron_10");
  EXPECT_STREQ(xdmf_topology_name(fem::ElementType::Hex8), "Hexahedron");
  EXPECT_STREQ(xdmf_topology_name(fem::ElementType::Hex20), "Hexahedron_20");
  // XDMF's cell-type ids (XdmfTopologyType): TET 0x6, TET_10 0x26, HEX 0x9, HEX_20 0x30.
  EXPECT_EQ(xdmf_mixed_code(fem::ElementType::Tet4), 6);
  EXPECT_EQ(xdmf_mixed_code(fem::ElementType::Tet10), 38);
  EXPECT_EQ(xdmf_mixed_code(fem::ElementType::Hex8), 9);
  EXPECT_EQ(xdmf_mixed_code(fem::ElementType::Hex20), 48);
}

}  // namespace
}  // namespace kinetofem::post
