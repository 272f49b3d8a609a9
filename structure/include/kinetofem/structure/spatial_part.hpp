#pragma once
// SpatialPart — the elastic FE part of one body of a spatial mechanism
// (mech::spatial::Model): its mesh in the body's frame of the spatial model
// (m), its material, and where each load of the mechanism enters it
// (loads::SpatialLinkDefinition: the face sets of its joints and drives, point
// masses, point forces and slides). The per-part stress stage
// (pipeline::analyse_spatial_part_over_motion) and the spatial elastic
// assembly (spatial_elastic_assembly.hpp) share this definition and the
// support below.
#include <string>
#include <vector>

#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/structure/part.hpp"

namespace kinetofem::structure {

struct SpatialPart {
  std::string label;                         // for messages: "part 'arm'"
  loads::SpatialLinkDefinition attachments;  // its `model` is set by whoever loads the part
  fem::FeModel model;                        // mesh in the body frame, material; no supports
  const std::string& body() const { return attachments.body; }
};

// A part of a planar linkage as a part of the same linkage lifted into the
// spatial core (mech::spatial::from_planar keeps the bodies' frames and the
// joints', drives' and point masses' names): each joint, motion drive, point
// mass and point force through the same face set. Throws Error naming the
// part for what the spatial loads do not take: a bore load other than the
// distributing coupling (bearing pressure, contact), a transmission, a spring,
// a part of the ground.
SpatialPart spatial_part_of(const Part& part);

// The nodes of the face sets through which the mechanism loads the part (its
// joints and drives, point masses, point forces, and the side of each slide
// it carries: a guide's lands or a slider's face), as a mask over the nodes.
std::vector<char> loaded_nodes(const SpatialPart& part);

// The part held by a 3-2-1 support on nodes where no load enters (a support
// node under a coupling would take part of the load into a reaction that
// must vanish; any other node holds only the rigid motion). Throws Error
// naming the part when a face set it names is missing.
fem::FeModel spatial_supported_model(const SpatialPart& part);

}  // namespace kinetofem::structure
