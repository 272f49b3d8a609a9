#include "kinetofem/solver/mesh.hpp"

#include <algorithm>
#include <cmath>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::Tet4: return 4;
    case ElementType::Tet10: return 10;
    case ElementType::Hex8: return 8;
    case ElementType::Hex20: return 20;
  }
  return 0;
}

int nodes_per_face(FaceType type) {
  switch (type) {
    case FaceType::Tri3: return 3;
    case FaceType::Tri6: return 6;
    case FaceType::Quad4: return 4;
    case FaceType::Quad8: return 8;
  }
  return 0;
}

const char* name_of(ElementType type) {
  switch (type) {
    case ElementType::Tet4: return "TET4";
    case ElementType::Tet10: return "TET10";
    case ElementType::Hex8: return "HEX8";
    case ElementType::Hex20: return "HEX20";
  }
  return "?";
}

const char* name_of(FaceType type) {
  switch (type) {
    case FaceType::Tri3: return "TRI3";
    case FaceType::Tri6: return "TRI6";
    case FaceType::Quad4: return "QUAD4";
    case FaceType::Quad8: return "QUAD8";
  }
  return "?";
}

int corner_nodes(ElementType type) {
  return (type == ElementType::Tet4 || type == ElementType::Tet10) ? 4 : 8;
}

FaceType face_type_of(ElementType type) {
  switch (type) {
    case ElementType::Tet4: return FaceType::Tri3;
    case ElementType::Tet10: return FaceType::Tri6;
    case ElementType::Hex8: return FaceType::Quad4;
    case ElementType::Hex20: return FaceType::Quad8;
  }
  return FaceType::Tri3;
}

int faces_per_element(ElementType type) { return corner_nodes(type) == 4 ? 4 : 6; }

std::vector<int> element_face_nodes(ElementType type, int face) {
  // Corners of each face, ordered counter-clockwise seen from outside
  // (outward normal by the right-hand rule), then the face's mid-edge nodes
  // in the order of its edges (c0-c1, c1-c2, ...).
  static const int tet_faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  static const int hex_faces[6][4] = {{0, 3, 2, 1}, {0, 1, 5, 4}, {1, 2, 6, 5},
                                      {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
  // Mid-edge node of the edge between two corners (Gmsh ordering).
  auto tet_edge = [](int a, int b) {
    static const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
    for (int e = 0; e < 6; ++e)
      if ((edges[e][0] == a && edges[e][1] == b) || (edges[e][0] == b && edges[e][1] == a))
        return 4 + e;
    return -1;
  };
  auto hex_edge = [](int a, int b) {
    static const int edges[12][2] = {{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                     {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
    for (int e = 0; e < 12; ++e)
      if ((edges[e][0] == a && edges[e][1] == b) || (edges[e][0] == b && edges[e][1] == a))
        return 8 + e;
    return -1;
  };
  require(face >= 0 && face < faces_per_element(type), "element face {} out of range for {}",
          face, name_of(type));
  std::vector<int> nodes;
  if (corner_nodes(type) == 4) {
    nodes.assign(tet_faces[face], tet_faces[face] + 3);
    if (type == ElementType::Tet10)
      for (int k = 0; k < 3; ++k) nodes.push_back(tet_edge(nodes[k], nodes[(k + 1) % 3]));
  } else {
    nodes.assign(hex_faces[face], hex_faces[face] + 4);
    if (type == ElementType::Hex20)
      for (int k = 0; k < 4; ++k) nodes.push_back(hex_edge(nodes[k], nodes[(k + 1) % 4]));
  }
  return nodes;
}

Index Mesh::element_count() const {
  Index total = 0;
  for (const auto& block : blocks) total += block.size();
  return total;
}

void Mesh::validate() const {
  const Index n = node_count();
  require(n > 0, "mesh has no nodes");
  require(!blocks.empty() && element_count() > 0, "mesh has no volume elements");
  for (Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      require(std::isfinite(nodes(i, c)), "mesh node {} has a non-finite coordinate", i);
  for (const auto& block : blocks) {
    require(block.connectivity.size() % size_t(nodes_per_element(block.type)) == 0,
            "{} block connectivity length {} is not a multiple of {}", name_of(block.type),
            block.connectivity.size(), nodes_per_element(block.type));
    for (Index node : block.connectivity)
      require(node >= 0 && node < n, "{} element refers to node {} (mesh has {} nodes)",
              name_of(block.type), node, n);
  }
  for (const auto& [name, set] : node_sets)
    for (Index node : set)
      require(node >= 0 && node < n, "node set '{}' refers to node {} (mesh has {} nodes)", name,
              node, n);
  for (const auto& [name, faces] : face_sets)
    for (const auto& block : faces)
      for (Index node : block.connectivity)
        require(node >= 0 && node < n, "face set '{}' refers to node {} (mesh has {} nodes)",
                name, node, n);
  const Index elements = element_count();
  for (const auto& [name, set] : element_sets)
    for (Index e : set)
      require(e >= 0 && e < elements, "element set '{}' refers to element {} (mesh has {})", name,
              e, elements);
}

namespace {
template <typename Map>
std::string names_of(const Map& map) {
  std::string names;
  for (const auto& [name, value] : map) names += (names.empty() ? "" : ", ") + name;
  return names.empty() ? "none" : names;
}
}  // namespace

const std::vector<Index>& Mesh::node_set(const std::string& name) const {
  auto it = node_sets.find(name);
  if (it == node_sets.end())
    fail("mesh has no node set '{}' (node sets present: {})", name, names_of(node_sets));
  return it->second;
}

const std::vector<FaceBlock>& Mesh::face_set(const std::string& name) const {
  auto it = face_sets.find(name);
  if (it == face_sets.end())
    fail("mesh has no face set '{}' (face sets present: {})", name, names_of(face_sets));
  return it->second;
}

std::vector<Index> nodes_of_faces(const std::vector<FaceBlock>& faces) {
  std::vector<Index> nodes;
  for (const auto& block : faces)
    nodes.insert(nodes.end(), block.connectivity.begin(), block.connectivity.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

}  // namespace kinetofem::fem
