#include "kinetofem/structure/spatial_part.hpp"

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::structure {

std::vector<char> loaded_nodes(const SpatialPart& part) {
  const fem::Mesh& mesh = part.model.mesh;
  std::vector<char> loaded(std::size_t(mesh.node_count()), 0);
  auto mark = [&](const std::string& face_set) {
    try {
      for (const fem::Index n : fem::nodes_of_faces(mesh.face_set(face_set))) loaded[std::size_t(n)] = 1;
    } catch (const Error& e) {
      fail("{}: {}", part.label, e.what());
    }
  };
  const loads::SpatialLinkDefinition& a = part.attachments;
  for (const auto* list : {&a.joints, &a.point_masses, &a.point_forces})
    for (const loads::SpatialAttachment& item : *list) mark(item.face_set);
  // A slide's attachment names the guide's lands and the slider's face; this
  // part has one side of them.
  for (const loads::SpatialSlideAttachment& slide : a.slides)
    for (const std::string* face_set : {&slide.front_face_set, &slide.rear_face_set, &slide.stations.face_set})
      if (mesh.face_sets.count(*face_set) != 0) mark(*face_set);
  return loaded;
}

fem::FeModel spatial_supported_model(const SpatialPart& part) {
  fem::FeModel supported = part.model;
  const std::vector<char> loaded = loaded_nodes(part);
  std::vector<fem::Index> candidates;
  for (fem::Index i = 0; i < supported.mesh.node_count(); ++i)
    if (!loaded[std::size_t(i)]) candidates.push_back(i);
  supported.supports = fem::three_two_one_support(supported.mesh, candidates);
  return supported;
}

}  // namespace kinetofem::structure
