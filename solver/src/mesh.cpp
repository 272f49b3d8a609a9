#include "kinetofem/solver/mesh.hpp"

#include <algorithm>
#include <cmath>

#include "kinetofem/core/error.hpp"

namespace kinetofem::fem {

int nodes_per_element(ElementType type) { return element_facts(type).nodes; }

int nodes_per_face(FaceType type) { return face_facts(type).nodes; }

const char* name_of(ElementType type) { return element_facts(type).name; }

const char* name_of(FaceType type) { return face_facts(type).name; }

int corner_nodes(ElementType type) { return element_facts(type).corners; }

FaceType face_type_of(ElementType type) { return element_facts(type).face_type; }

int faces_per_element(ElementType type) { return element_facts(type).face_count; }

std::vector<int> element_face_nodes(ElementType type, int face) {
  const ElementFacts& facts = element_facts(type);
  require(face >= 0 && face < facts.face_count, "element face {} out of range for {}", face,
          facts.name);
  const auto nodes = facts.face(face);
  return {nodes.begin(), nodes.end()};
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
