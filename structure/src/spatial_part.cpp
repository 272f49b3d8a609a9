#include "kinetofem/structure/spatial_part.hpp"

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::structure {

SpatialPart spatial_part_of(const Part& part) {
  SpatialPart out;
  out.label = part.name();
  out.model = part.model;
  loads::SpatialLinkDefinition& a = out.attachments;
  a.body = part.body();
  require(part.held_face.empty(), "{}: a part of the ground (held on '{}') is not taken by the spatial core yet",
          part.name(), part.held_face);
  for (const loads::JointAttachment& j : part.attachments.joints) {
    require(j.distribution == loads::BoreLoad::DistributingCoupling,
            "{}: joint '{}': in the spatial core a pin's load enters through a distributing coupling only (no "
            "bearing pressure, no contact)",
            part.name(), j.joint);
    a.joints.push_back({j.joint, j.face_set});
  }
  for (const loads::DriveAttachment& d : part.attachments.drives) a.joints.push_back({d.drive, d.face_set});
  for (const loads::PointMassAttachment& m : part.attachments.point_masses)
    a.point_masses.push_back({m.point_mass, m.face_set});
  for (const loads::PointForceAttachment& f : part.attachments.point_forces)
    a.point_forces.push_back({f.point_force, f.face_set});
  require(part.attachments.transmissions.empty() && part.attachments.springs.empty(),
          "{}: transmissions and springs are not taken by the spatial core's loads yet", part.name());
  return out;
}

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
