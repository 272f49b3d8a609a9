#include "kinetofem/app/part_keys.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/iso_fit.hpp"
#include "kinetofem/core/units.hpp"

namespace kinetofem::app {

using units::kDeg;
using units::kMm;
using units::kMpa;
using Type = KeySpec::Type;

namespace {

const std::vector<std::string> kSources = {"file", "lever", "arm_with_roller", "coupler", "rocker"};

// Dimension keys of the parametric links: key, the source(s) it belongs to,
// and where it goes. Defaults come from the dimension structs (declared once there).
struct DimensionKey {
  std::string key;
  bool lever, arm;
  double meshes::LeverDimensions::* lever_field;
  double meshes::ArmDimensions::* arm_field;
  std::string doc;
};

const std::vector<DimensionKey>& dimension_keys() {
  using L = meshes::LeverDimensions;
  using A = meshes::ArmDimensions;
  static const std::vector<DimensionKey> keys = {
      {"length_mm", true, false, &L::length_m, nullptr, "lever/rocker: distance between the bore centres"},
      {"width_mm", true, false, &L::width_m, nullptr, "lever/rocker: plate width"},
      {"thickness_mm", true, false, &L::thickness_m, nullptr, "lever/rocker: plate thickness"},
      {"bore_diameter_mm", true, true, &L::bore_diameter_m, &A::bore_diameter_m, "pin bore diameter"},
      {"boss_diameter_mm", true, true, &L::boss_diameter_m, &A::boss_diameter_m, "boss outer diameter"},
      {"boss_length_mm", true, true, &L::boss_length_m, &A::boss_length_m, "boss length along the pins"},
      {"arm_length_mm", false, true, nullptr, &A::length_m, "arm/coupler: c = |A C| along the arm"},
      {"gripper_offset_mm", false, true, nullptr, &A::gripper_offset_m, "arm/coupler: h, the gripper mount face's y"},
      {"roller_radius_mm", false, true, nullptr, &A::roller_radius_m, "arm_with_roller: roller radius r"},
      {"roller_thickness_mm", false, true, nullptr, &A::roller_thickness_m, "arm_with_roller: roller thickness"},
      {"bore_b_offset_mm", false, true, nullptr, &A::bore_b_offset_m, "coupler: x of bore B"},
      {"arm_depth_mm", false, true, nullptr, &A::arm_depth_m, "arm/coupler: arm plate depth (in the plane)"},
      {"arm_thickness_mm", false, true, nullptr, &A::arm_thickness_m, "arm/coupler: arm plate thickness"},
  };
  return keys;
}

pipeline::PartSource source_named(const std::string& name) {
  if (name == "lever") return pipeline::PartSource::Lever;
  if (name == "arm_with_roller") return pipeline::PartSource::ArmWithRoller;
  if (name == "coupler") return pipeline::PartSource::Coupler;
  if (name == "rocker") return pipeline::PartSource::Rocker;
  return pipeline::PartSource::File;
}

loads::BoreLoad bore_load_named(const std::string& name) {
  if (name == "bearing") return loads::BoreLoad::BearingPressure;
  if (name == "contact") return loads::BoreLoad::Contact;
  return loads::BoreLoad::DistributingCoupling;
}

}  // namespace

void add_part_keys(std::vector<KeySpec>& s) {
  const meshes::LeverDimensions lever;
  const meshes::ArmDimensions arm;
  s.push_back({.path = "part", .type = Type::TableArray, .doc = "FE parts: the elastic bodies whose stress is computed over the motion"});
  s.push_back({.path = "part[].body", .type = Type::String,
               .doc = "the body this part belongs to (one part per body): a moving body, or the ground (the frame, "
                      "with held_face)",
               .required = true});
  s.push_back({.path = "part[].held_face", .type = Type::String,
               .doc = "a part of the ground (the frame: a column, a base plate) only: the face set of its foundation, "
                      "held fixed (x, y, z); the ground joints and drives then act on the frame's faces"});
  s.push_back({.path = "part[].source", .type = Type::String, .default_text = "file", .allowed = kSources,
               .doc = "file: a geometry file; lever, arm_with_roller, coupler, rocker: the parametric links of SPEC §1/§2 "
                      "(frames and face sets: docs/meshes.md)"});
  s.push_back({.path = "part[].file", .type = Type::String,
               .doc = "source = \"file\": .step/.stp, .brep, .geo or .msh (4.1), relative to the case file; a STEP/BREP "
                      "of several solids is welded into one part (docs/meshes.md); may be left out when the body's "
                      "[[solid]] entries give files (the part is their union)"});
  s.push_back({.path = "part[].weld_tolerance_mm", .type = Type::Number, .unit = "mm", .to_si = kMm,
               .default_number = meshes::kDefaultWeldToleranceM / kMm, .min = 0, .max = 10,
               .doc = "solids of a welded part closer than this are joined (welded); a larger gap is an error"});
  s.push_back({.path = "part[].length_unit", .type = Type::String, .allowed = {"mm", "m"},
               .doc = "unit of the file's coordinates: needed for .brep/.geo/.msh; a STEP file carries its own (checked if given)"});
  s.push_back({.path = "part[].offset_mm", .type = Type::Array, .unit = "mm",
               .doc = "[x, y] or [x, y, z] of the part's origin in the body frame; z places the part in its own plane "
                      "along the pin axes (a pin between bores at different z is an elastic member, [[pin]]); "
                      "default [0, 0, 0]"});
  s.push_back({.path = "part[].angle_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 0,
               .doc = "rotation of the part's axes in the body frame (about z, the pin axis)"});
  s.push_back({.path = "part[].mass_properties", .type = Type::String, .default_text = "mesh", .allowed = {"mesh", "case"},
               .doc = "mesh: the body's mass, centre of mass and inertia from the mesh and the material; case: the body's "
                      "own mass_kg, com_mm, inertia_kgm2 (both are printed)"});
  for (const auto& d : dimension_keys()) {
    const double def = d.lever ? lever.*(d.lever_field) : arm.*(d.arm_field);
    s.push_back({.path = "part[]." + d.key, .type = Type::Number, .unit = "mm", .to_si = kMm, .min = 0,
                 .max = kMaxPartDimensionMm, .min_exclusive = true,
                 .doc = d.doc + fmt::format(" (default {:g} mm)", def / kMm), .range_note = kPartDimensionNote});
  }
  s.push_back({.path = "solid", .type = Type::TableArray,
               .doc = "a solid of a welded part (docs/meshes.md): its name (element set solid.<name>, seams "
                      "weld.<a>.<b>), its own file or a point inside it, and optionally its own material"});
  s.push_back({.path = "solid[].body", .type = Type::String, .doc = "the body whose [[part]] this solid belongs to", .required = true});
  s.push_back({.path = "solid[].name", .type = Type::String,
               .doc = "the solid's name: letters, digits, '_' and '-'; without file and inside_mm it names a solid of "
                      "the part file (solid1, solid2, ... by position, or its only solid)",
               .required = true});
  s.push_back({.path = "solid[].file", .type = Type::String,
               .doc = "the solid's own STEP/BREP file (one solid), relative to the case file; a .brep in the part's "
                      "length_unit"});
  s.push_back({.path = "solid[].inside_mm", .type = Type::Array, .unit = "mm",
               .doc = "[x, y, z]: a point inside one solid of the [[part]] file, in the file's coordinates, in mm"});
  s.push_back({.path = "solid[].youngs_modulus_mpa", .type = Type::Number, .unit = "MPa", .to_si = 1e6, .min = 1e-3,
               .max = 1e7, .doc = "the solid's Young's modulus; default the case's [material]",
               .range_note = "plausible for a solid: from a soft gel to above diamond"});
  s.push_back({.path = "solid[].poisson_ratio", .type = Type::Number, .min = -1, .max = 0.4999, .min_exclusive = true,
               .doc = "the solid's Poisson's ratio (below 0.5); default the case's [material]"});
  s.push_back({.path = "solid[].density_kg_m3", .type = Type::Number, .unit = "kg/m^3", .min = 1, .max = 1e5,
               .doc = "the solid's density; default the case's [material]", .zero_allowed = true,
               .range_note = "0 for a massless solid, else plausible for a solid: osmium is 22 590 kg/m^3"});
  s.push_back({.path = "face_set", .type = Type::TableArray,
               .doc = "named faces of a part file that has none (STEP from CAD): the surfaces inside a box"});
  s.push_back({.path = "face_set[].body", .type = Type::String, .doc = "body whose part file the box selects from", .required = true});
  s.push_back({.path = "face_set[].name", .type = Type::String, .doc = "name of the face set (used by face keys)", .required = true});
  s.push_back({.path = "face_set[].box_mm", .type = Type::Array, .unit = "mm",
               .doc = "[xmin, ymin, zmin, xmax, ymax, zmax] in the part file's coordinates, in mm", .required = true});
  // Face keys of the tables that act on parts.
  const std::string loads_doc = "coupling (distributing, RBE3-like: exact resultant), bearing (cosine pressure, pins only) or "
                                "contact (a rigid round pin in frictionless contact with the bores, revolute joints only: "
                                "docs/contact.md)";
  s.push_back({.path = "joint[].face_i", .type = Type::String, .doc = "face set of body_i's part the joint acts through"});
  s.push_back({.path = "joint[].face_j", .type = Type::String, .doc = "face set of body_j's part the joint acts through (chain: the roller rim)"});
  s.push_back({.path = "joint[].load", .type = Type::String, .default_text = "coupling",
               .allowed = {"coupling", "bearing", "contact"}, .doc = "how the joint's reaction enters the parts: " + loads_doc});
  s.push_back({.path = "joint[].clearance_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .min = 0, .max = 10,
               .doc = "load = \"contact\": the pin's radial clearance in its bores (default 0: line-to-line)",
               .range_note = "an interference fit (negative) is not supported"});
  s.push_back({.path = "joint[].fit", .type = Type::String,
               .doc = "load = \"contact\": an ISO 286 clearance fit such as \"H7/g6\" instead of clearance_mm: its mean "
                      "radial clearance at each bore's diameter"});
  s.push_back({.path = "joint[].pin_youngs_modulus_mpa", .type = Type::Number, .unit = "MPa", .to_si = kMpa, .min = 1e-3,
               .max = 1e7, .doc = "load = \"contact\": an elastic pin of this modulus (meshed from each bore's diameter "
                                  "less the clearance and its span; docs/contact.md); absent: a rigid pin"});
  s.push_back({.path = "joint[].pin_poisson_ratio", .type = Type::Number, .default_number = 0.3, .min = -0.999, .max = 0.499,
               .doc = "the elastic pin's Poisson ratio (with pin_youngs_modulus_mpa)"});
  for (const char* table : {"motion_drive", "force_drive"}) {
    s.push_back({.path = std::string(table) + "[].face_i", .type = Type::String,
                 .doc = "face set of body_i's part the drive's reaction enters through (an angle drive's torque: the "
                        "motor's mount; a displacement drive's force at point_i and its couple: the actuator's mount)"});
    s.push_back({.path = std::string(table) + "[].face_j", .type = Type::String,
                 .doc = "face set of body_j's part the drive's effort enters through (an angle drive's torque: the shaft "
                        "bore; a displacement drive's force along its axis at point_j: the rod eye)"});
  }
  for (const char* side : {"input", "output"}) {
    const std::string p = std::string("transmission[].") + side + ".";
    s.push_back({.path = p + "face_i", .type = Type::String,
                 .doc = fmt::format("face set of the {} angle's body_i part the reaction moment enters through", side)});
    s.push_back({.path = p + "face_j", .type = Type::String,
                 .doc = fmt::format("face set of the {} angle's body_j part the transmitted moment enters through (the "
                                    "pulley's, sprocket's or gear's bore)", side)});
  }
  s.push_back({.path = "point_mass[].face", .type = Type::String, .doc = "face set of the body's part the mass is mounted on"});
  s.push_back({.path = "spring[].face_i", .type = Type::String, .doc = "face set of body_i's part the spring acts through"});
  s.push_back({.path = "spring[].face_j", .type = Type::String, .doc = "face set of body_j's part the spring acts through"});
  s.push_back({.path = "point_force[].face", .type = Type::String, .doc = "face set of the body's part the force acts through"});
}

namespace {

// A contact joint's clearance (clearance_mm, or a fit), checked against the
// joint's type and the other loads.
loads::ContactFit read_pin_fit(const CaseFile& c, std::size_t k, const mech::Joint& j, loads::BoreLoad load) {
  const bool clearance = c.has("joint[].clearance_mm", k), fit = c.has("joint[].fit", k);
  const bool elastic = c.has("joint[].pin_youngs_modulus_mpa", k);
  require(elastic || !c.has("joint[].pin_poisson_ratio", k), "{}: joint '{}': a pin's Poisson ratio needs its "
          "pin_youngs_modulus_mpa", c.where("joint[].pin_poisson_ratio", k), j.name);
  if (load != loads::BoreLoad::Contact) {
    require(!clearance && !fit && !elastic, "{}: joint '{}': a clearance, fit or elastic pin needs load = \"contact\"",
            c.where(clearance ? "joint[].clearance_mm" : fit ? "joint[].fit" : "joint[].pin_youngs_modulus_mpa", k),
            j.name);
    return {};
  }
  require(mech::joint_facts(j.type).bearing_pressure, "{} = \"contact\": joint '{}' is {}; contact needs a revolute (pin) joint",
          c.where("joint[].load", k), j.name, c.text_value("joint[].type", k));
  require(!(clearance && fit), "{}: joint '{}': give clearance_mm or fit, not both", c.where("joint[].fit", k), j.name);
  loads::ContactFit out;
  if (c.has("joint[].pin_youngs_modulus_mpa", k)) {
    fem::IsotropicMaterial pin;
    pin.name = "pin of joint '" + j.name + "'";
    pin.youngs_modulus_pa = c.number("joint[].pin_youngs_modulus_mpa", k);
    pin.poisson_ratio = c.number("joint[].pin_poisson_ratio", k);
    out.pin_material = pin;
  }
  if (clearance) out.clearance_m = c.number("joint[].clearance_mm", k);
  if (fit) {
    out.fit = c.text_value("joint[].fit", k);
    try {
      loads::check_fit(out.fit);
    } catch (const Error& e) {
      fail("{}: {}", c.where("joint[].fit", k), e.what());
    }
  }
  return out;
}

}  // namespace

std::vector<pipeline::PartSpec> read_parts(const CaseFile& c, const mech::MultibodyModel& model) {
  std::vector<pipeline::PartSpec> parts;
  std::map<std::string, std::size_t> part_of_body;
  std::set<std::string> bodies_with_solid_files;  // a [[part]] of these may leave out its file
  for (std::size_t k = 0; k < c.count("solid"); ++k)
    if (c.has("solid[].file", k)) bodies_with_solid_files.insert(c.text_value("solid[].body", k));
  auto body_named = [&](const std::string& key, std::size_t k) -> const mech::Body& {
    const std::string name = c.text_value(key, k);
    for (const auto& b : model.bodies)
      if (b.name == name) return b;
    std::string names;
    for (const auto& b : model.bodies) names += (names.empty() ? "" : ", ") + b.name;
    fail("{} = \"{}\": no body of that name (bodies: {})", c.where(key, k), name, names);
  };
  for (std::size_t k = 0; k < c.count("part"); ++k) {
    const mech::Body& body = body_named("part[].body", k);
    // A part of the ground is the frame, held on its foundation; a moving
    // part has no foundation (a 3-2-1 support and its rigid motion hold it).
    require(!body.fixed || c.has("part[].held_face", k),
            "{} = \"{}\": a part of the ground (the frame) needs held_face, the face set of its foundation",
            c.where("part[].body", k), body.name);
    require(body.fixed || !c.has("part[].held_face", k),
            "{} = \"{}\": held_face is for a part of the ground (the frame); body '{}' moves", c.where("part[].held_face", k),
            c.has("part[].held_face", k) ? c.text_value("part[].held_face", k) : std::string(), body.name);
    require(!part_of_body.contains(body.name), "{} = \"{}\": this body already has a part (one part per body)",
            c.where("part[].body", k), body.name);
    pipeline::PartSpec spec;
    spec.attachments.body = body.name;
    const std::string source = c.text_value("part[].source", k);
    spec.source = source_named(source);
    const bool lever_like = spec.source == pipeline::PartSource::Lever || spec.source == pipeline::PartSource::Rocker;
    const bool arm_like = spec.source == pipeline::PartSource::ArmWithRoller || spec.source == pipeline::PartSource::Coupler;
    spec.arm.with_roller = spec.source != pipeline::PartSource::Coupler;
    for (const auto& d : dimension_keys()) {
      const std::string key = "part[]." + d.key;
      if (!c.has(key, k)) continue;
      require((lever_like && d.lever) || (arm_like && d.arm), "{}: not a dimension of a \"{}\" part", c.where(key, k), source);
      if (lever_like) spec.lever.*(d.lever_field) = c.number(key, k);
      else spec.arm.*(d.arm_field) = c.number(key, k);
    }
    if (spec.source == pipeline::PartSource::File) {
      spec.file_options.weld_tolerance_m = c.number("part[].weld_tolerance_mm", k);
      spec.file_options.case_folder = c.path().parent_path().empty() ? "." : c.path().parent_path();
      if (c.has("part[].length_unit", k)) spec.file_options.length_unit_m = c.text_value("part[].length_unit", k) == "mm" ? kMm : 1.0;
      // Without a file the part is the union of its [[solid]] files.
      const bool union_of_solids = !c.has("part[].file", k) && bodies_with_solid_files.contains(body.name);
      require(c.has("part[].file", k) || union_of_solids,
              "{}: source = \"file\" needs 'file' (or [[solid]] entries with files)", c.where("part[].body", k));
      if (union_of_solids) spec.label = fmt::format("part '{}' (its [[solid]] files)", body.name);
    }
    if (spec.source == pipeline::PartSource::File && c.has("part[].file", k)) {
      std::filesystem::path file = c.text_value("part[].file", k);
      if (file.is_relative()) file = c.path().parent_path() / file;
      const std::string problem = input_file_problem(file);
      require(problem.empty(), "{} = \"{}\": {} ({})", c.where("part[].file", k), c.text_value("part[].file", k),
              problem, file.string());
      spec.file = file;
      spec.label = fmt::format("part '{}' ({})", body.name, c.text_value("part[].file", k));
    } else if (spec.source != pipeline::PartSource::File) {
      require(!c.has("part[].file", k), "{}: a \"{}\" part is parametric: no file", c.where("part[].file", k), source);
      spec.label = fmt::format("part '{}' ({})", body.name, source);
    }
    if (c.has("part[].offset_mm", k)) {
      const std::vector<double> offset = read_numbers(c, "part[].offset_mm", k, kMm);
      require(offset.size() == 2 || offset.size() == 3,
              "{} must be [x, y] or [x, y, z] (z: along the pin axes, the part's own plane), got {} numbers",
              c.where("part[].offset_mm", k), offset.size());
      spec.placement.offset_m = {offset[0], offset[1], offset.size() == 3 ? offset[2] : 0.0};
    }
    spec.placement.angle_rad = c.number("part[].angle_deg", k);
    spec.mass_from_mesh = c.text_value("part[].mass_properties", k) == "mesh";
    if (body.fixed) spec.held_face = c.text_value("part[].held_face", k);
    part_of_body[body.name] = parts.size();
    parts.push_back(std::move(spec));
  }
  for (std::size_t k = 0; k < c.count("face_set"); ++k) {
    const std::string body = c.text_value("face_set[].body", k);
    require(part_of_body.contains(body), "{} = \"{}\": that body has no [[part]]", c.where("face_set[].body", k), body);
    pipeline::PartSpec& spec = parts[part_of_body[body]];
    require(spec.source == pipeline::PartSource::File, "{}: face sets by box are for part files; the \"{}\" part has its own",
            c.where("face_set[].body", k), pipeline::name_of(spec.source));
    const std::vector<double> box = read_numbers(c, "face_set[].box_mm", k, kMm);
    require(box.size() == 6, "{} must be [xmin, ymin, zmin, xmax, ymax, zmax], got {} numbers", c.where("face_set[].box_mm", k),
            box.size());
    spec.file_options.face_sets.push_back({c.text_value("face_set[].name", k), {box[0], box[1], box[2]}, {box[3], box[4], box[5]}});
  }

  // The solids of welded parts: names, files or points, own materials (the
  // part file's solids are matched when it is meshed).
  for (std::size_t k = 0; k < c.count("solid"); ++k) {
    const std::string body = c.text_value("solid[].body", k);
    require(part_of_body.contains(body), "{} = \"{}\": that body has no [[part]] for the solid to belong to",
            c.where("solid[].body", k), body);
    pipeline::PartSpec& spec = parts[part_of_body[body]];
    require(spec.source == pipeline::PartSource::File, "{}: solids are for part files; the \"{}\" part is parametric",
            c.where("solid[].body", k), pipeline::name_of(spec.source));
    meshes::PartSolid solid;
    solid.name = c.text_value("solid[].name", k);
    require(!c.has("solid[].file", k) || !c.has("solid[].inside_mm", k),
            "{}: give file (the solid's own file) or inside_mm (a point inside a solid of the part file), not both",
            c.where("solid[].inside_mm", k));
    if (c.has("solid[].file", k)) {
      std::filesystem::path file = c.text_value("solid[].file", k);
      if (file.is_relative()) file = c.path().parent_path() / file;
      const std::string problem = input_file_problem(file);
      require(problem.empty(), "{} = \"{}\": {} ({})", c.where("solid[].file", k), c.text_value("solid[].file", k),
              problem, file.string());
      solid.file = file;
    }
    if (c.has("solid[].inside_mm", k)) {
      require(!spec.file.empty(), "{}: the part of body '{}' has no file for the point to be in",
              c.where("solid[].inside_mm", k), body);
      const std::vector<double> point = read_numbers(c, "solid[].inside_mm", k, kMm);
      require(point.size() == 3, "{} must be [x, y, z], got {} numbers", c.where("solid[].inside_mm", k), point.size());
      solid.inside_m = Eigen::Vector3d(point[0], point[1], point[2]);
    }
    pipeline::SolidMaterial material{solid.name, {}, {}, {}};
    if (c.has("solid[].youngs_modulus_mpa", k)) material.youngs_modulus_pa = c.number("solid[].youngs_modulus_mpa", k);
    if (c.has("solid[].poisson_ratio", k)) material.poisson_ratio = c.number("solid[].poisson_ratio", k);
    if (c.has("solid[].density_kg_m3", k)) material.density_kg_m3 = c.number("solid[].density_kg_m3", k);
    if (material.youngs_modulus_pa || material.poisson_ratio || material.density_kg_m3)
      spec.solid_materials.push_back(material);
    spec.file_options.solids.push_back(std::move(solid));
  }

  // Attachments: every table that acts on a body with a part names its face.
  auto part_for = [&](const std::string& body) -> pipeline::PartSpec* {
    const auto it = part_of_body.find(body);
    return it == part_of_body.end() ? nullptr : &parts[it->second];
  };
  // Returns the face for body `body` from key `key` of element k; empty if the body has no part.
  auto face = [&](const std::string& key, std::size_t k, const std::string& body, const std::string& what) -> std::string {
    pipeline::PartSpec* p = part_for(body);
    if (!p) {
      require(!c.has(key, k), "{}: body '{}' has no [[part]] to act through", c.where(key, k), body);
      return {};
    }
    require(c.has(key, k), "{}: {} acts on body '{}', which has a part: give '{}' (a face set of the part)", c.where(key.substr(0, key.find('.')) + ".name", k),
            what, body, key.substr(key.find('.') + 1));
    return c.text_value(key, k);
  };
  for (std::size_t k = 0; k < c.count("joint"); ++k) {
    const mech::Joint& j = model.joints.at(k);
    const loads::BoreLoad load = bore_load_named(c.text_value("joint[].load", k));
    const std::string what = fmt::format("joint '{}'", j.name);
    const std::string fi = face("joint[].face_i", k, j.body_i, what), fj = face("joint[].face_j", k, j.body_j, what);
    const loads::BoreLoad used = mech::joint_facts(j.type).always_distributing ? loads::BoreLoad::DistributingCoupling : load;
    const loads::ContactFit pin = read_pin_fit(c, k, j, load);
    if (!fi.empty())
      part_for(j.body_i)->attachments.joints.push_back({j.name, fi, used, pin.clearance_m, pin.fit, pin.pin_material});
    if (!fj.empty())
      part_for(j.body_j)->attachments.joints.push_back({j.name, fj, used, pin.clearance_m, pin.fit, pin.pin_material});
  }
  auto drives = [&](const char* table, const auto& list) {
    for (std::size_t k = 0; k < c.count(table); ++k) {
      const auto& d = list.at(k);
      const std::string p = std::string(table) + "[].";
      const std::string what = fmt::format("drive '{}'", d.name);
      const std::string fi = face(p + "face_i", k, d.coordinate.body_i, what), fj = face(p + "face_j", k, d.coordinate.body_j, what);
      if (!fi.empty()) part_for(d.coordinate.body_i)->attachments.drives.push_back({d.name, fi});
      if (!fj.empty()) part_for(d.coordinate.body_j)->attachments.drives.push_back({d.name, fj});
    }
  };
  drives("motion_drive", model.motion_drives);
  drives("force_drive", model.force_drives);
  for (std::size_t k = 0; k < c.count("transmission"); ++k) {
    const mech::Transmission& t = model.transmissions.at(k);
    const std::string what = fmt::format("transmission '{}'", t.name);
    for (const auto side : {loads::TransmissionSide::Input, loads::TransmissionSide::Output}) {
      const bool input = side == loads::TransmissionSide::Input;
      const mech::RelativeCoordinate& rc = input ? t.input : t.output;
      const std::string p = input ? "transmission[].input." : "transmission[].output.";
      const std::string fi = face(p + "face_i", k, rc.body_i, what), fj = face(p + "face_j", k, rc.body_j, what);
      if (!fi.empty()) part_for(rc.body_i)->attachments.transmissions.push_back({t.name, side, fi});
      if (!fj.empty()) part_for(rc.body_j)->attachments.transmissions.push_back({t.name, side, fj});
    }
  }
  for (std::size_t k = 0; k < c.count("point_mass"); ++k) {
    const std::string body = c.text_value("point_mass[].body", k), name = c.text_value("point_mass[].name", k);
    const std::string f = face("point_mass[].face", k, body, fmt::format("point mass '{}'", name));
    if (!f.empty()) part_for(body)->attachments.point_masses.push_back({name, f});
  }
  for (std::size_t k = 0; k < c.count("spring"); ++k) {
    const mech::Spring& sp = model.springs.at(k);
    const std::string what = fmt::format("spring '{}'", sp.name);
    const std::string fi = face("spring[].face_i", k, sp.body_i, what), fj = face("spring[].face_j", k, sp.body_j, what);
    if (!fi.empty()) part_for(sp.body_i)->attachments.springs.push_back({sp.name, fi});
    if (!fj.empty()) part_for(sp.body_j)->attachments.springs.push_back({sp.name, fj});
  }
  for (std::size_t k = 0; k < c.count("point_force"); ++k) {
    const mech::PointForce& pf = model.point_forces.at(k);
    const std::string f = face("point_force[].face", k, pf.body, fmt::format("point force '{}'", pf.name));
    if (!f.empty()) part_for(pf.body)->attachments.point_forces.push_back({pf.name, f});
  }
  // The frame carries the ground joints: without one it would be loaded by
  // nothing but its weight and add nothing to the mechanism.
  for (std::size_t k = 0; k < parts.size(); ++k)
    require(parts[k].held_face.empty() || !parts[k].attachments.joints.empty(),
            "{} = \"{}\": no joint of the mechanism acts on the ground's part (the frame): the ground joints must "
            "join the ground body '{}'",
            c.where("part[].body", k), parts[k].attachments.body, parts[k].attachments.body);
  return parts;
}

}  // namespace kinetofem::app
