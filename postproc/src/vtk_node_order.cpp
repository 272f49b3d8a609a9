#include "kinetofem/postproc/vtk_node_order.hpp"

namespace kinetofem::post {

std::span<const int> vtk_from_gmsh(fem::ElementType type) {
  return fem::element_facts(type).vtk_from_gmsh;
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
  return fem::element_facts(type).xdmf_topology;
}

int xdmf_mixed_code(fem::ElementType type) { return fem::element_facts(type).xdmf_mixed_code; }

}  // namespace kinetofem::post
