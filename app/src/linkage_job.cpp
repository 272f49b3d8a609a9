#include "kinetofem/app/linkage_job.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <set>

#include "kinetofem/app/assembly_keys.hpp"
#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/fatigue_keys.hpp"
#include "kinetofem/app/vibration_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/app/motion_case_keys.hpp"
#include "kinetofem/app/motion_keys.hpp"
#include "kinetofem/app/part_keys.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/driver/motion_to_stress.hpp"
#include "kinetofem/pipeline/run_report.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
using units::kRpm;

// Keys of a relative coordinate (drives, the CVODES coordinate) under `prefix`.
void add_coordinate_keys(std::vector<KeySpec>& s, const std::string& prefix, bool required) {
  s.push_back({.path = prefix + "coordinate", .type = Type::String, .default_text = "angle", .allowed = {"angle", "displacement"},
               .doc = "angle: s = theta_j - theta_i (deg); displacement: s = u_i . (P_j - P_i) along axis (mm)"});
  s.push_back({.path = prefix + "body_i", .type = Type::String, .doc = "reference body (the effort's reaction acts on it)", .required = required});
  s.push_back({.path = prefix + "point_i", .type = Type::String, .default_text = "origin", .doc = "point of body_i (displacement)"});
  s.push_back({.path = prefix + "body_j", .type = Type::String, .doc = "driven body (the effort acts on it)", .required = required});
  s.push_back({.path = prefix + "point_j", .type = Type::String, .default_text = "origin", .doc = "point of body_j (displacement)"});
  s.push_back({.path = prefix + "axis", .type = Type::Array, .doc = "displacement direction [x, y] in body_i's frame; default [1, 0]"});
}

bool valid_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.';
  });
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none" : out;
}

// Reads and checks the names: bodies, their points, joints, drives.
class Reader {
 public:
  explicit Reader(const CaseFile& c) : c_(c) {}

  std::string name_key(const std::string& path, std::size_t k, const char* what, std::set<std::string>& seen) const {
    const std::string name = c_.text_value(path, k);
    require(valid_name(name), "{} = \"{}\": a {} name may hold letters, digits, '_', '-' and '.' only", c_.where(path, k),
            name, what);
    require(seen.insert(name).second, "{} = \"{}\": a second {} of that name", c_.where(path, k), name, what);
    return name;
  }

  // Index of the body named by key `path` (element k).
  std::size_t body(const std::vector<mech::Body>& bodies, const std::string& path, std::size_t k) const {
    const std::string name = c_.text_value(path, k);
    std::vector<std::string> names;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (bodies[b].name == name) return b;
      names.push_back(bodies[b].name);
    }
    fail("{} = \"{}\": no body of that name (bodies: {})", c_.where(path, k), name, join_names(names));
  }

  // The point named by key `path` on body `b`.
  std::string point(const mech::Body& b, const std::string& path, std::size_t k) const {
    const std::string name = c_.text_value(path, k);
    if (name == "origin" || b.points.contains(name)) return name;
    std::vector<std::string> names = {"origin"};
    for (const auto& [n, p] : b.points) names.push_back(n);
    fail("{} = \"{}\": body '{}' has no point of that name (points: {})", c_.where(path, k), name, b.name,
         join_names(names));
  }

  mech::RelativeCoordinate coordinate(const std::vector<mech::Body>& bodies, const std::string& prefix,
                                      std::size_t k) const {
    mech::RelativeCoordinate rc;
    rc.type = c_.text_value(prefix + "coordinate", k) == "angle" ? mech::CoordinateType::Angle
                                                                 : mech::CoordinateType::Displacement;
    const std::size_t bi = body(bodies, prefix + "body_i", k), bj = body(bodies, prefix + "body_j", k);
    require(bi != bj, "{} = \"{}\": body_j must differ from body_i", c_.where(prefix + "body_j", k), bodies[bj].name);
    rc.body_i = bodies[bi].name;
    rc.body_j = bodies[bj].name;
    rc.point_i = point(bodies[bi], prefix + "point_i", k);
    rc.point_j = point(bodies[bj], prefix + "point_j", k);
    rc.axis_i = read_vector2(c_, prefix + "axis", k, 1.0, {1.0, 0.0});
    require(rc.axis_i.norm() > 0, "{}: the axis must not be zero", c_.where(prefix + "axis", k));
    return rc;
  }

  std::optional<double> coordinate_number(const std::string& prefix, const std::string& base, const std::string& suffix_deg,
                                          const std::string& suffix_mm, bool angle, std::size_t k) const {
    return app::coordinate_number(c_, prefix, base, suffix_deg, suffix_mm, angle, k);
  }
  std::shared_ptr<const mech::MotionLaw> law(const std::string& prefix, const std::string& law_key, bool angle,
                                             std::size_t k) const {
    return read_motion_law(c_, prefix, law_key, angle, k);
  }

 private:
  const CaseFile& c_;
};

}  // namespace

const std::vector<KeySpec>& linkage_schema() {
  static const std::vector<KeySpec> schema = [] {
    std::vector<KeySpec> s = mechanism_case_keys("linkage");
    // bodies and points
    s.push_back({.path = "body", .type = Type::TableArray, .doc = "rigid bodies"});
    s.push_back({.path = "body[].name", .type = Type::String, .doc = "body name (letters, digits, _ - .)", .required = true});
    s.push_back({.path = "body[].mass_kg", .type = Type::Number, .unit = "kg", .default_number = 0, .min = 0, .doc = "mass of the bare body"});
    s.push_back({.path = "body[].inertia_kgm2", .type = Type::Number, .unit = "kg*m^2", .default_number = 0, .min = 0, .doc = "moment of inertia about the bare body's centre of mass"});
    s.push_back({.path = "body[].com_mm", .type = Type::Array, .unit = "mm", .doc = "centre of mass [x, y] in the body frame; default [0, 0]"});
    s.push_back({.path = "body[].pose_mm_deg", .type = Type::Vector3, .default_number = 0,
                 .doc = "pose [x mm, y mm, theta deg] of the body frame: the ground's pose, else the initial guess for assembly"});
    s.push_back({.path = "body[].velocity_mm_s_deg_s", .type = Type::Vector3, .default_number = 0,
                 .doc = "initial velocity guess [x' mm/s, y' mm/s, theta' deg/s] of the body frame origin (projected onto the constraints)"});
    s.push_back({.path = "body[].fixed", .type = Type::Boolean, .default_number = 0, .doc = "true for the ground (no coordinates)"});
    s.push_back({.path = "point", .type = Type::TableArray, .doc = "named points of bodies ('origin' exists on every body)"});
    s.push_back({.path = "point[].body", .type = Type::String, .doc = "body the point belongs to", .required = true});
    s.push_back({.path = "point[].name", .type = Type::String, .doc = "point name, unique on its body", .required = true});
    s.push_back({.path = "point[].at_mm", .type = Type::Array, .unit = "mm", .doc = "[x, y] in the body frame", .required = true});
    s.push_back({.path = "point_mass", .type = Type::TableArray, .doc = "lumped masses (gripper, casting) added to a body"});
    s.push_back({.path = "point_mass[].body", .type = Type::String, .doc = "body carrying the mass", .required = true});
    s.push_back({.path = "point_mass[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "point_mass[].mass_kg", .type = Type::Number, .unit = "kg", .min = 0, .doc = "mass", .required = true});
    s.push_back({.path = "point_mass[].at_mm", .type = Type::Array, .unit = "mm", .doc = "[x, y] in the body frame; default [0, 0]"});
    s.push_back({.path = "point_mass[].at_point", .type = Type::String, .doc = "a named point of the body instead of at_mm"});
    // joints
    s.push_back({.path = "joint", .type = Type::TableArray, .doc = "joints between two bodies"});
    s.push_back({.path = "joint[].name", .type = Type::String, .doc = "joint name", .required = true});
    s.push_back({.path = "joint[].type", .type = Type::String, .allowed = mech::joint_type_names([](const mech::JointFacts&) { return true; }),
                 .doc = "revolute: points coincide; prismatic: point_j slides on the line through point_i along axis; fixed: welded; "
                        "chain: chain hinged at point_i of body_i wrapped on a roller (radius_mm) centred at point_j of body_j",
                 .required = true});
    s.push_back({.path = "joint[].body_i", .type = Type::String, .doc = "first body (chain: the body carrying the hinge)", .required = true});
    s.push_back({.path = "joint[].point_i", .type = Type::String, .default_text = "origin", .doc = "point of body_i"});
    s.push_back({.path = "joint[].body_j", .type = Type::String, .doc = "second body (chain: the body carrying the roller)", .required = true});
    s.push_back({.path = "joint[].point_j", .type = Type::String, .default_text = "origin", .doc = "point of body_j (chain: roller centre)"});
    s.push_back({.path = "joint[].axis", .type = Type::Array, .doc = "prismatic: sliding direction [x, y] in body_i's frame; default [1, 0]"});
    s.push_back({.path = "joint[].radius_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .min = 0, .min_exclusive = true, .doc = "chain: roller radius"});
    s.push_back({.path = "joint[].wrap", .type = Type::String, .default_text = "ccw", .allowed = {"ccw", "cw"},
                 .doc = "chain: going from point_i along the chain onto the roller, the chain turns counter-clockwise (ccw) or clockwise (cw)"});
    s.push_back({.path = "joint[].reference_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg,
                 .doc = "fixed/prismatic: relative angle theta_j - theta_i held; default: from the initial poses"});
    s.push_back({.path = "joint[].reference_mm", .type = Type::Number, .unit = "mm", .to_si = kMm,
                 .doc = "chain: constant free length + r * wrap angle; default: from the initial poses"});
    // springs and forces
    s.push_back({.path = "spring", .type = Type::TableArray, .doc = "linear spring-dampers between two body points"});
    s.push_back({.path = "spring[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "spring[].body_i", .type = Type::String, .doc = "first body", .required = true});
    s.push_back({.path = "spring[].point_i", .type = Type::String, .default_text = "origin", .doc = "point of body_i"});
    s.push_back({.path = "spring[].body_j", .type = Type::String, .doc = "second body", .required = true});
    s.push_back({.path = "spring[].point_j", .type = Type::String, .default_text = "origin", .doc = "point of body_j"});
    s.push_back({.path = "spring[].stiffness_n_per_m", .type = Type::Number, .unit = "N/m", .default_number = 0, .min = 0, .doc = "stiffness k (tension = k (L - L0) + c L')"});
    s.push_back({.path = "spring[].damping_ns_per_m", .type = Type::Number, .unit = "N*s/m", .default_number = 0, .min = 0, .doc = "damping c"});
    s.push_back({.path = "spring[].free_length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 0, .min = 0, .doc = "free length L0"});
    s.push_back({.path = "point_force", .type = Type::TableArray, .doc = "constant forces (world frame) at body points"});
    s.push_back({.path = "point_force[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "point_force[].body", .type = Type::String, .doc = "body", .required = true});
    s.push_back({.path = "point_force[].point", .type = Type::String, .default_text = "origin", .doc = "point of the body"});
    s.push_back({.path = "point_force[].force_n", .type = Type::Array, .unit = "N", .doc = "[Fx, Fy] in the world frame", .required = true});
    // drives
    s.push_back({.path = "motion_drive", .type = Type::TableArray, .doc = "prescribed motions s(t) = s_0 + law(t) (constraints)"});
    s.push_back({.path = "motion_drive[].name", .type = Type::String, .doc = "name", .required = true});
    add_coordinate_keys(s, "motion_drive[].", true);
    add_motion_law_keys(s, "motion_drive[].", "law", {.default_law = "polynomial345"});
    s.push_back({.path = "motion_drive[].initial_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .doc = "s_0 of an angle; default: from the initial poses"});
    s.push_back({.path = "motion_drive[].initial_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .doc = "s_0 of a displacement; default: from the initial poses"});
    // constant-ratio transmissions (SPEC §4's belts, chains, gear trains): docs/transmissions.md
    s.push_back({.path = "transmission", .type = Type::TableArray,
                 .doc = "belts, chains, gear trains between two relative angles: s_out = ratio * s_in + reference (constraints)"});
    s.push_back({.path = "transmission[].name", .type = Type::String, .doc = "name", .required = true});
    for (const char* side : {"input", "output"}) {
      const std::string p = std::string("transmission[].") + side + ".";
      s.push_back({.path = p + "body_i", .type = Type::String,
                   .doc = fmt::format("{} angle s = theta_j - theta_i: its reference body (the moment's reaction acts on it)", side),
                   .required = true});
      s.push_back({.path = p + "body_j", .type = Type::String,
                   .doc = fmt::format("{} angle s = theta_j - theta_i: its turned body (the moment acts on it)", side),
                   .required = true});
    }
    s.push_back({.path = "transmission[].ratio", .type = Type::Number,
                 .doc = "i in s_out = i * s_in + reference, finite and non-zero; SPEC §4's phi_{k+1,k} = i_k phi_{k,k-1} "
                        "(an open belt from a pulley of radius r_in to one of r_out: -r_in/r_out; a gear pair: +r_in/r_out)",
                 .required = true});
    s.push_back({.path = "transmission[].kind", .type = Type::String, .default_text = "belt", .allowed = {"belt", "gear"},
                 .doc = "belt (belt, chain, band: the force is the effective pull) or gear (the force is the tangential tooth force)"});
    s.push_back({.path = "transmission[].radius_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .min = 0,
                 .min_exclusive = true, .doc = "the output's pulley (sprocket) or pitch radius: force = output moment / radius",
                 .required = true});
    s.push_back({.path = "transmission[].reference_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg,
                 .doc = "the constant c of s_out = i * s_in + c; default: from the initial poses"});
    s.push_back({.path = "force_drive", .type = Type::TableArray, .doc = "motors: an effort on the relative coordinate"});
    s.push_back({.path = "force_drive[].name", .type = Type::String, .doc = "name", .required = true});
    add_coordinate_keys(s, "force_drive[].", true);
    s.push_back({.path = "force_drive[].law", .type = Type::String, .default_text = "constant", .allowed = {"constant", "dc_motor", "pd_servo"},
                 .doc = "constant: effort = torque/force; dc_motor: effort = stall (1 - s'/no_load_speed); pd_servo: kp (s_ref - s) + kd (s_ref' - s')"});
    s.push_back({.path = "force_drive[].torque_nm", .type = Type::Number, .unit = "N*m", .doc = "constant: torque (angle)"});
    s.push_back({.path = "force_drive[].force_n", .type = Type::Number, .unit = "N", .doc = "constant: force (displacement)"});
    s.push_back({.path = "force_drive[].stall_torque_nm", .type = Type::Number, .unit = "N*m", .doc = "dc_motor: stall torque (angle)"});
    s.push_back({.path = "force_drive[].stall_force_n", .type = Type::Number, .unit = "N", .doc = "dc_motor: stall force (displacement)"});
    s.push_back({.path = "force_drive[].no_load_speed_rpm", .type = Type::Number, .unit = "rpm", .to_si = kRpm, .doc = "dc_motor: no-load speed (angle)"});
    s.push_back({.path = "force_drive[].no_load_speed_mm_s", .type = Type::Number, .unit = "mm/s", .to_si = kMm, .doc = "dc_motor: no-load speed (displacement)"});
    s.push_back({.path = "force_drive[].kp_nm_per_rad", .type = Type::Number, .unit = "N*m/rad", .min = 0, .doc = "pd_servo: stiffness gain (angle)"});
    s.push_back({.path = "force_drive[].kd_nms_per_rad", .type = Type::Number, .unit = "N*m*s/rad", .min = 0, .doc = "pd_servo: damping gain (angle)"});
    s.push_back({.path = "force_drive[].kp_n_per_m", .type = Type::Number, .unit = "N/m", .min = 0, .doc = "pd_servo: stiffness gain (displacement)"});
    s.push_back({.path = "force_drive[].kd_ns_per_m", .type = Type::Number, .unit = "N*s/m", .min = 0, .doc = "pd_servo: damping gain (displacement)"});
    add_motion_law_keys(s, "force_drive[].", "reference", {});
    s.push_back({.path = "force_drive[].initial_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .doc = "pd_servo: s_0 of an angle; default: from the initial poses"});
    s.push_back({.path = "force_drive[].initial_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .doc = "pd_servo: s_0 of a displacement; default: from the initial poses"});
    // gravity and simulation
    s.push_back({.path = "gravity.vector_m_s2", .type = Type::Array, .unit = "m/s^2", .doc = "gravity [gx, gy] in the world frame; default [0, -9.80665]; [0, 0]: none"});
    s.push_back({.path = "simulation.method", .type = Type::String, .default_text = "idas", .allowed = {"idas", "cvodes", "kinematic"},
                 .doc = "idas: IDAS on the index-2 GGL form (any DoF); cvodes: CVODES on one minimal coordinate (1 DoF); kinematic: prescribed motion (DoF 0)"});
    s.push_back({.path = "simulation.duration_s", .type = Type::Number, .unit = "s", .min = 0, .min_exclusive = true, .doc = "end time (the run starts at t = 0)", .required = true});
    s.push_back({.path = "simulation.output_times", .type = Type::Integer, .default_number = 101, .min = 2, .max = 1000000, .doc = "number of equally spaced output times, both ends included"});
    s.push_back({.path = "simulation.relative_tolerance", .type = Type::Number, .default_number = 1e-10, .min = 0, .max = 1e-2, .min_exclusive = true, .doc = "integrator relative tolerance"});
    s.push_back({.path = "simulation.absolute_tolerance", .type = Type::Number, .default_number = 1e-12, .min = 0, .max = 1, .min_exclusive = true, .doc = "integrator absolute tolerance of q (m, rad) and v"});
    s.push_back({.path = "simulation.max_step_s", .type = Type::Number, .unit = "s", .default_number = 0, .min = 0, .doc = "largest integrator step; 0: no limit"});
    s.push_back({.path = "simulation.characteristic_length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 0, .min = 0,
                 .doc = "length that scales the drift checks; 0: the largest distance of a point or body origin from the first body's origin"});
    s.push_back({.path = "simulation.slack_is_error", .type = Type::Boolean, .default_number = 1, .doc = "a chain with negative tension stops the run (naming the time)"});
    s.push_back({.path = "simulation.initial_step_s", .type = Type::Number, .unit = "s", .default_number = 0, .min = 0,
                 .doc = "first integrator step; 0: automatic (from the initial accelerations and the tolerances)"});
    add_coordinate_keys(s, "simulation.coordinate.", false);
    // FE parts and the stress over the motion
    add_part_keys(s);
    add_linkage_assembly_keys(s);
    add_fatigue_keys(s);
    add_vibration_keys(s);
    for (auto&& k : part_mesh_keys()) s.push_back(std::move(k));
    for (auto&& k : motion_solver_keys()) s.push_back(std::move(k));
    s.push_back({.path = "static_study.enabled", .type = Type::Boolean, .default_number = 0,
                 .doc = "also solve the parts in a static pose (at rest: gravity, point masses, forces); needs a fully driven linkage"});
    s.push_back({.path = "static_study.time_s", .type = Type::Number, .unit = "s", .default_number = 0, .min = 0,
                 .doc = "the static pose: every motion drive at its value of this time of the motion"});
    s.push_back({.path = "output.tracked_points", .type = Type::StringList,
                 .doc = "body points whose world path is written as a history point.<body>.<point>, as \"body.point\""});
    return with_common_keys(s);
  }();
  return schema;
}

mech::MultibodyModel read_linkage_model(const CaseFile& c) {
  const Reader r(c);
  mech::MultibodyModel m;
  m.name = mechanism_case_name(c);

  std::set<std::string> body_names, bodies_with_parts;
  for (std::size_t k = 0; k < c.count("part"); ++k) bodies_with_parts.insert(c.text_value("part[].body", k));
  const std::size_t n_bodies = c.count("body");
  require(n_bodies >= 2, "{}: a linkage needs at least two [[body]] tables (a ground and a moving body), got {}",
          c.path().string(), n_bodies);
  for (std::size_t k = 0; k < n_bodies; ++k) {
    mech::Body b;
    b.name = r.name_key("body[].name", k, "body", body_names);
    b.mass_kg = c.number("body[].mass_kg", k);
    b.inertia_kgm2 = c.number("body[].inertia_kgm2", k);
    b.com_body = read_vector2(c, "body[].com_mm", k, kMm);
    const Eigen::Vector3d pose = c.vector3("body[].pose_mm_deg", k);
    b.pose = {pose.x() * kMm, pose.y() * kMm, pose.z() * kDeg};
    const Eigen::Vector3d vel = c.vector3("body[].velocity_mm_s_deg_s", k);
    b.velocity = {vel.x() * kMm, vel.y() * kMm, vel.z() * kDeg};
    b.fixed = c.boolean("body[].fixed", k);
    if (!b.fixed && !bodies_with_parts.contains(b.name))
      require(b.mass_kg > 0 && b.inertia_kgm2 > 0, "{}: moving body '{}' needs mass_kg > 0 and inertia_kgm2 > 0 (got {:g} kg, {:g} kg*m^2), or a [[part]] to take them from",
              c.where("body[].name", k), b.name, b.mass_kg, b.inertia_kgm2);
    m.bodies.push_back(b);
  }
  require(std::any_of(m.bodies.begin(), m.bodies.end(), [](const mech::Body& b) { return b.fixed; }),
          "{}: no [[body]] has fixed = true (the ground)", c.path().string());

  for (std::size_t k = 0; k < c.count("point"); ++k) {
    mech::Body& b = m.bodies[r.body(m.bodies, "point[].body", k)];
    const std::string name = c.text_value("point[].name", k);
    require(valid_name(name) && name != "origin", "{} = \"{}\": a point name may hold letters, digits, '_', '-' and '.' and is not 'origin'",
            c.where("point[].name", k), name);
    require(!b.points.contains(name), "{} = \"{}\": body '{}' already has a point of that name", c.where("point[].name", k), name, b.name);
    b.points[name] = read_vector2(c, "point[].at_mm", k, kMm);
  }
  for (std::size_t k = 0; k < c.count("point_mass"); ++k) {
    mech::Body& b = m.bodies[r.body(m.bodies, "point_mass[].body", k)];
    Eigen::Vector2d at = read_vector2(c, "point_mass[].at_mm", k, kMm);
    if (c.has("point_mass[].at_point", k)) {
      require(!c.has("point_mass[].at_mm", k), "{}: give at_mm or at_point, not both", c.where("point_mass[].at_point", k));
      const std::string point = r.point(b, "point_mass[].at_point", k);
      at = point == "origin" ? Eigen::Vector2d::Zero() : b.points.at(point);
    }
    b.point_masses.push_back({c.text_value("point_mass[].name", k), c.number("point_mass[].mass_kg", k), at});
  }

  std::set<std::string> constraint_names;  // joints, motion drives and transmissions share one namespace
  for (std::size_t k = 0; k < c.count("joint"); ++k) {
    mech::Joint j;
    j.name = r.name_key("joint[].name", k, "joint, motion drive or transmission", constraint_names);
    const std::string type = c.text_value("joint[].type", k);
    const auto named = mech::joint_type_named(type);
    require(named.has_value(), "{} = \"{}\": unknown joint type", c.where("joint[].type", k), type);
    j.type = *named;
    const mech::JointFacts& facts = mech::joint_facts(j.type);
    const std::size_t bi = r.body(m.bodies, "joint[].body_i", k), bj = r.body(m.bodies, "joint[].body_j", k);
    require(bi != bj, "{} = \"{}\": a joint connects two different bodies", c.where("joint[].body_j", k), m.bodies[bj].name);
    j.body_i = m.bodies[bi].name;
    j.body_j = m.bodies[bj].name;
    j.point_i = r.point(m.bodies[bi], "joint[].point_i", k);
    j.point_j = r.point(m.bodies[bj], "joint[].point_j", k);
    // A key that the joint's type has no use for is a mistake: name the types that take it.
    auto only_for = [&](const char* key, auto takes) {
      require(takes(facts) || !c.has(std::string("joint[].") + key, k), "{}: only for {} joints (this one is {})",
              c.where(std::string("joint[].") + key, k), mech::joint_type_list(takes), type);
    };
    only_for("axis", [](const mech::JointFacts& f) { return f.has_axis; });
    only_for("radius_mm", [](const mech::JointFacts& f) { return f.has_roller; });
    only_for("wrap", [](const mech::JointFacts& f) { return f.has_roller; });
    only_for("reference_mm", [](const mech::JointFacts& f) { return f.reference == mech::JointReference::Length; });
    only_for("reference_deg", [](const mech::JointFacts& f) { return f.reference == mech::JointReference::Angle; });
    j.axis_i = read_vector2(c, "joint[].axis", k, 1.0, {1.0, 0.0});
    require(j.axis_i.norm() > 0, "{}: the axis must not be zero", c.where("joint[].axis", k));
    if (facts.has_roller) {
      require(c.has("joint[].radius_mm", k), "{}: a chain joint needs radius_mm (the roller radius)", c.where("joint[].type", k));
      j.radius_m = c.number("joint[].radius_mm", k);
      j.wrap_ccw = c.text_value("joint[].wrap", k) == "ccw";
    }
    if (c.has("joint[].reference_mm", k)) j.reference = c.number("joint[].reference_mm", k);
    if (c.has("joint[].reference_deg", k)) j.reference = c.number("joint[].reference_deg", k);
    m.joints.push_back(j);
  }

  for (std::size_t k = 0; k < c.count("spring"); ++k) {
    mech::Spring sp;
    sp.name = c.text_value("spring[].name", k);
    const std::size_t bi = r.body(m.bodies, "spring[].body_i", k), bj = r.body(m.bodies, "spring[].body_j", k);
    sp.body_i = m.bodies[bi].name;
    sp.body_j = m.bodies[bj].name;
    sp.point_i = r.point(m.bodies[bi], "spring[].point_i", k);
    sp.point_j = r.point(m.bodies[bj], "spring[].point_j", k);
    sp.stiffness_N_per_m = c.number("spring[].stiffness_n_per_m", k);
    sp.damping_Ns_per_m = c.number("spring[].damping_ns_per_m", k);
    sp.free_length_m = c.number("spring[].free_length_mm", k);
    m.springs.push_back(sp);
  }
  for (std::size_t k = 0; k < c.count("point_force"); ++k) {
    mech::PointForce pf;
    pf.name = c.text_value("point_force[].name", k);
    const std::size_t b = r.body(m.bodies, "point_force[].body", k);
    pf.body = m.bodies[b].name;
    pf.point = r.point(m.bodies[b], "point_force[].point", k);
    pf.force_world = read_vector2(c, "point_force[].force_n", k, 1.0);
    m.point_forces.push_back(pf);
  }

  for (std::size_t k = 0; k < c.count("transmission"); ++k) {
    const std::string p = "transmission[].";
    mech::Transmission t;
    t.name = r.name_key(p + "name", k, "joint, motion drive or transmission", constraint_names);
    for (auto [side, coordinate] : {std::pair{"input.", &t.input}, std::pair{"output.", &t.output}}) {
      const std::size_t bi = r.body(m.bodies, p + side + "body_i", k), bj = r.body(m.bodies, p + side + "body_j", k);
      require(bi != bj, "{} = \"{}\": body_j must differ from body_i", c.where(p + side + "body_j", k), m.bodies[bj].name);
      coordinate->type = mech::CoordinateType::Angle;
      coordinate->body_i = m.bodies[bi].name;
      coordinate->body_j = m.bodies[bj].name;
    }
    t.ratio = c.number(p + "ratio", k);
    require(t.ratio != 0.0, "{} = 0: transmission '{}' would hold its output still whatever its input does; a ratio "
            "must not be zero", c.where(p + "ratio", k), t.name);
    t.kind = c.text_value(p + "kind", k) == "gear" ? mech::TransmissionKind::Gear : mech::TransmissionKind::Belt;
    t.radius_m = c.number(p + "radius_mm", k);
    if (c.has(p + "reference_deg", k)) t.reference = c.number(p + "reference_deg", k);
    m.transmissions.push_back(t);
  }

  std::set<std::string> drive_names;
  for (std::size_t k = 0; k < c.count("motion_drive"); ++k) {
    const std::string p = "motion_drive[].";
    mech::MotionDrive d;
    d.name = r.name_key(p + "name", k, "joint, motion drive or transmission", constraint_names);
    drive_names.insert(d.name);
    d.coordinate = r.coordinate(m.bodies, p, k);
    const bool angle = d.coordinate.type == mech::CoordinateType::Angle;
    d.law = r.law(p, "law", angle, k);
    d.initial = r.coordinate_number(p, "initial", "_deg", "_mm", angle, k);
    m.motion_drives.push_back(d);
  }
  for (std::size_t k = 0; k < c.count("force_drive"); ++k) {
    const std::string p = "force_drive[].";
    mech::ForceDrive d;
    d.name = r.name_key(p + "name", k, "drive", drive_names);
    d.coordinate = r.coordinate(m.bodies, p, k);
    const bool angle = d.coordinate.type == mech::CoordinateType::Angle;
    const std::string law = c.text_value(p + "law", k);
    const std::string at = c.where(p + "law", k);
    auto needed = [&](const std::string& angle_key, const std::string& displacement_key) {
      const std::string mine = p + (angle ? angle_key : displacement_key), other = p + (angle ? displacement_key : angle_key);
      require(!c.has(other, k), "{}: this drive's coordinate is {}: use '{}'", c.where(other, k),
              angle ? "an angle" : "a displacement", angle ? angle_key : displacement_key);
      require(c.has(mine, k), "{} = \"{}\": needs '{}'", at, law, angle ? angle_key : displacement_key);
      return c.number(mine, k);
    };
    if (law == "constant") {
      d.law_type = mech::ForceLaw::Constant;
      d.value = needed("torque_nm", "force_n");
    } else if (law == "dc_motor") {
      d.law_type = mech::ForceLaw::DcMotor;
      d.stall = needed("stall_torque_nm", "stall_force_n");
      d.no_load_speed = needed("no_load_speed_rpm", "no_load_speed_mm_s");
      require(d.no_load_speed != 0.0, "{}: the no-load speed must not be zero", at);
    } else {
      d.law_type = mech::ForceLaw::PdServo;
      d.kp = needed("kp_nm_per_rad", "kp_n_per_m");
      d.kd = needed("kd_nms_per_rad", "kd_ns_per_m");
      require(c.has(p + "reference", k), "{} = \"pd_servo\": needs 'reference' (a motion law) and its parameters", at);
      d.law = r.law(p, "reference", angle, k);
      d.initial = r.coordinate_number(p, "initial", "_deg", "_mm", angle, k);
    }
    m.force_drives.push_back(d);
  }

  if (c.has("gravity.vector_m_s2")) m.gravity = read_vector2(c, "gravity.vector_m_s2", 0, 1.0);

  double length = c.number("simulation.characteristic_length_mm");
  if (length == 0.0) {
    const Eigen::Vector2d o = m.bodies.front().pose.head<2>();
    for (const auto& b : m.bodies) {
      length = std::max(length, (b.pose.head<2>() - o).norm());
      for (const auto& [n, p] : b.points) length = std::max(length, p.norm());
    }
    if (length == 0.0) length = 1.0;
  }
  m.characteristic_length_m = length;
  return m;
}

LinkageRun run_linkage(const CaseFile& c, const RunOptions& options) {
  Stopwatch total;
  const std::string name = mechanism_case_name(c);

  // ---- read the case: the mechanism, its parts, the run ----------------------
  driver::MotionStressCase run_case;
  run_case.model = read_linkage_model(c);
  const mech::MultibodyModel& m = run_case.model;
  const Log log = start_case_log(c, options, name, fmt::format("linkage: {} bodies, {} joints, {} motion drives, {} transmissions, {} force "
                                 "drives, {} springs, {} parts", m.bodies.size(), m.joints.size(), m.motion_drives.size(),
                                 m.transmissions.size(), m.force_drives.size(), m.springs.size(), c.count("part")));
  run_case.parts = read_parts(c, m);
  for (auto& part : run_case.parts) part.file_options.trusted = options.trust_part_files;
  // An elastic guide: the per-part stress spreads the slider's load over the
  // whole guide face (a statically equivalent coupling, not where the slider
  // is); only the assembly places it at the slider. Said, not silent.
  for (std::size_t k = 0; k < c.count("joint"); ++k)
    if (c.text_value("joint[].type", k) == "prismatic" && c.has("joint[].face_i", k))
      log.info("note: joint '{}': the per-part stress of body '{}' spreads the slider's load over its whole face set "
               "'{}' (statically equivalent, not at the slider); {} places it where the slider is, over its contact "
               "length",
               c.text_value("joint[].name", k), c.text_value("joint[].body_i", k), c.text_value("joint[].face_i", k),
               c.boolean("assembly.enabled") ? "the elastic assembly (its fields assembly.<body>)"
                                             : "the elastic assembly (assembly.enabled = true)");
  run_case.times = mech::equally_spaced_times(c.number("simulation.duration_s"), c.integer("simulation.output_times"));
  const std::string method = c.text_value("simulation.method");
  run_case.dynamics.method = method == "kinematic" ? pipeline::DynamicsMethod::Kinematic
                             : method == "cvodes"  ? pipeline::DynamicsMethod::Cvodes
                                                   : pipeline::DynamicsMethod::Idas;
  mech::DynamicsOptions& dyn = run_case.dynamics.options;
  dyn.relative_tolerance = c.number("simulation.relative_tolerance");
  dyn.absolute_tolerance = c.number("simulation.absolute_tolerance");
  dyn.max_step_s = c.number("simulation.max_step_s");
  dyn.initial_step_s = c.number("simulation.initial_step_s");
  dyn.slack_is_error = c.boolean("simulation.slack_is_error");
  if (c.has("simulation.coordinate.body_i"))
    run_case.dynamics.cvodes_coordinate = Reader(c).coordinate(m.bodies, "simulation.coordinate.", 0);
  if (c.boolean("static_study.enabled")) {
    const double t = c.number("static_study.time_s");
    std::vector<double> values;
    for (const auto& d : m.motion_drives) values.push_back(d.law ? d.law->at(t).s : 0.0);
    run_case.static_pose = values;
  }
  for (const auto& text : c.has("output.tracked_points") ? c.strings("output.tracked_points") : std::vector<std::string>{}) {
    const auto dot = text.find('.');
    require(dot != std::string::npos, "{} = \"{}\": write \"body.point\"", c.where("output.tracked_points"), text);
    run_case.tracked_points.push_back({text.substr(0, dot), text.substr(dot + 1)});
  }
  read_shared_motion_keys(c, options, name, [&](const std::vector<std::string>& bodies) {
    return read_linkage_assembly(c, m, bodies);
  }, run_case);

  // ---- run the pipeline ------------------------------------------------------
  driver::MotionStressRun result = driver::run_motion_to_stress(run_case, log);

  // ---- summary ----------------------------------------------------------------
  LinkageRun run;
  run.model = result.model;
  run.results = std::move(result.motion);
  run.results_file = result.results_file;
  run.parts = result.parts;
  run.assembly = result.assembly;
  run.fatigue = result.fatigue;
  run.vibration = result.vibration;
  const pipeline::MechanismExtremes extremes = pipeline::mechanism_extremes(run.model, run.results);
  run.max_abs_drive_effort = extremes.max_abs_drive_effort;
  run.min_chain_tension_n = extremes.min_chain_tension_n;
  run.max_chain_tension_n = extremes.max_chain_tension_n;
  std::printf("\nSummary of '%s' (linkage, %s, %zu output times over %.4g s)\n%s", name.c_str(), method.c_str(),
              run.results.frames.size(), run_case.times.back(), extremes.text.c_str());
  if (!run.parts.empty())
    std::printf("%s", pipeline::format_part_table(run.parts, pipeline::parts_in_several_planes(run_case.parts)).c_str());
  print_stage_summaries(result);
  // The stage lines printed the dynamics checks already; under --quiet the summary is all there is.
  if (log.is_quiet()) std::printf("%s\n", run.results.format_checks().c_str());
  std::printf("  results: %s (+ .xdmf)\n  wall time: %.2f s\n", run.results_file.string().c_str(), total.seconds());
  return run;
}

}  // namespace kinetofem::app
