#include "kinetofem/pipeline/spherical_manipulator_parts.hpp"

#include <algorithm>
#include <string>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/spatial/spherical_manipulator_model.hpp"
#include "kinetofem/pipeline/spherical_part_sizing.hpp"

namespace kinetofem::pipeline {

namespace names = mech::spatial::spherical_names;

SphericalManipulatorParts spherical_manipulator_parts(const mech::SphericalDesign& design,
                                                      meshes::SphericalPartRules rules, const meshes::MeshOptions& mesh,
                                                      const fem::IsotropicMaterial& material, const Log& log) {
  SphericalManipulatorParts out;
  rules.density_kg_m3 = material.density_kg_m3;
  out.dimensions = meshes::spherical_part_dimensions(spherical_part_sizing(design), rules);
  const meshes::SphericalPartDimensions& d = out.dimensions;
  Stopwatch clock;
  auto part = [&](meshes::SphericalPart which) {
    SpatialPart p;
    const std::string body(meshes::spherical_part_name(which));
    p.label = "part '" + body + "'";
    p.attachments.body = body;
    p.model.material = material;
    try {
      p.model.mesh = meshes::mesh_spherical_part(which, d, mesh);
    } catch (const Error& e) {
      fail("{} (SPEC §5 parametric part): {}", p.label, e.what());
    }
    log.info("{}: {} nodes, {} elements", p.label, p.model.mesh.node_count(), p.model.mesh.element_count());
    return p;
  };
  const std::string pair_10(names::pair_10), pair_21(names::pair_21), pair_32(names::pair_32);
  const std::string drive_10(names::drive_10), drive_21(names::drive_21), drive_32(names::drive_32);

  SpatialPart column = part(meshes::SphericalPart::Column);
  column.attachments.joints = {
      {pair_10, "pair_10"}, {drive_10, "pair_10"}, {pair_21, "pair_21"}, {drive_21, "pair_21"}};

  SpatialPart sleeve = part(meshes::SphericalPart::Sleeve);
  sleeve.attachments.joints = {{pair_21, "pair_21"}, {drive_21, "pair_21"}};
  loads::SpatialSlideAttachment slide;
  slide.joint = pair_32;
  slide.drive = drive_32;
  slide.front_m = 0.5 * (d.sleeve.length_m - d.sleeve.guide_length_m);
  slide.rear_m = -slide.front_m;
  slide.front_face_set = "pair_32_front";
  slide.rear_face_set = "pair_32_rear";

  SpatialPart arm = part(meshes::SphericalPart::Arm);
  // The model's arm frame: origin at the rear end (header).
  arm.model.mesh.nodes.col(0).array() += d.arm.length_m;
  const Eigen::Vector3d point_m(d.arm.length_m, 0.0, 0.0);
  try {
    slide.stations = loads::add_slide_stations(arm.model.mesh, "slide", point_m, Eigen::Vector3d::UnitX(),
                                               d.sleeve.guide_length_m, 0.5 * d.sleeve.guide_length_m);
  } catch (const Error& e) {
    fail("{}: {}", arm.label, e.what());
  }
  sleeve.attachments.slides = {slide};
  arm.attachments.slides = {slide};
  arm.attachments.point_masses = {{std::string(names::payload), "gripper_mount"}};
  out.meshing_seconds = clock.seconds();
  out.parts = {std::move(column), std::move(sleeve), std::move(arm)};
  return out;
}

void apply_spatial_mass_properties(mech::spatial::Model& model, const std::vector<SpatialPart>& parts) {
  for (const SpatialPart& p : parts) {
    const auto body = std::find_if(model.bodies.begin(), model.bodies.end(),
                                   [&](const mech::spatial::Body& b) { return b.name == p.attachments.body; });
    require(body != model.bodies.end(), "{}: the mechanism has no body '{}'", p.label, p.attachments.body);
    loads::assign_mass_properties(*body, p.model);
  }
}

}  // namespace kinetofem::pipeline
