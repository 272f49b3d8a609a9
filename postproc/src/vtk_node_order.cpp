#include "kinetofem/postproc/vtk_node_order.hpp"

namespace kinetofem::post {

namespace {
constexpr int kTet4[] = {0, 1, 2, 3};
constexpr int kTet10[] = {0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
constexpr int kHex8[] = {0, 1, 2, 3, 4, 5, 6, 7};
// VTK edge k (01,12,23,30,45,56,67,74,04,15,26,37) looked up in Gmsh's edge list
// (01,03,04,12,15,23,26,37,45,47,56,67 -> nodes 8..19).
constexpr int kHex20[] = {0, 1, 2,  3,  4,  5,  6,  7,  8,  11,
                          13, 9, 16, 18, 19, 17, 10, 12, 14, 15};
}  // namespace

std::span<const int> vtk_from_gmsh(fem::ElementType type) {
  switch (type) {
    case fem::ElementType::Tet4: return kTet4;
    case fem::ElementType::Tet10: return kTet10;
    case fem::ElementType::Hex8: return kHex8;
    case fem::ElementType::Hex20: return kHex20;
  }
  return {};
}

std::vector<fem::Index> vtk_connectivity(const fem::ElementBlock& block) {
  const auto order = vtk_from_gmsh(block.type);
  const size_t n = order.size();
  std::vector<fem::Index> out(block.connectivity.size());
  for (size_t e = 0; e * n < block.connectivity.size(); ++e)
    for (size_t k = 0; k < n; ++k) out[e * n + k] = block.connectivity[e * n + size_t(order[k])];
  return out;
}

const char* xdmf_topology_name(fem::ElementType type) {
  switch (type) {
    case fem::ElementType::Tet4: return "Tetrahedron";
    case fem::ElementType::Tet10: return "Tetrahedron_10";
    case fem::ElementType::Hex8: return "Hexahedron";
    case fem::ElementType::Hex20: return "Hexahedron_20";
  }
  return "?";
}

int xdmf_mixed_code(fem::ElementType type) {
  // XdmfTopologyType ids: XDMF_TET 0x6, XDMF_HEX 0x9, XDMF_TET_10 0x26, XDMF_HEX_20 0x30.
  switch (type) {
    case fem::ElementType::Tet4: return 0x6;
    case fem::ElementType::Tet10: return 0x26;
    case fem::ElementType::Hex8: return 0x9;
    case fem::ElementType::Hex20: return 0x30;
  }
  return 0;
}

}  // namespace kinetofem::post
