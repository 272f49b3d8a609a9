#include "kinetofem/pipeline/part_model.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/postproc/results_layout.hpp"
#include "kinetofem/solver/couplings.hpp"

namespace kinetofem::pipeline {

using units::kMm;

const char* name_of(PartSource source) {
  switch (source) {
    case PartSource::File: return "file";
    case PartSource::Lever: return "lever";
    case PartSource::ArmWithRoller: return "arm_with_roller";
    case PartSource::Coupler: return "coupler";
    case PartSource::Rocker: return "rocker";
  }
  return "?";
}

void place_mesh(fem::Mesh& mesh, const PartPlacement& placement) {
  if (placement.angle_rad == 0.0 && placement.offset_m.isZero()) return;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(placement.angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::RowVector3d offset = placement.offset_m.transpose();
  for (fem::Index i = 0; i < mesh.node_count(); ++i)
    mesh.nodes.row(i) = mesh.nodes.row(i) * R.transpose() + offset;
}

namespace {

fem::Mesh mesh_of(const PartSpec& spec, const meshes::MeshOptions& options) {
  try {
    switch (spec.source) {
      case PartSource::File: return meshes::mesh_part_file(spec.file, spec.file_options, options);
      case PartSource::Lever:
      case PartSource::Rocker: spec.lever.validate(); return meshes::mesh_lever(spec.lever, options);
      case PartSource::ArmWithRoller:
      case PartSource::Coupler: spec.arm.validate(); return meshes::mesh_arm(spec.arm, options);
    }
  } catch (const Error& e) {
    fail("{}: {}", spec.label, e.what());
  }
  fail("{}: unknown part source", spec.label);
}

// The case's material with each value a solid gives in its place.
std::vector<fem::ElementSetMaterial> solid_materials(const PartSpec& spec, const fem::IsotropicMaterial& material,
                                                     const fem::Mesh& mesh) {
  std::vector<fem::ElementSetMaterial> out;
  for (const auto& solid : spec.solid_materials) {
    const std::string set = meshes::solid_set_name(solid.solid);
    require(mesh.element_sets.contains(set), "{}: a material for solid '{}', which the part does not have", spec.label,
            solid.solid);
    fem::IsotropicMaterial own = material;
    own.name = fmt::format("{} (solid {})", material.name, solid.solid);
    own.youngs_modulus_pa = solid.youngs_modulus_pa.value_or(material.youngs_modulus_pa);
    own.poisson_ratio = solid.poisson_ratio.value_or(material.poisson_ratio);
    own.density_kg_m3 = solid.density_kg_m3.value_or(material.density_kg_m3);
    try {
      own.validate();
    } catch (const Error& e) {
      fail("{}: solid '{}': {}", spec.label, solid.solid, e.what());
    }
    out.push_back({set, own});
  }
  return out;
}

}  // namespace

std::vector<Part> build_part_models(const std::vector<PartSpec>& specs, const fem::IsotropicMaterial& material,
                                    const meshes::MeshOptions& options, const Log& log) {
  std::set<std::string> bodies;
  for (const auto& spec : specs)
    require(bodies.insert(spec.attachments.body).second, "{}: body '{}' has a second part (one part per body)",
            spec.label, spec.attachments.body);
  std::vector<Part> parts;
  parts.reserve(specs.size());
  if (!specs.empty())
    log.info("meshing {} part(s) (element size {:.1f} mm, order {})", specs.size(), options.element_size_m / kMm,
             options.order);
  for (const auto& spec : specs) {
    Stopwatch clock;
    Part part;
    part.label = spec.label;
    part.attachments = spec.attachments;
    part.model.mesh = mesh_of(spec, options);
    place_mesh(part.model.mesh, spec.placement);
    part.model.material = material;
    part.model.set_materials = solid_materials(spec, material, part.model.mesh);
    part.mass = fem::mass_properties(part.model.mesh, fem::element_materials(part.model));
    part.meshing_seconds = clock.seconds();
    part.held_face = spec.held_face;
    if (!part.held_face.empty()) structure::foundation_support(part);  // the face set exists (else Error)
    const fem::Mesh& mesh = part.model.mesh;
    log.info("  {}: {} nodes, {} elements ({}), {} DoFs, {:.3f} kg; {:.2f} s", spec.label, mesh.node_count(),
             mesh.element_count(), mesh.blocks.empty() ? "-" : fem::name_of(mesh.blocks.front().type),
             3 * mesh.node_count(), part.mass.mass_kg, part.meshing_seconds);
    parts.push_back(std::move(part));
  }
  for (auto& part : parts) part.attachments.model = &part.model;
  // Parts in their own planes: the per-part stage is planar, the elastic
  // assembly is not; the user should know which result carries what.
  if (parts_in_several_planes(specs))
    log.info("  parts in their own planes (offset_mm z differs): each part's stress over the motion uses the planar "
             "multibody reactions; the out-of-plane moments at pins between bores at different z are carried by the "
             "elastic assembly (assembly.enabled: its fields, its pins' histories and the fatigue check's stress, "
             "docs/elastic_assembly.md)");
  return parts;
}

bool parts_in_several_planes(const std::vector<PartSpec>& specs) {
  return std::any_of(specs.begin(), specs.end(), [&](const PartSpec& spec) {
    return spec.placement.offset_m.z() != specs.front().placement.offset_m.z();
  });
}

void write_solid_field(post::BodyWriter& body, const fem::Mesh& mesh) {
  const meshes::ElementSolids solids = meshes::element_solids(mesh);
  if (solids.names.empty()) return;
  Eigen::VectorXd solid(Eigen::Index(solids.of_element.size()));
  for (std::size_t e = 0; e < solids.of_element.size(); ++e) solid(Eigen::Index(e)) = solids.of_element[e];
  body.write_element_field(post::layout::kSolid, post::layout::kDimensionless, solid);
}

void apply_mass_properties(mech::MultibodyModel& model, const std::vector<Part>& parts, const Log& log,
                           const std::vector<PartSpec>& specs) {
  require(specs.empty() || specs.size() == parts.size(), "mass properties: {} part specs for {} parts", specs.size(),
          parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const Part& part = parts[k];
    auto it = std::find_if(model.bodies.begin(), model.bodies.end(),
                           [&](const mech::Body& b) { return b.name == part.body(); });
    require(it != model.bodies.end(), "{}: the mechanism has no body '{}'", part.label, part.body());
    const fem::MassProperties& mp = part.mass;
    if (it->fixed) {
      require(!part.held_face.empty(), "{}: body '{}' is the ground: a part on it is the frame and needs held_face (its foundation face set)",
              part.label, it->name);
      // The frame: the ground does not move, so its mass enters no equation
      // of motion; its weight loads its own stress and the foundation.
      log.info("  body '{}' (the ground) carries a frame part held on '{}': {:.4f} kg, not in the dynamics", it->name,
               part.held_face, mp.mass_kg);
      continue;
    }
    const std::string mesh_line =
        fmt::format("mesh {:.4f} kg, centre of mass ({:.2f}, {:.2f}) mm, I_zz {:.5g} kg m^2", mp.mass_kg,
                    mp.centre_of_mass_m.x() / kMm, mp.centre_of_mass_m.y() / kMm, mp.inertia_about_com_kgm2(2, 2));
    const bool case_given = it->mass_kg > 0 || it->inertia_kgm2 > 0;
    const std::string case_line =
        case_given ? fmt::format("case {:.4f} kg, centre of mass ({:.2f}, {:.2f}) mm, I_zz {:.5g} kg m^2", it->mass_kg,
                                 it->com_body.x() / kMm, it->com_body.y() / kMm, it->inertia_kgm2)
                   : std::string("case: none given");
    if (specs.empty() || specs[k].mass_from_mesh) {
      loads::assign_mass_properties(*it, part.model);
      log.detail("  body '{}' mass properties: {} (used); {}", it->name, mesh_line, case_line);
    } else {
      require(it->mass_kg > 0 && it->inertia_kgm2 > 0,
              "{}: mass_properties = \"case\" needs the body's mass_kg > 0 and inertia_kgm2 > 0", part.label);
      log.detail("  body '{}' mass properties: {} (used); {}", it->name, case_line, mesh_line);
    }
  }
}

namespace {

// Centre (in the plane) and mean in-plane radius of a face set's nodes.
struct FaceSetCircle {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius_m = 0.0;
};

FaceSetCircle circle_of(const fem::Mesh& mesh, const std::string& face_set) {
  // The area-weighted centroid (exact for a full cylinder whatever the node
  // spacing, unlike the mean of the nodes).
  const fem::DistributingCoupling coupling(mesh, face_set);
  const std::vector<fem::Index>& nodes = coupling.nodes();
  FaceSetCircle c;
  c.centre = coupling.centroid().head<2>();
  for (fem::Index n : nodes) c.radius_m += (mesh.nodes.row(n).head<2>().transpose() - c.centre).norm();
  c.radius_m /= double(std::max<std::size_t>(nodes.size(), 1));
  return c;
}

std::string sets_of(const fem::Mesh& mesh) {
  std::string out;
  for (const auto& [name, faces] : mesh.face_sets) out += (out.empty() ? "" : ", ") + name;
  return out.empty() ? "none" : out;
}

void require_face_set(const Part& part, const std::string& face_set, const std::string& user) {
  const fem::Mesh& mesh = part.model.mesh;
  if (mesh.face_sets.contains(face_set)) return;
  if (mesh.element_sets.contains(face_set) || mesh.node_sets.contains(face_set))
    fail("{}: {} acts through '{}', which is not a surface of the part (it is a {} group); surface sets: {}",
         part.label, user, face_set, mesh.element_sets.contains(face_set) ? "volume" : "curve or point",
         sets_of(mesh));
  fail("{}: {} acts through face set '{}', which the part does not have (it has: {})", part.label, user, face_set,
       sets_of(mesh));
}

Eigen::Vector2d point_on(const mech::Body& body, const std::string& point) {
  if (point == "origin") return Eigen::Vector2d::Zero();
  const auto it = body.points.find(point);
  require(it != body.points.end(), "body '{}' has no point '{}'", body.name, point);
  return it->second;
}

}  // namespace

void check_part_against_model(const Part& part, const mech::MultibodyModel& model) {
  const loads::LinkDefinition& a = part.attachments;
  const auto body_it = std::find_if(model.bodies.begin(), model.bodies.end(),
                                    [&](const mech::Body& b) { return b.name == a.body; });
  require(body_it != model.bodies.end(), "{}: the mechanism has no body '{}'", part.label, a.body);
  const mech::Body& body = *body_it;
  for (const auto& j : a.joints) require_face_set(part, j.face_set, fmt::format("joint '{}'", j.joint));
  for (const auto& m : a.point_masses) require_face_set(part, m.face_set, fmt::format("point mass '{}'", m.point_mass));
  for (const auto& d : a.drives) require_face_set(part, d.face_set, fmt::format("drive '{}'", d.drive));
  for (const auto& t : a.transmissions)
    require_face_set(part, t.face_set, fmt::format("transmission '{}'", t.transmission));
  for (const auto& s : a.springs) require_face_set(part, s.face_set, fmt::format("spring '{}'", s.spring));
  for (const auto& f : a.point_forces)
    require_face_set(part, f.face_set, fmt::format("point force '{}'", f.point_force));

  // Joint points of the body (revolute and chain: the bore or roller centre).
  struct JointPoint {
    std::string joint, face_set;
    Eigen::Vector2d at;
  };
  std::vector<JointPoint> points;
  for (const auto& attachment : a.joints) {
    const auto joint = std::find_if(model.joints.begin(), model.joints.end(),
                                    [&](const mech::Joint& j) { return j.name == attachment.joint; });
    require(joint != model.joints.end(), "{}: the mechanism has no joint '{}'", part.label, attachment.joint);
    const mech::JointFacts& facts = mech::joint_facts(joint->type);
    if (!(joint->body_i == a.body ? facts.pivot_i : facts.pivot_j)) continue;
    const std::string& point = joint->body_i == a.body ? joint->point_i : joint->point_j;
    points.push_back({joint->name, attachment.face_set, point_on(body, point)});
  }
  // Every other point a load acts at counts for the size check (a part with
  // one pivot and a payload, like the SPEC §1 arm, still has a span).
  std::vector<JointPoint> load_points = points;
  for (const auto& m : a.point_masses)
    for (const auto& pm : body.point_masses)
      if (pm.name == m.point_mass) load_points.push_back({"point mass '" + pm.name + "'", m.face_set, pm.position_body});
  for (const auto& f : a.point_forces)
    for (const auto& pf : model.point_forces)
      if (pf.name == f.point_force) load_points.push_back({"point force '" + pf.name + "'", f.face_set, point_on(body, pf.point)});
  for (const auto& sa : a.springs)
    for (const auto& sp : model.springs)
      if (sp.name == sa.spring)
        load_points.push_back({"spring '" + sp.name + "'", sa.face_set, point_on(body, sp.body_i == a.body ? sp.point_i : sp.point_j)});

  // Size: the part must be of the order of the distance between its joints.
  const fem::Mesh& mesh = part.model.mesh;
  const Eigen::Vector3d lo = mesh.nodes.colwise().minCoeff().transpose(), hi = mesh.nodes.colwise().maxCoeff().transpose();
  const double extent = (hi - lo).head<2>().norm();
  double span = 0.0;
  std::string from, to;
  for (const auto& p : load_points)
    for (const auto& q : load_points)
      if ((p.at - q.at).norm() > span) span = (p.at - q.at).norm(), from = p.joint, to = q.joint;
  if (span > 0.0)
    require(extent > 0.5 * span && extent < 20.0 * span,
            "{}: the part spans {:.4g} mm in the plane but its load points '{}' and '{}' are {:.4g} mm apart: is its "
            "length unit right? (expected a part of about {:.4g} mm or more)",
            part.label, extent / kMm, from, to, span / kMm, span / kMm);

  // Placement: each joint point must lie in its bore (the face set's circle).
  for (const auto& p : points) {
    const FaceSetCircle c = circle_of(mesh, p.face_set);
    const double distance = (p.at - c.centre).norm();
    require(distance <= 0.5 * c.radius_m + 1e-9,
            "{}: joint '{}' at ({:.3f}, {:.3f}) mm (body frame) lies {:.3f} mm from the centre of its face set '{}' "
            "(radius {:.3f} mm, centre ({:.3f}, {:.3f}) mm): check the part's placement (offset_mm, angle_deg) or the "
            "face set",
            part.label, p.joint, p.at.x() / kMm, p.at.y() / kMm, distance / kMm, p.face_set, c.radius_m / kMm,
            c.centre.x() / kMm, c.centre.y() / kMm);
  }
}

}  // namespace kinetofem::pipeline
