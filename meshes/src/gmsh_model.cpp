#include "gmsh_model.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <optional>
#include <unordered_map>

#include <fmt/format.h>
#include <gmsh.h>

#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes::detail {

namespace {

using fem::ElementType;
using fem::FaceType;
using fem::Index;
using Tags = std::vector<std::size_t>;

// Gmsh element type numbers are rows of the element table (element_traits.hpp).
int gmsh_type_of(ElementType type) { return fem::element_facts(type).gmsh_code; }
int gmsh_type_of(FaceType type) { return fem::face_facts(type).gmsh_code; }
constexpr int gmsh_point_type = 15;

std::optional<ElementType> element_type_of_gmsh(int gmsh_type) {
  for (auto type : fem::all_element_types)
    if (gmsh_type_of(type) == gmsh_type) return type;
  return std::nullopt;
}
std::optional<FaceType> face_type_of_gmsh(int gmsh_type) {
  for (auto type : fem::all_face_types)
    if (gmsh_type_of(type) == gmsh_type) return type;
  return std::nullopt;
}

std::string gmsh_type_name(GmshSession& session, const std::string& context, int gmsh_type) {
  std::string name;
  int dim = 0, order = 0, nodes = 0, primary = 0;
  std::vector<double> local;
  session.call(context, "gmsh::model::mesh::getElementProperties", [&] {
    gmsh::model::mesh::getElementProperties(gmsh_type, name, dim, order, nodes, local, primary);
  });
  return name;
}

struct EntityElements {
  std::vector<int> types;
  std::vector<Tags> tags;
  std::vector<Tags> nodes;
};

EntityElements elements_of(GmshSession& session, const std::string& context, int dim, int tag) {
  EntityElements result;
  session.call(context, "gmsh::model::mesh::getElements", [&] {
    gmsh::model::mesh::getElements(result.types, result.tags, result.nodes, dim, tag);
  });
  return result;
}

// A face identified by its sorted corner nodes (-1 pads triangles).
using FaceKey = std::array<Index, 4>;
struct FaceKeyHash {
  std::size_t operator()(const FaceKey& key) const {
    std::size_t hash = 0;
    for (Index v : key) hash = hash * 1000003u ^ std::hash<Index>()(v);
    return hash;
  }
};
FaceKey key_of(std::span<const Index> corners) {
  FaceKey key{-1, -1, -1, -1};
  const std::size_t n = std::min<std::size_t>(corners.size(), key.size());
  std::copy_n(corners.begin(), n, key.begin());
  std::sort(key.begin(), key.begin() + std::ptrdiff_t(n));
  return key;
}

// Where a face lies on the volume mesh: the first element (lowest global
// index) having it as one of its faces.
struct FaceOwner {
  Index block = -1;
  Index element = -1;
  int face = -1;
};

// Finds the owning element face of every key (one pass over all elements).
void find_owners(const fem::Mesh& mesh, std::unordered_map<FaceKey, FaceOwner, FaceKeyHash>& owners) {
  if (owners.empty()) return;
  for (Index b = 0; b < Index(mesh.blocks.size()); ++b) {
    const auto& block = mesh.blocks[b];
    const int faces = fem::faces_per_element(block.type);
    std::vector<std::vector<int>> local(faces);
    for (int f = 0; f < faces; ++f) local[f] = fem::element_face_nodes(block.type, f);
    const int face_corners = fem::face_facts(fem::face_type_of(block.type)).corners;
    std::array<Index, 4> corners{};
    for (Index e = 0; e < block.size(); ++e) {
      const auto element = block.element(e);
      for (int f = 0; f < faces; ++f) {
        for (int k = 0; k < face_corners; ++k) corners[k] = element[local[f][k]];
        auto it = owners.find(key_of({corners.data(), std::size_t(face_corners)}));
        if (it != owners.end() && it->second.block < 0) it->second = {b, e, f};
      }
    }
  }
}

}  // namespace

fem::Mesh mesh_from_model(GmshSession& session, const std::string& context) {
  fem::Mesh mesh;

  // ---- volume elements, grouped by type, each type sorted by Gmsh tag ----
  gmsh::vectorpair volumes;
  session.call(context, "gmsh::model::getEntities",
               [&] { gmsh::model::getEntities(volumes, 3); });
  std::array<std::vector<std::pair<std::size_t, std::vector<std::size_t>>>,
             fem::all_element_types.size()>
      collected;
  for (const auto& [dim, tag] : volumes) {
    const auto elements = elements_of(session, context, 3, tag);
    for (std::size_t k = 0; k < elements.types.size(); ++k) {
      const auto type = element_type_of_gmsh(elements.types[k]);
      if (!type)
        fail("{}: volume {} holds {} elements of type '{}' (Gmsh type {}); only TET4, TET10, "
             "HEX8 and HEX20 (Gmsh types 4, 11, 5, 17) are supported",
             context, tag, elements.tags[k].size(),
             gmsh_type_name(session, context, elements.types[k]), elements.types[k]);
      const int n = fem::nodes_per_element(*type);
      auto& list = collected[std::size_t(*type)];
      for (std::size_t e = 0; e < elements.tags[k].size(); ++e)
        list.emplace_back(elements.tags[k][e],
                          std::vector<std::size_t>(elements.nodes[k].begin() + e * n,
                                                   elements.nodes[k].begin() + (e + 1) * n));
    }
  }
  std::size_t element_total = 0;
  for (const auto& list : collected) element_total += list.size();
  require(element_total > 0,
          "{}: the mesh has no volume elements (TET4, TET10, HEX8 or HEX20); a surface or line "
          "mesh cannot be analysed",
          context);

  // ---- nodes: those of volume elements, in increasing Gmsh tag order ----
  Tags all_tags;
  std::vector<double> all_coords, parametric;
  session.call(context, "gmsh::model::mesh::getNodes", [&] {
    gmsh::model::mesh::getNodes(all_tags, all_coords, parametric, -1, -1, false, false);
  });
  std::unordered_map<std::size_t, std::size_t> position;  // Gmsh tag -> row in all_coords
  position.reserve(all_tags.size());
  for (std::size_t i = 0; i < all_tags.size(); ++i) position.emplace(all_tags[i], i);
  Tags used;
  for (const auto& list : collected)
    for (const auto& [tag, nodes] : list) used.insert(used.end(), nodes.begin(), nodes.end());
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  std::unordered_map<std::size_t, Index> index_of;  // Gmsh node tag -> 0-based index
  index_of.reserve(used.size());
  mesh.nodes.resize(Index(used.size()), 3);
  for (std::size_t i = 0; i < used.size(); ++i) {
    const auto it = position.find(used[i]);
    require(it != position.end(), "{}: an element refers to node {}, which the file does not define",
            context, used[i]);
    for (int c = 0; c < 3; ++c) mesh.nodes(Index(i), c) = all_coords[3 * it->second + c];
    index_of.emplace(used[i], Index(i));
  }

  // ---- element blocks in the order TET4, TET10, HEX8, HEX20 ----
  std::unordered_map<std::size_t, Index> global_of;  // Gmsh element tag -> global index
  global_of.reserve(element_total);
  Index global = 0;
  for (auto type : fem::all_element_types) {
    auto& list = collected[std::size_t(type)];
    if (list.empty()) continue;
    std::sort(list.begin(), list.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    fem::ElementBlock block;
    block.type = type;
    block.connectivity.reserve(list.size() * std::size_t(fem::nodes_per_element(type)));
    for (const auto& [tag, nodes] : list) {
      require(global_of.emplace(tag, global++).second, "{}: element tag {} appears twice", context,
              tag);
      for (auto node : nodes) block.connectivity.push_back(index_of.at(node));
    }
    mesh.blocks.push_back(std::move(block));
  }

  // ---- physical groups -> sets ----
  gmsh::vectorpair groups;
  session.call(context, "gmsh::model::getPhysicalGroups",
               [&] { gmsh::model::getPhysicalGroups(groups, -1); });
  std::map<std::string, std::pair<int, int>> seen;  // name -> (dim, tag)
  struct PendingFaces {
    std::string name;
    std::vector<std::pair<FaceType, std::vector<Index>>> faces;  // one per face
  };
  std::vector<PendingFaces> pending;
  for (const auto& [dim, group] : groups) {
    std::string name;
    session.call(context, "gmsh::model::getPhysicalName",
                 [&, dim = dim, group = group] { gmsh::model::getPhysicalName(dim, group, name); });
    if (name.empty()) name = fmt::format("physical_{}d_{}", dim, group);
    const auto [it, inserted] = seen.emplace(name, std::pair{dim, group});
    require(inserted,
            "{}: physical group name '{}' is used twice (dimension {} tag {} and dimension {} "
            "tag {}); give each group its own name",
            context, name, it->second.first, it->second.second, dim, group);
    std::vector<int> entities;
    session.call(context, "gmsh::model::getEntitiesForPhysicalGroup", [&, dim = dim, group = group] {
      gmsh::model::getEntitiesForPhysicalGroup(dim, group, entities);
    });

    std::vector<Index> node_set;
    std::vector<Index> element_set;
    PendingFaces faces{name, {}};
    for (int entity : entities) {
      Tags tags;
      std::vector<double> coords;
      session.call(context, "gmsh::model::mesh::getNodes", [&, dim = dim] {
        gmsh::model::mesh::getNodes(tags, coords, parametric, dim, entity, true, false);
      });
      const auto elements = elements_of(session, context, dim, entity);
      for (const auto& nodes : elements.nodes) tags.insert(tags.end(), nodes.begin(), nodes.end());
      for (auto tag : tags)
        if (auto found = index_of.find(tag); found != index_of.end())
          node_set.push_back(found->second);
      if (dim == 3)
        for (const auto& element_tags : elements.tags)
          for (auto tag : element_tags) element_set.push_back(global_of.at(tag));
      if (dim == 2)
        for (std::size_t k = 0; k < elements.types.size(); ++k) {
          const auto type = face_type_of_gmsh(elements.types[k]);
          if (!type)
            fail("{}: surface {} of physical group '{}' holds elements of type '{}' (Gmsh type "
                 "{}); face sets take only TRI3, TRI6, QUAD4 and QUAD8",
                 context, entity, name, gmsh_type_name(session, context, elements.types[k]),
                 elements.types[k]);
          const int n = fem::nodes_per_face(*type);
          for (std::size_t f = 0; f < elements.tags[k].size(); ++f) {
            std::vector<Index> face(static_cast<std::size_t>(n));
            for (int v = 0; v < n; ++v) {
              const auto tag = elements.nodes[k][f * n + v];
              const auto found = index_of.find(tag);
              require(found != index_of.end(),
                      "{}: physical surface '{}' has a face (element {}) on node {} that belongs "
                      "to no volume element",
                      context, name, elements.tags[k][f], tag);
              face[v] = found->second;
            }
            faces.faces.emplace_back(*type, std::move(face));
          }
        }
    }
    std::sort(node_set.begin(), node_set.end());
    node_set.erase(std::unique(node_set.begin(), node_set.end()), node_set.end());
    mesh.node_sets[name] = std::move(node_set);
    if (dim == 3) {
      std::sort(element_set.begin(), element_set.end());
      element_set.erase(std::unique(element_set.begin(), element_set.end()), element_set.end());
      mesh.element_sets[name] = std::move(element_set);
    }
    if (dim == 2) pending.push_back(std::move(faces));
  }

  // ---- face sets, each face renumbered as the face of its volume element
  //      (so its normal points out of that element) ----
  std::unordered_map<FaceKey, FaceOwner, FaceKeyHash> owners;
  for (const auto& group : pending)
    for (const auto& [type, face] : group.faces)
      owners.emplace(key_of({face.data(), std::size_t(fem::face_facts(type).corners)}),
                     FaceOwner{});
  find_owners(mesh, owners);
  for (const auto& group : pending) {
    std::map<FaceType, fem::FaceBlock> blocks;
    for (const auto& [type, face] : group.faces) {
      const auto corners = std::size_t(fem::face_facts(type).corners);
      const auto& owner = owners.at(key_of({face.data(), corners}));
      require(owner.block >= 0,
              "{}: a face of physical surface '{}' (nodes {}) is no face of any volume element",
              context, group.name, fmt::join(face, " "));
      const auto& block = mesh.blocks[std::size_t(owner.block)];
      const auto element = block.element(owner.element);
      std::vector<Index> oriented;
      for (int local : fem::element_face_nodes(block.type, owner.face))
        oriented.push_back(element[local]);
      auto sorted_face = face, sorted_oriented = oriented;
      std::sort(sorted_face.begin(), sorted_face.end());
      std::sort(sorted_oriented.begin(), sorted_oriented.end());
      require(sorted_face == sorted_oriented,
              "{}: a {} face of physical surface '{}' does not match the {} face of the {} "
              "element it lies on (mixed orders?)",
              context, fem::name_of(type), group.name, fem::name_of(fem::face_type_of(block.type)),
              fem::name_of(block.type));
      auto& out = blocks[type];
      out.type = type;
      out.connectivity.insert(out.connectivity.end(), oriented.begin(), oriented.end());
    }
    auto& set = mesh.face_sets[group.name];
    for (auto& [type, block] : blocks) set.push_back(std::move(block));
  }
  return mesh;
}

void model_from_mesh(GmshSession& session, const fem::Mesh& mesh, const std::string& context) {
  mesh.validate();
  const Index element_total = mesh.element_count();

  // Element sets may overlap, but a Gmsh element lives in one entity: put the
  // elements with the same set membership into one discrete volume, and make
  // each set the physical group of the volumes whose membership includes it.
  std::vector<std::string> set_names;
  for (const auto& [name, set] : mesh.element_sets) set_names.push_back(name);
  std::vector<std::vector<int>> membership(static_cast<std::size_t>(element_total));
  for (std::size_t s = 0; s < set_names.size(); ++s)
    for (Index e : mesh.element_sets.at(set_names[s])) {
      auto& m = membership[std::size_t(e)];
      if (m.empty() || m.back() != int(s)) m.push_back(int(s));
    }
  std::map<std::vector<int>, int> volume_of;  // membership -> discrete volume tag
  for (auto& m : membership) std::sort(m.begin(), m.end());
  for (const auto& m : membership) volume_of.emplace(m, 0);

  // A node set named like a face or element set must be that set's nodes:
  // a .msh file has one physical group per name.
  for (const auto& [name, nodes] : mesh.node_sets) {
    std::vector<Index> implied;
    if (auto it = mesh.face_sets.find(name); it != mesh.face_sets.end()) {
      implied = fem::nodes_of_faces(it->second);
    } else if (auto es = mesh.element_sets.find(name); es != mesh.element_sets.end()) {
      std::vector<bool> in_set(static_cast<std::size_t>(element_total), false);
      for (Index e : es->second) in_set[std::size_t(e)] = true;
      Index global = 0;
      for (const auto& block : mesh.blocks)
        for (Index e = 0; e < block.size(); ++e, ++global)
          if (in_set[std::size_t(global)])
            for (Index v : block.element(e)) implied.push_back(v);
      std::sort(implied.begin(), implied.end());
      implied.erase(std::unique(implied.begin(), implied.end()), implied.end());
    } else {
      continue;
    }
    require(implied == nodes,
            "{}: node set '{}' is not the node list of the face/element set of the same name; a "
            ".msh file cannot hold both under one name",
            context, name);
  }
  for (const auto& [name, faces] : mesh.face_sets)
    require(!mesh.element_sets.count(name),
            "{}: '{}' is both a face set and an element set; a .msh file has one physical group "
            "per name",
            context, name);

  session.call(context, "building the Gmsh model", [&] {
    gmsh::clear();
    gmsh::model::add("kinetofem");
    int first_volume = 0;
    for (auto& [m, tag] : volume_of) {
      tag = gmsh::model::addDiscreteEntity(3);
      if (!first_volume) first_volume = tag;
    }
    Tags node_tags(static_cast<std::size_t>(mesh.node_count()));
    std::iota(node_tags.begin(), node_tags.end(), std::size_t(1));
    std::vector<double> coords(mesh.nodes.data(), mesh.nodes.data() + mesh.nodes.size());
    gmsh::model::mesh::addNodes(3, first_volume, node_tags, coords);

    // Element tags are global index + 1, so reading keeps the element order.
    std::size_t next_tag = 1;
    for (const auto& block : mesh.blocks) {
      const int n = fem::nodes_per_element(block.type);
      std::map<int, std::pair<Tags, Tags>> by_volume;  // volume -> (element tags, node tags)
      for (Index e = 0; e < block.size(); ++e, ++next_tag) {
        auto& [tags, nodes] = by_volume[volume_of.at(membership[next_tag - 1])];
        tags.push_back(next_tag);
        for (int v = 0; v < n; ++v) nodes.push_back(std::size_t(block.element(e)[v] + 1));
      }
      for (const auto& [volume, data] : by_volume)
        gmsh::model::mesh::addElementsByType(volume, gmsh_type_of(block.type), data.first,
                                             data.second);
    }
    for (std::size_t s = 0; s < set_names.size(); ++s) {
      std::vector<int> volumes;
      for (const auto& [m, tag] : volume_of)
        if (std::binary_search(m.begin(), m.end(), int(s))) volumes.push_back(tag);
      const int group = gmsh::model::addPhysicalGroup(3, volumes);
      gmsh::model::setPhysicalName(3, group, set_names[s]);
    }
    for (const auto& [name, blocks] : mesh.face_sets) {
      const int surface = gmsh::model::addDiscreteEntity(2);
      for (const auto& block : blocks) {
        Tags tags, nodes;
        for (Index f = 0; f < block.size(); ++f) {
          tags.push_back(next_tag++);
          for (Index v : block.face(f)) nodes.push_back(std::size_t(v + 1));
        }
        gmsh::model::mesh::addElementsByType(surface, gmsh_type_of(block.type), tags, nodes);
      }
      const int group = gmsh::model::addPhysicalGroup(2, {surface});
      gmsh::model::setPhysicalName(2, group, name);
    }
    // Other node sets: point elements on one discrete point entity each.
    for (const auto& [name, nodes] : mesh.node_sets) {
      if (mesh.face_sets.count(name) || mesh.element_sets.count(name)) continue;
      const int point = gmsh::model::addDiscreteEntity(0);
      Tags tags, node_tags_of_set;
      for (Index v : nodes) {
        tags.push_back(next_tag++);
        node_tags_of_set.push_back(std::size_t(v + 1));
      }
      if (!tags.empty())
        gmsh::model::mesh::addElementsByType(point, gmsh_point_type, tags, node_tags_of_set);
      const int group = gmsh::model::addPhysicalGroup(0, {point});
      gmsh::model::setPhysicalName(0, group, name);
    }
  });
}

}  // namespace kinetofem::meshes::detail
