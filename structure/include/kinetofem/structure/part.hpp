#pragma once
// Part — the elastic FE part of one body of a planar linkage, as the
// libraries beneath the pipeline see it: its mesh in the BODY frame of the
// multibody model (m), its material, its mass properties (body frame) and how
// the mechanism acts on it (loads::LinkDefinition: the face set of every
// joint, chain, drive, point mass, spring and point force on its body).
//
// Here in structure/, not in loads/: a Part is a body of the linkage's
// elastic structure (the elastic assembly models it, the assembly's modes in
// vibration/ reduce it, the per-part stress in pipeline/ loads it), while
// loads/ only needs a part's attachments and mesh (LinkDefinition). How a part
// is built (its source: a file or parametric dimensions, its placement) is
// the pipeline's (pipeline::PartSpec, pipeline::build_part_models).
#include <string>
#include <vector>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::structure {

struct Part {
  std::string label;                // for messages: "part 'crank' (parts/crank.step)"
  // The body this part belongs to and where each load on it acts; its
  // `model` points at `model` below once the part sits in its final place
  // (pipeline::build_part_models sets it).
  loads::LinkDefinition attachments;
  fem::FeModel model;               // mesh in the body frame, material; no supports
  fem::MassProperties mass;         // of the mesh, body frame
  double meshing_seconds = 0.0;     // wall time its mesh took
  // A part of the ground body (the frame: a column, a base plate) is held on
  // this face set, its foundation (every node fixed in x, y and z); empty
  // for the parts of moving bodies, which only a 3-2-1 support holds.
  std::string held_face;
  const std::string& body() const { return attachments.body; }
  // The label, or "part '<body>'" when none was given.
  std::string name() const { return label.empty() ? "part '" + body() + "'" : label; }
};

// The foundation of a frame part: every node of its held_face fixed in x, y
// and z. Throws Error naming the part when it has no held_face or its mesh
// lacks that face set.
inline std::vector<fem::DisplacementSupport> foundation_support(const Part& part) {
  require(!part.held_face.empty(), "{}: a part of the ground (a frame) needs held_face, the face set of its foundation",
          part.name());
  std::vector<fem::Index> nodes;
  try {
    nodes = fem::nodes_of_faces(part.model.mesh.face_set(part.held_face));
  } catch (const Error& e) {
    fail("{}: held_face '{}': {}", part.name(), part.held_face, e.what());
  }
  require(!nodes.empty(), "{}: held_face '{}' has no nodes", part.name(), part.held_face);
  fem::DisplacementSupport held;
  held.label = "foundation '" + part.held_face + "'";
  held.nodes = std::move(nodes);
  return {held};
}

// The part as its static analyses hold it: the frame on its foundation
// (foundation_support); a moving part by a 3-2-1 support
// (fem::three_two_one_support: it holds only the rigid motion, so a
// self-equilibrated load meets no reaction) on any node but those of a bore
// a pin is in contact with (a contact node must be free to move against the
// pin, and a held one would have no compliance). The per-part stage and the
// elastic assembly share a factorization of this very model.
inline fem::FeModel supported_model(const Part& part) {
  fem::FeModel supported = part.model;
  if (!part.held_face.empty()) {
    supported.supports = foundation_support(part);
    return supported;
  }
  std::vector<char> on_contact_bore(size_t(supported.mesh.node_count()), 0);
  for (const auto& j : part.attachments.joints)
    if (j.distribution == loads::BoreLoad::Contact)
      for (const fem::Index n : fem::nodes_of_faces(supported.mesh.face_set(j.face_set))) on_contact_bore[size_t(n)] = 1;
  std::vector<fem::Index> candidates;
  for (fem::Index i = 0; i < supported.mesh.node_count(); ++i)
    if (!on_contact_bore[size_t(i)]) candidates.push_back(i);
  supported.supports = fem::three_two_one_support(supported.mesh, candidates);
  return supported;
}

}  // namespace kinetofem::structure
