#include "kinetofem/app/assembly_keys.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/mechanisms/multibody/joint_traits.hpp"

namespace kinetofem::app {

namespace {

using Type = KeySpec::Type;
constexpr long kDefaultStrands = 1;  // a simplex chain

// How the elastic assembly ties the bodies at joint k (its type's row in the joint table).
mech::AssemblyTie assembly_tie_of(const CaseFile& c, std::size_t k) {
  const std::string type = c.text_value("joint[].type", k);
  const auto named = mech::joint_type_named(type);
  require(named.has_value(), "{} = \"{}\": unknown joint type", c.where("joint[].type", k), type);
  return mech::joint_facts(*named).assembly_tie;
}
// A gear pair's mesh stiffness: ISO 6336-1 method B's mean c_gamma_alpha for
// solid steel spur gears, 20 N/(mm um); the pressure angle of ISO 53's
// basic rack, 20 deg, gives the base radius.
constexpr double kDefaultMeshStiffnessNPerMmUm = 20.0;
constexpr double kMeshStiffnessToSi = 1e9;  // N/(mm um) -> N/m^2
constexpr double kPressureAngleRad = 20.0 * std::numbers::pi / 180.0;
// EA is a stiffness in N, not a force: a steel bar of 100 cm^2 has 2e9 N.
constexpr double kMaxEaN = 1e12;
constexpr const char* kEaNote = "a plausible axial stiffness EA";

void add_common(std::vector<KeySpec>& s, bool enabled_by_default, const char* enabled_doc) {
  s.push_back({.path = "assembly.enabled", .type = Type::Boolean, .default_number = enabled_by_default ? 1.0 : 0.0,
               .doc = enabled_doc});
  s.push_back({.path = "assembly.coupling", .type = Type::String, .default_text = "distributing",
               .allowed = {"distributing", "rigid_bore"},
               .doc = "how a joint's pin holds its bore: 'distributing' (RBE3-like, the bore deforms freely) or "
                      "'rigid_bore' (kinematic: the bore moves rigidly with the pin)"});
}

structure::BoreCoupling read_coupling(const CaseFile& c) {
  return c.text_value("assembly.coupling") == "rigid_bore" ? structure::BoreCoupling::RigidBore
                                                           : structure::BoreCoupling::Distributing;
}

double chain_ea(const CaseFile& c, const std::string& ea_key, const std::string& strands_key, std::size_t k) {
  const double ea = c.number(ea_key, k);
  require(std::isfinite(ea), "{} = {}: the chain's axial stiffness must be a finite number of N", c.where(ea_key, k), ea);
  return ea * double(c.integer(strands_key, k));
}

// A transmission's member in the assembly: its torsional stiffness on the
// output coordinate, given or from the belt's spans or the gear's mesh.
structure::TransmissionMember read_transmission_member(const CaseFile& c, std::size_t k) {
  const std::string p = "transmission[].";
  structure::TransmissionMember m;
  m.transmission = c.text_value(p + "name", k);
  const bool belt = c.text_value(p + "kind", k) == "belt";
  const double r = c.number(p + "radius_mm", k);
  for (const char* key : {"belt_ea_n", "span_length_mm", "preload_n"})
    require(belt || !c.departs_from_default(p + key, k), "{}: transmission '{}' is a gear: this key is a belt's", c.where(p + key, k),
            m.transmission);
  for (const char* key : {"face_width_mm", "mesh_stiffness_n_per_mm_um"})
    require(!belt || !c.departs_from_default(p + key, k), "{}: transmission '{}' is a belt: this key is a gear's", c.where(p + key, k),
            m.transmission);
  if (belt) {
    m.radius_m = r;
    m.preload_n = c.number(p + "preload_n", k);
  }
  if (c.has(p + "stiffness_n_m_per_rad", k)) {
    m.torsional_stiffness_nm_per_rad = c.number(p + "stiffness_n_m_per_rad", k);
    require(std::isfinite(m.torsional_stiffness_nm_per_rad), "{} = {}: must be a finite number of N*m/rad",
            c.where(p + "stiffness_n_m_per_rad", k), m.torsional_stiffness_nm_per_rad);
    return m;
  }
  if (belt) {
    require(c.has(p + "span_length_mm", k),
            "{}: belt '{}' in the elastic assembly needs span_length_mm (its spans' free length) or "
            "stiffness_n_m_per_rad",
            c.where(p + "name", k), m.transmission);
    const double ea = c.number(p + "belt_ea_n", k), b = c.number(p + "span_length_mm", k);
    require(std::isfinite(ea), "{} = {}: must be a finite number of N", c.where(p + "belt_ea_n", k), ea);
    const double spans = m.preload_n > 0 ? 2.0 : 1.0;  // preloaded: both spans carry
    m.torsional_stiffness_nm_per_rad = spans * ea * r * r / b;
  } else {
    require(c.has(p + "face_width_mm", k),
            "{}: gear '{}' in the elastic assembly needs face_width_mm (its mesh's face width) or "
            "stiffness_n_m_per_rad",
            c.where(p + "name", k), m.transmission);
    const double rb = r * std::cos(kPressureAngleRad);
    m.torsional_stiffness_nm_per_rad =
        c.number(p + "mesh_stiffness_n_per_mm_um", k) * kMeshStiffnessToSi * c.number(p + "face_width_mm", k) * rb * rb;
  }
  return m;
}

}  // namespace

void add_manipulator_assembly_keys(std::vector<KeySpec>& s) {
  add_common(s, true,
             "also solve the manipulator as one elastic structure held by its frame: total deformation, the gripper "
             "point H's deflection, its split and compliance");
  s.push_back({.path = "assembly.chain_ea_per_strand_n", .type = Type::Number, .unit = "N",
               .default_number = mech::manipulator::kDefaultChain.ea_per_strand_n, .min = 0, .max = kMaxEaN, .min_exclusive = true,
               .doc = "lever-chain: axial stiffness EA of one chain strand (default: ISO 606 08B-1, see the case README)",
               .range_note = kEaNote});
  s.push_back({.path = "assembly.chain_strands", .type = Type::Integer, .default_number = double(kDefaultStrands), .min = 1, .max = 3,
               .doc = "lever-chain: strands of the chain (simplex 1, duplex 2, triplex 3); EA = strands x per strand"});
  s.push_back({.path = "assembly.drive_stiffness_n_m_per_rad", .type = Type::Number, .unit = "N*m/rad", .min = 0,
               .min_exclusive = true,
               .doc = "torsional stiffness of the lever's drive train (motor, gearbox, coupling); absent: rigid"});
}

std::optional<structure::AssemblyOptions> read_manipulator_assembly(const CaseFile& c, bool with_chain) {
  namespace names = mech::manipulator;
  if (!c.boolean("assembly.enabled")) return std::nullopt;
  require(c.text_value("loads.bore_load") != "contact" || c.text_value("assembly.coupling") != "rigid_bore",
          "{} = \"rigid_bore\": pins in contact need the distributing couplings (rigid_bore presses every pin into "
          "its bore); loads.bore_load = \"contact\" is set",
          c.where("assembly.coupling"));
  require(!c.has("loads.pin_youngs_modulus_mpa"),
          "{}: elastic pins in contact are modelled in the per-part analysis only (the elastic assembly's pins in "
          "contact are rigid in their bores): leave the pins rigid, or set assembly.enabled = false",
          c.where("loads.pin_youngs_modulus_mpa"));
  structure::AssemblyOptions o;
  o.coupling = read_coupling(c);
  if (with_chain) {
    o.chains.push_back({names::kChain, chain_ea(c, "assembly.chain_ea_per_strand_n", "assembly.chain_strands", 0)});
  } else {
    // Keys at their defaults (as `kinetofem case --template` writes them) say
    // nothing; another value would be silently unused.
    const auto unused = [&](const char* key, double at_default) {
      require(!c.has(key) || c.number(key) == at_default,
              "{}: the lever manipulator has no chain (this key is for mechanism.type = \"lever_chain\")", c.where(key));
    };
    unused("assembly.chain_ea_per_strand_n", names::kDefaultChain.ea_per_strand_n);
    unused("assembly.chain_strands", double(kDefaultStrands));
  }
  if (c.has("assembly.drive_stiffness_n_m_per_rad")) {
    const double k = c.number("assembly.drive_stiffness_n_m_per_rad");
    require(std::isfinite(k), "{} = {}: the drive's stiffness must be a finite number of N*m/rad (leave the key out "
            "for a rigid drive)", c.where("assembly.drive_stiffness_n_m_per_rad"), k);
    o.drives.push_back({names::kLeverDrive, k});
  }
  o.points.push_back({names::kPointH, names::kArm, names::kPointH, names::kGripperMount});
  return o;
}

void add_linkage_assembly_keys(std::vector<KeySpec>& s) {
  add_common(s, false,
             "also solve the linkage as one elastic structure held by the ground (needs [[part]]s; revolute, "
             "prismatic, fixed and chain joints; angle and displacement drives)");
  s.push_back({.path = "joint[].ea_per_strand_n", .type = Type::Number, .unit = "N", .min = 0, .max = kMaxEaN,
               .min_exclusive = true,
               .doc = "chain, elastic assembly: axial stiffness EA of one strand (required when the assembly is on)",
               .range_note = kEaNote});
  s.push_back({.path = "joint[].strands", .type = Type::Integer, .default_number = double(kDefaultStrands), .min = 1, .max = 3,
               .doc = "chain, elastic assembly: number of strands; EA = strands x per strand"});
  s.push_back({.path = "motion_drive[].stiffness_n_m_per_rad", .type = Type::Number, .unit = "N*m/rad", .min = 0,
               .min_exclusive = true,
               .doc = "angle drive, elastic assembly: torsional stiffness of the drive train; absent: rigid"});
  s.push_back({.path = "motion_drive[].stiffness_n_per_m", .type = Type::Number, .unit = "N/m", .min = 0,
               .min_exclusive = true,
               .doc = "displacement drive, elastic assembly: axial stiffness of the drive train (screw, cylinder, "
                      "belt); absent: rigid"});
  s.push_back({.path = "transmission[].stiffness_n_m_per_rad", .type = Type::Number, .unit = "N*m/rad", .min = 0,
               .min_exclusive = true,
               .doc = "elastic assembly: torsional stiffness of the transmission on its output coordinate; default: "
                      "from belt_ea_n and span_length_mm (a belt), face_width_mm (a gear)"});
  s.push_back({.path = "transmission[].belt_ea_n", .type = Type::Number, .unit = "N",
               .default_number = mech::manipulator::kDefaultChain.ea_per_strand_n, .min = 0, .max = kMaxEaN,
               .min_exclusive = true,
               .doc = fmt::format("belt, elastic assembly: axial stiffness EA of the belt or chain (default: a {} roller "
                                  "chain, docs/transmissions.md)",
                                  mech::manipulator::kDefaultChain.designation),
               .range_note = kEaNote});
  s.push_back({.path = "transmission[].span_length_mm", .type = Type::Number, .unit = "mm", .to_si = units::kMm, .min = 0,
               .max = 1e6, .min_exclusive = true,
               .doc = "belt, elastic assembly: free length of each span (about the pulleys' centre distance); "
                      "required for a belt in the assembly unless stiffness_n_m_per_rad is given"});
  s.push_back({.path = "transmission[].preload_n", .type = Type::Number, .unit = "N", .default_number = 0, .min = 0,
               .max = 1e9,
               .doc = "belt, elastic assembly: the spans' preload; > 0: both spans carry (k = 2 EA r^2 / b) and a span "
                      "that would go slack is an error; 0: one span carries (k = EA r^2 / b, a chain)",
               .zero_allowed = true});
  s.push_back({.path = "transmission[].face_width_mm", .type = Type::Number, .unit = "mm", .to_si = units::kMm, .min = 0,
               .max = 1e4, .min_exclusive = true,
               .doc = "gear, elastic assembly: face width b of the mesh; required for a gear in the assembly unless "
                      "stiffness_n_m_per_rad is given"});
  s.push_back({.path = "transmission[].mesh_stiffness_n_per_mm_um", .type = Type::Number, .unit = "N/(mm*um)",
               .default_number = kDefaultMeshStiffnessNPerMmUm, .min = 0, .max = 1e3, .min_exclusive = true,
               .doc = "gear, elastic assembly: mesh stiffness per face width c_gamma (default: ISO 6336-1 method B's "
                      "mean for solid steel spur gears); k = c_gamma b (r cos 20 deg)^2"});
  s.push_back({.path = "slide", .type = Type::TableArray,
               .doc = "elastic assembly: the bearing of a prismatic joint's slider on an elastic guide (body_i with a "
                      "part); joints not listed get the defaults"});
  s.push_back({.path = "slide[].joint", .type = Type::String, .doc = "the prismatic joint", .required = true});
  s.push_back({.path = "slide[].contact_length_mm", .type = Type::Number, .unit = "mm", .to_si = units::kMm, .min = 0,
               .max = 1e5, .min_exclusive = true,
               .doc = "length of the slider's bearing on the guide: the load spreads over a window this long on the "
                      "guide's face set; default: the slider's face set's extent along the axis (a slider with a part)"});
  s.push_back({.path = "slide[].station_spacing_mm", .type = Type::Number, .unit = "mm", .to_si = units::kMm, .min = 0,
               .max = 1e5, .min_exclusive = true,
               .doc = "distance between the guide's stations (windows) along the axis, between which the slider's "
                      "position is interpolated; default: a quarter of the contact length"});
  s.push_back({.path = "assembly_point", .type = Type::TableArray,
               .doc = "points whose elastic displacement, split and compliance the assembly reports (e.g. a gripper point)"});
  s.push_back({.path = "assembly_point[].name", .type = Type::String, .doc = "name (histories assembly.point.<name>.*)", .required = true});
  s.push_back({.path = "assembly_point[].body", .type = Type::String, .doc = "moving body", .required = true});
  s.push_back({.path = "assembly_point[].point", .type = Type::String, .default_text = "origin", .doc = "point of the body"});
  s.push_back({.path = "assembly_point[].face", .type = Type::String,
               .doc = "body with a part: the face set whose distributing coupling carries the point"});
  // The pin of a revolute joint whose bores sit at different z (parts in
  // their own planes): a Timoshenko beam between the bores (docs/elastic_assembly.md).
  s.push_back({.path = "pin", .type = Type::TableArray,
               .doc = "elastic assembly: the pin of a revolute joint whose bores sit at different z (an elastic "
                      "beam between them); joints not listed get the defaults"});
  s.push_back({.path = "pin[].joint", .type = Type::String, .doc = "the revolute joint the pin belongs to", .required = true});
  s.push_back({.path = "pin[].diameter_mm", .type = Type::Number, .unit = "mm", .to_si = units::kMm, .min = 0, .max = 1e4,
               .min_exclusive = true,
               .doc = "pin diameter; default: the diameter of the smaller of its bores (measured from the face sets); "
                      "no larger than a bore it passes through"});
  s.push_back({.path = "pin[].youngs_modulus_mpa", .type = Type::Number, .unit = "MPa", .to_si = units::kMpa, .min = 1e-3,
               .max = 1e7, .doc = "pin material's Young's modulus; default: the case's [material]",
               .range_note = "plausible for a solid: from a soft gel to above diamond"});
  s.push_back({.path = "pin[].poisson_ratio", .type = Type::Number, .min = -1, .max = 0.4999, .min_exclusive = true,
               .doc = "pin material's Poisson's ratio; default: the case's [material]"});
}

std::optional<structure::AssemblyOptions> read_linkage_assembly(const CaseFile& c, const mech::MultibodyModel& model,
                                                                 const std::vector<std::string>& bodies_with_parts) {
  const bool enabled = c.boolean("assembly.enabled");
  // Stiffness keys without an assembly, or on the wrong joint or drive, are
  // mistakes a user wants to hear about.
  for (std::size_t k = 0; k < c.count("joint"); ++k) {
    const std::string type = c.text_value("joint[].type", k);
    for (const char* key : {"joint[].ea_per_strand_n", "joint[].strands"})
      if (c.has(key, k)) {
        require(assembly_tie_of(c, k) == mech::AssemblyTie::ChainSpring, "{}: only a chain joint has an axial stiffness (this joint is {})", c.where(key, k), type);
        require(enabled, "{}: set assembly.enabled = true to use it (the chain's stiffness only enters the elastic assembly)",
                c.where(key, k));
      }
  }
  for (std::size_t k = 0; k < c.count("motion_drive"); ++k)
    for (const auto& [key, coordinate] : {std::pair{"motion_drive[].stiffness_n_m_per_rad", "angle"},
                                         std::pair{"motion_drive[].stiffness_n_per_m", "displacement"}})
      if (c.has(key, k)) {
        require(c.text_value("motion_drive[].coordinate", k) == coordinate,
                "{}: drive '{}' drives {} {}: its stiffness is {}", c.where(key, k), c.text_value("motion_drive[].name", k),
                c.text_value("motion_drive[].coordinate", k) == "angle" ? "an" : "a",
                c.text_value("motion_drive[].coordinate", k),
                coordinate == std::string("angle") ? "stiffness_n_per_m (N/m)" : "stiffness_n_m_per_rad (N*m/rad)");
        require(enabled, "{}: set assembly.enabled = true to use it (the drive's stiffness only enters the elastic assembly)",
                c.where(key, k));
      }
  for (std::size_t k = 0; k < c.count("transmission"); ++k)
    for (const char* key : {"stiffness_n_m_per_rad", "belt_ea_n", "span_length_mm", "preload_n", "face_width_mm",
                            "mesh_stiffness_n_per_mm_um"})
      require(enabled || !c.departs_from_default(std::string("transmission[].") + key, k),
              "{}: set assembly.enabled = true to use it (the transmission's stiffness only enters the elastic assembly)",
              c.where(std::string("transmission[].") + key, k));
  // A [[slide]] names a prismatic joint of the linkage, once.
  for (std::size_t k = 0; k < c.count("slide"); ++k) {
    require(enabled, "{}: [[slide]] needs assembly.enabled = true (it shapes the elastic assembly's guide)",
            c.where("slide[].joint", k));
    const std::string name = c.text_value("slide[].joint", k);
    const auto joint = std::find_if(model.joints.begin(), model.joints.end(), [&](const mech::Joint& j) { return j.name == name; });
    if (joint == model.joints.end() || joint->type != mech::JointType::Prismatic) {
      std::string names;
      for (const auto& j : model.joints)
        if (j.type == mech::JointType::Prismatic) names += (names.empty() ? "" : ", ") + j.name;
      fail("{} = \"{}\": no prismatic joint of that name (prismatic joints: {})", c.where("slide[].joint", k), name,
           names.empty() ? "none" : names);
    }
    require(std::find(bodies_with_parts.begin(), bodies_with_parts.end(), joint->body_i) != bodies_with_parts.end(),
            "{} = \"{}\": its guide (body_i '{}') has no part: a [[slide]] is for an elastic guide", c.where("slide[].joint", k),
            name, joint->body_i);
    for (std::size_t l = 0; l < k; ++l)
      require(c.text_value("slide[].joint", l) != name, "{} = \"{}\": that joint has a [[slide]] already",
              c.where("slide[].joint", k), name);
  }
  // A [[pin]] names a revolute joint of the linkage, once.
  for (std::size_t k = 0; k < c.count("pin"); ++k) {
    const std::string name = c.text_value("pin[].joint", k);
    const auto joint = std::find_if(model.joints.begin(), model.joints.end(), [&](const mech::Joint& j) { return j.name == name; });
    if (joint == model.joints.end() || joint->type != mech::JointType::Revolute) {
      std::string names;
      for (const auto& j : model.joints)
        if (j.type == mech::JointType::Revolute) names += (names.empty() ? "" : ", ") + j.name;
      fail("{} = \"{}\": no revolute joint of that name (a pin belongs to a revolute joint; revolute joints: {})",
           c.where("pin[].joint", k), name, names.empty() ? "none" : names);
    }
    for (std::size_t l = 0; l < k; ++l)
      require(c.text_value("pin[].joint", l) != name, "{} = \"{}\": that joint has a [[pin]] already",
              c.where("pin[].joint", k), name);
  }
  if (!enabled) {
    require(c.count("assembly_point") == 0, "{}: [[assembly_point]] needs assembly.enabled = true", c.where("assembly_point[].name", 0));
    require(c.count("pin") == 0, "{}: [[pin]] needs assembly.enabled = true (a pin is an elastic member of the assembly)",
            c.where("pin[].joint", 0));
    return std::nullopt;
  }
  require(!bodies_with_parts.empty(),
          "{} = true, but no body has a [[part]]: the elastic assembly needs at least one FE part",
          c.where("assembly.enabled"));
  // What the elastic model does not hold, said here with its key and line
  // rather than after the motion and the parts' stress (ElasticAssembly checks
  // it again for other callers).
  for (std::size_t k = 0; k < c.count("joint"); ++k)
    require(assembly_tie_of(c, k) != mech::AssemblyTie::None,
            "{} = \"{}\": joint '{}': the elastic assembly models {} joints only "
            "(leave assembly.enabled = false for this linkage)",
            c.where("joint[].type", k), c.text_value("joint[].type", k), c.text_value("joint[].name", k),
            mech::joint_type_list([](const mech::JointFacts& f) { return f.assembly_tie != mech::AssemblyTie::None; }));
  for (std::size_t k = 0; k < c.count("joint"); ++k)
    require(c.text_value("joint[].load", k) != "contact" || c.text_value("assembly.coupling") != "rigid_bore",
            "{} = \"rigid_bore\": pins in contact need the distributing couplings (rigid_bore presses every pin "
            "into its bore); joint '{}' has load = \"contact\"",
            c.where("assembly.coupling"), c.text_value("joint[].name", k));
  for (std::size_t k = 0; k < c.count("joint"); ++k)
    require(!c.has("joint[].pin_youngs_modulus_mpa", k),
            "{}: joint '{}': elastic pins in contact are modelled in the per-part analysis only (the elastic "
            "assembly's pins in contact are rigid in their bores): leave the pin rigid, or set assembly.enabled = false",
            c.where("joint[].pin_youngs_modulus_mpa", k), c.text_value("joint[].name", k));
  structure::AssemblyOptions o;
  o.coupling = read_coupling(c);
  for (std::size_t k = 0; k < c.count("joint"); ++k) {
    if (assembly_tie_of(c, k) != mech::AssemblyTie::ChainSpring) continue;
    require(c.has("joint[].ea_per_strand_n", k),
            "{}: chain '{}' needs ea_per_strand_n (its axial stiffness EA, N) for the elastic assembly", c.where("joint[].name", k),
            c.text_value("joint[].name", k));
    o.chains.push_back({c.text_value("joint[].name", k), chain_ea(c, "joint[].ea_per_strand_n", "joint[].strands", k)});
  }
  for (std::size_t k = 0; k < c.count("motion_drive"); ++k)
    if (c.has("motion_drive[].stiffness_n_m_per_rad", k)) {
      const double stiffness = c.number("motion_drive[].stiffness_n_m_per_rad", k);
      require(std::isfinite(stiffness), "{} = {}: the drive's stiffness must be a finite number of N*m/rad",
              c.where("motion_drive[].stiffness_n_m_per_rad", k), stiffness);
      o.drives.push_back({c.text_value("motion_drive[].name", k), stiffness});
    }
  for (std::size_t k = 0; k < c.count("motion_drive"); ++k)
    if (c.has("motion_drive[].stiffness_n_per_m", k)) {
      const double stiffness = c.number("motion_drive[].stiffness_n_per_m", k);
      require(std::isfinite(stiffness), "{} = {}: the drive's stiffness must be a finite number of N/m",
              c.where("motion_drive[].stiffness_n_per_m", k), stiffness);
      structure::DriveHold hold{c.text_value("motion_drive[].name", k)};
      hold.axial_stiffness_n_per_m = stiffness;
      o.drives.push_back(hold);
    }
  for (std::size_t k = 0; k < c.count("transmission"); ++k) o.transmissions.push_back(read_transmission_member(c, k));
  for (std::size_t k = 0; k < c.count("slide"); ++k) {
    structure::SlideOption slide{c.text_value("slide[].joint", k)};
    if (c.has("slide[].contact_length_mm", k)) slide.contact_length_m = c.number("slide[].contact_length_mm", k);
    if (c.has("slide[].station_spacing_mm", k)) slide.station_spacing_m = c.number("slide[].station_spacing_mm", k);
    o.slides.push_back(slide);
  }
  for (std::size_t k = 0; k < c.count("assembly_point"); ++k) {
    structure::AssemblyPoint p{c.text_value("assembly_point[].name", k), c.text_value("assembly_point[].body", k),
                              c.text_value("assembly_point[].point", k),
                              c.has("assembly_point[].face", k) ? c.text_value("assembly_point[].face", k) : std::string()};
    // Wrong names list the names that exist, as everywhere in a linkage case.
    const auto body = std::find_if(model.bodies.begin(), model.bodies.end(), [&](const mech::Body& b) { return b.name == p.body; });
    if (body == model.bodies.end()) {
      std::string names;
      for (const auto& b : model.bodies)
        if (!b.fixed) names += (names.empty() ? "" : ", ") + b.name;
      fail("{} = \"{}\": no moving body of that name (moving bodies: {})", c.where("assembly_point[].body", k), p.body,
           names);
    }
    require(!body->fixed, "{} = \"{}\": the ground does not move; name a moving body", c.where("assembly_point[].body", k), p.body);
    if (p.point != "origin" && !body->points.contains(p.point)) {
      std::string names = "origin";
      for (const auto& [n, at] : body->points) names += ", " + n;
      fail("{} = \"{}\": body '{}' has no point of that name (points: {})", c.where("assembly_point[].point", k), p.point,
           p.body, names);
    }
    const bool on_part = std::find(bodies_with_parts.begin(), bodies_with_parts.end(), p.body) != bodies_with_parts.end();
    require(!on_part || !p.face_set.empty(), "{}: point '{}' is on body '{}', which has a part: name the face set that carries it (face = \"...\")",
            c.where("assembly_point[].name", k), p.name, p.body);
    require(on_part || p.face_set.empty(), "{}: body '{}' has no part, so the point needs no face", c.where("assembly_point[].face", k), p.body);
    o.points.push_back(p);
  }
  for (std::size_t k = 0; k < c.count("pin"); ++k) {
    structure::PinOption pin;
    pin.joint = c.text_value("pin[].joint", k);
    if (c.has("pin[].diameter_mm", k)) pin.diameter_m = c.number("pin[].diameter_mm", k);
    if (c.has("pin[].youngs_modulus_mpa", k)) pin.youngs_modulus_pa = c.number("pin[].youngs_modulus_mpa", k);
    if (c.has("pin[].poisson_ratio", k)) pin.poisson_ratio = c.number("pin[].poisson_ratio", k);
    o.pins.push_back(pin);
  }
  return o;
}

}  // namespace kinetofem::app
