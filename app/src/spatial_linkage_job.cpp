// The "spatial_linkage" case type: its schema, its reader (case file ->
// mech::spatial::Model) and its job (run, checks, results, summary).
// What it models and its frames and units: spatial_linkage_job.hpp.
#include "kinetofem/app/spatial_linkage_job.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/motion_keys.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/spatial/dynamics.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/pipeline/spatial_histories.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
namespace sp = mech::spatial;

// The joint types a case may name: every spatial type but the chain (a planar
// element, for the `linkage` case type).
bool offered(sp::JointType type) { return !sp::joint_facts(type).holds_length; }

std::vector<std::string> offered_joint_names() {
  std::vector<std::string> names;
  for (sp::JointType type : sp::all_joint_types)
    if (offered(type)) names.push_back(sp::joint_facts(type).name);
  return names;
}

// Whether a joint type's equations use the axis h_i (and h_j).
bool uses_axis(sp::JointType type) {
  switch (type) {
    case sp::JointType::Spherical:
      return false;
    case sp::JointType::Revolute:
    case sp::JointType::Prismatic:
    case sp::JointType::Cylindrical:
    case sp::JointType::Universal:
    case sp::JointType::Fixed:
    case sp::JointType::Chain:
      return true;
  }
  return true;
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

std::string shown(const Eigen::Vector3d& v) { return fmt::format("[{:g}, {:g}, {:g}]", v.x(), v.y(), v.z()); }

// Rotation body axes -> world of roll, pitch, yaw (rad): R = Rz(yaw) Ry(pitch) Rx(roll).
Eigen::Matrix3d rotation_rpy(const Eigen::Vector3d& rpy) {
  using Eigen::AngleAxisd;
  return (AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) * AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// Reads and checks names, points, inertias and axes, each error naming its key.
class Reader {
 public:
  explicit Reader(const CaseFile& c) : c_(c) {}

  std::string name_key(const std::string& path, std::size_t k, const char* what, std::set<std::string>& seen) const {
    const std::string name = c_.text_value(path, k);
    require(valid_name(name), "{} = \"{}\": a {} name may hold letters, digits, '_', '-' and '.' only",
            c_.where(path, k), name, what);
    require(seen.insert(name).second, "{} = \"{}\": a second {} of that name", c_.where(path, k), name, what);
    return name;
  }

  std::size_t body(const std::vector<sp::Body>& bodies, const std::string& path, std::size_t k) const {
    const std::string name = c_.text_value(path, k);
    std::vector<std::string> names;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (bodies[b].name == name) return b;
      names.push_back(bodies[b].name);
    }
    fail("{} = \"{}\": no body of that name (bodies: {})", c_.where(path, k), name, join_names(names));
  }

  std::string point(const sp::Body& b, const std::string& path, std::size_t k) const {
    const std::string name = c_.text_value(path, k);
    if (name == "origin" || b.points.contains(name)) return name;
    std::vector<std::string> names = {"origin"};
    for (const auto& [n, p] : b.points) names.push_back(n);
    fail("{} = \"{}\": body '{}' has no point of that name (points: {})", c_.where(path, k), name, b.name,
         join_names(names));
  }

  // An inertia key: 3 numbers (principal moments about the body axes) or 6
  // (the tensor's entries Ixx, Iyy, Izz, Ixy, Ixz, Iyz), kg m^2; zero if absent.
  Eigen::Matrix3d inertia(const std::string& path, std::size_t k) const {
    const std::vector<double> v = read_numbers(c_, path, k, 1.0);
    Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
    if (v.size() == 3) {
      j.diagonal() << v[0], v[1], v[2];
    } else if (v.size() == 6) {
      j << v[0], v[3], v[4], v[3], v[1], v[5], v[4], v[5], v[2];
    } else {
      require(v.empty(), "{} must hold 3 numbers (principal moments) or 6 (Ixx, Iyy, Izz, Ixy, Ixz, Iyz), got {}",
              c_.where(path, k), v.size());
    }
    return j;
  }

  // A Vector3 axis key that must not be zero: the unit vector.
  Eigen::Vector3d axis(const std::string& path, std::size_t k, const std::string& joint) const {
    const Eigen::Vector3d a = c_.vector3(path, k);
    require(a.norm() > 0.0, "{} = {}: joint '{}': the axis has zero length (give its direction, any length)",
            c_.where(path, k), shown(a), joint);
    return a.normalized();
  }

 private:
  const CaseFile& c_;
};

// The smallest eigenvalue of a symmetric 3x3 tensor.
double smallest_eigenvalue(const Eigen::Matrix3d& j) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(j, Eigen::EigenvaluesOnly).eigenvalues().minCoeff();
}

// Integral of equally or unequally spaced samples: composite Simpson when the
// intervals are even in number and equal, else the trapezoidal rule.
double integrate(const std::vector<double>& t, const std::vector<double>& f) {
  const std::size_t n = t.size();
  if (n < 2) return 0.0;
  const double h = (t.back() - t.front()) / double(n - 1);
  bool equal = true;
  for (std::size_t k = 1; k < n; ++k) equal = equal && std::abs(t[k] - t[k - 1] - h) <= 1e-9 * h;
  if (equal && (n - 1) % 2 == 0) {
    double sum = f.front() + f.back();
    for (std::size_t k = 1; k + 1 < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * f[k];
    return sum * h / 3.0;
  }
  double sum = 0.0;
  for (std::size_t k = 1; k < n; ++k) sum += 0.5 * (f[k] + f[k - 1]) * (t[k] - t[k - 1]);
  return sum;
}

// The default of a Vector3 key of the schema (SI).
Eigen::Vector3d spec_default_vector(const std::string& path);

}  // namespace

const std::vector<KeySpec>& spatial_linkage_schema() {
  static const std::vector<KeySpec> schema = [] {
    const sp::DynamicsOptions idas_defaults;
    std::vector<KeySpec> s = mechanism_case_keys("spatial_linkage");
    const std::string joint_types = join_names(offered_joint_names());
    // bodies, points, point masses
    s.push_back({.path = "body", .type = Type::TableArray, .doc = "rigid bodies (one with fixed = true: the ground)"});
    s.push_back(
        {.path = "body[].name", .type = Type::String, .doc = "body name (letters, digits, _ - .)", .required = true});
    s.push_back({.path = "body[].fixed",
                 .type = Type::Boolean,
                 .default_number = 0,
                 .doc = "true for the ground (no coordinates)"});
    s.push_back({.path = "body[].mass_kg",
                 .type = Type::Number,
                 .unit = "kg",
                 .default_number = 0,
                 .min = 0,
                 .doc = "mass of the bare body (> 0 for a moving body)"});
    s.push_back({.path = "body[].com_mm",
                 .type = Type::Vector3,
                 .unit = "mm",
                 .to_si = kMm,
                 .default_number = 0,
                 .doc = "centre of mass [x, y, z] of the bare body, body frame"});
    s.push_back({.path = "body[].inertia_kgm2",
                 .type = Type::Array,
                 .unit = "kg*m^2",
                 .doc =
                     "inertia about the bare body's centre of mass, body axes: [Ixx, Iyy, Izz] (principal moments) or "
                     "[Ixx, Iyy, Izz, Ixy, Ixz, Iyz] (the tensor's entries, Ixy = -integral of x y dm); positive "
                     "definite for a moving body"});
    s.push_back({.path = "body[].position_mm",
                 .type = Type::Vector3,
                 .unit = "mm",
                 .to_si = kMm,
                 .default_number = 0,
                 .doc = "origin of the body frame, world: the ground's pose, else the initial guess for assembly"});
    s.push_back(
        {.path = "body[].rotation_rpy_deg",
         .type = Type::Vector3,
         .unit = "deg",
         .to_si = kDeg,
         .default_number = 0,
         .doc =
             "orientation [roll, pitch, yaw] of the body frame: R = Rz(yaw) Ry(pitch) Rx(roll), body axes -> world"});
    s.push_back({.path = "body[].velocity_mm_s",
                 .type = Type::Vector3,
                 .unit = "mm/s",
                 .to_si = kMm,
                 .default_number = 0,
                 .doc = "initial velocity guess of the body frame origin, world (projected onto the constraints)"});
    s.push_back({.path = "body[].angular_velocity_deg_s",
                 .type = Type::Vector3,
                 .unit = "deg/s",
                 .to_si = kDeg,
                 .default_number = 0,
                 .doc = "initial angular velocity guess, world (projected onto the constraints)"});
    s.push_back(
        {.path = "point", .type = Type::TableArray, .doc = "named points of bodies ('origin' exists on every body)"});
    s.push_back({.path = "point[].body", .type = Type::String, .doc = "body the point belongs to", .required = true});
    s.push_back(
        {.path = "point[].name", .type = Type::String, .doc = "point name, unique on its body", .required = true});
    s.push_back({.path = "point[].at_mm",
                 .type = Type::Vector3,
                 .unit = "mm",
                 .to_si = kMm,
                 .doc = "[x, y, z] in the body frame",
                 .required = true});
    s.push_back({.path = "point_mass",
                 .type = Type::TableArray,
                 .doc = "lumped masses with rotary inertia (a gripper, a casting) added to a body"});
    s.push_back({.path = "point_mass[].body", .type = Type::String, .doc = "body carrying the mass", .required = true});
    s.push_back({.path = "point_mass[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "point_mass[].mass_kg",
                 .type = Type::Number,
                 .unit = "kg",
                 .min = 0,
                 .doc = "mass",
                 .required = true});
    s.push_back({.path = "point_mass[].at_mm",
                 .type = Type::Vector3,
                 .unit = "mm",
                 .to_si = kMm,
                 .doc = "its centre [x, y, z] in the body frame; default: the body's origin"});
    s.push_back(
        {.path = "point_mass[].at_point", .type = Type::String, .doc = "a named point of the body instead of at_mm"});
    s.push_back({.path = "point_mass[].inertia_kgm2",
                 .type = Type::Array,
                 .unit = "kg*m^2",
                 .doc = "its own inertia about its centre, body axes, as body[].inertia_kgm2; default none (a point)"});
    // joints
    s.push_back({.path = "joint", .type = Type::TableArray, .doc = "joints between two bodies"});
    s.push_back({.path = "joint[].name",
                 .type = Type::String,
                 .doc = "joint name (joints and motion drives share one namespace)",
                 .required = true});
    s.push_back(
        {.path = "joint[].type",
         .type = Type::String,
         .allowed = offered_joint_names(),
         .doc =
             "spherical: points coincide; revolute: points coincide, axes stay parallel; cylindrical: point_j on the "
             "line through point_i along axis_i, axes parallel; prismatic: cylindrical without the turn about the "
             "axis; universal: points coincide, the cross axes axis_i, axis_j stay perpendicular; fixed: welded (" +
             joint_types + ")",
         .required = true});
    s.push_back({.path = "joint[].body_i",
                 .type = Type::String,
                 .doc = "first body (a drive's effort is reacted on it)",
                 .required = true});
    s.push_back({.path = "joint[].point_i", .type = Type::String, .default_text = "origin", .doc = "point of body_i"});
    s.push_back({.path = "joint[].body_j",
                 .type = Type::String,
                 .doc = "second body (a drive's effort acts on it)",
                 .required = true});
    s.push_back({.path = "joint[].point_j", .type = Type::String, .default_text = "origin", .doc = "point of body_j"});
    s.push_back({.path = "joint[].axis_i",
                 .type = Type::Vector3,
                 .default_vector = std::array<double, 3>{0, 0, 1},
                 .doc = "axis h_i in body_i's frame (any length but zero); not for spherical joints"});
    s.push_back(
        {.path = "joint[].axis_j",
         .type = Type::Vector3,
         .doc = "axis h_j in body_j's frame; default: axis_i's direction at the initial poses; universal: required, "
                "the cross axis (perpendicular to axis_i)"});
    s.push_back({.path = "joint[].rotation_deg",
                 .type = Type::Number,
                 .unit = "deg",
                 .to_si = kDeg,
                 .doc = "prismatic, fixed: the relative angle about axis_i held; default: that of the initial poses"});
    // drives
    s.push_back({.path = "motion_drive",
                 .type = Type::TableArray,
                 .doc = "prescribed motions of a joint coordinate s(t) = s_0 + law(t) (constraints)"});
    s.push_back({.path = "motion_drive[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "motion_drive[].joint",
                 .type = Type::String,
                 .doc = "the driven joint (revolute, prismatic or cylindrical)",
                 .required = true});
    s.push_back(
        {.path = "motion_drive[].coordinate",
         .type = Type::String,
         .allowed = {"rotation", "translation"},
         .doc = "rotation: angle about axis_i (deg; revolute, cylindrical); translation: along axis_i (mm; prismatic, "
                "cylindrical); default: the one the joint has (a cylindrical joint needs it)"});
    add_motion_law_keys(s, "motion_drive[].", "law", {.default_law = "polynomial345"});
    s.push_back({.path = "motion_drive[].initial_deg",
                 .type = Type::Number,
                 .unit = "deg",
                 .to_si = kDeg,
                 .doc = "s_0 of a rotation; default: from the initial poses"});
    s.push_back({.path = "motion_drive[].initial_mm",
                 .type = Type::Number,
                 .unit = "mm",
                 .to_si = kMm,
                 .doc = "s_0 of a translation; default: from the initial poses"});
    // springs and forces
    s.push_back({.path = "spring", .type = Type::TableArray, .doc = "linear spring-dampers between two body points"});
    s.push_back({.path = "spring[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "spring[].body_i", .type = Type::String, .doc = "first body", .required = true});
    s.push_back({.path = "spring[].point_i", .type = Type::String, .default_text = "origin", .doc = "point of body_i"});
    s.push_back({.path = "spring[].body_j", .type = Type::String, .doc = "second body", .required = true});
    s.push_back({.path = "spring[].point_j", .type = Type::String, .default_text = "origin", .doc = "point of body_j"});
    s.push_back({.path = "spring[].stiffness_n_per_m",
                 .type = Type::Number,
                 .unit = "N/m",
                 .default_number = 0,
                 .min = 0,
                 .doc = "stiffness k (tension = k (L - L0) + c L')"});
    s.push_back({.path = "spring[].damping_ns_per_m",
                 .type = Type::Number,
                 .unit = "N*s/m",
                 .default_number = 0,
                 .min = 0,
                 .doc = "damping c"});
    s.push_back({.path = "spring[].free_length_mm",
                 .type = Type::Number,
                 .unit = "mm",
                 .to_si = kMm,
                 .default_number = 0,
                 .min = 0,
                 .doc = "free length L0"});
    s.push_back(
        {.path = "point_force", .type = Type::TableArray, .doc = "constant forces (world frame) at body points"});
    s.push_back({.path = "point_force[].name", .type = Type::String, .doc = "name", .required = true});
    s.push_back({.path = "point_force[].body", .type = Type::String, .doc = "body", .required = true});
    s.push_back(
        {.path = "point_force[].point", .type = Type::String, .default_text = "origin", .doc = "point of the body"});
    s.push_back({.path = "point_force[].force_n",
                 .type = Type::Vector3,
                 .unit = "N",
                 .doc = "[Fx, Fy, Fz], world",
                 .required = true});
    // gravity and simulation
    s.push_back({.path = "gravity.vector_m_s2",
                 .type = Type::Vector3,
                 .unit = "m/s^2",
                 .default_vector = std::array<double, 3>{0, 0, -units::kStandardGravity},
                 .doc = "gravity, world; [0, 0, 0]: none"});
    s.push_back({.path = "simulation.method",
                 .type = Type::String,
                 .default_text = "kinematic",
                 .allowed = {"kinematic", "idas"},
                 .doc =
                     "kinematic: prescribed motion of a fully driven mechanism (DoF 0), inverse dynamics at each time; "
                     "idas: SUNDIALS IDAS on the stabilised index-2 form (any DoF)"});
    s.push_back({.path = "simulation.duration_s",
                 .type = Type::Number,
                 .unit = "s",
                 .min = 0,
                 .min_exclusive = true,
                 .doc = "end time (the run starts at t = 0)",
                 .required = true});
    s.push_back({.path = "simulation.output_times",
                 .type = Type::Integer,
                 .default_number = 101,
                 .min = 2,
                 .max = 1000000,
                 .doc = "number of equally spaced output times, both ends included"});
    s.push_back({.path = "simulation.relative_tolerance",
                 .type = Type::Number,
                 .default_number = idas_defaults.relative_tolerance,
                 .min = 0,
                 .max = 1e-2,
                 .min_exclusive = true,
                 .doc = "idas: relative tolerance"});
    s.push_back({.path = "simulation.absolute_tolerance",
                 .type = Type::Number,
                 .default_number = idas_defaults.absolute_tolerance,
                 .min = 0,
                 .max = 1,
                 .min_exclusive = true,
                 .doc = "idas: absolute tolerance of q (m, 1) and v (m/s, rad/s)"});
    s.push_back({.path = "simulation.max_step_s",
                 .type = Type::Number,
                 .unit = "s",
                 .default_number = 0,
                 .min = 0,
                 .doc = "idas: largest step; 0: no limit"});
    s.push_back({.path = "simulation.initial_step_s",
                 .type = Type::Number,
                 .unit = "s",
                 .default_number = idas_defaults.initial_step_s,
                 .min = 0,
                 .doc = "idas: first step; 0: automatic"});
    s.push_back({.path = "simulation.characteristic_length_mm",
                 .type = Type::Number,
                 .unit = "mm",
                 .to_si = kMm,
                 .default_number = 0,
                 .min = 0,
                 .doc = "length that scales the drift checks; 0: the largest distance of a body origin from the first "
                        "body's origin or of a point from its body's origin"});
    const std::vector<KeySpec> sweep = sweep_keys();
    s.insert(s.end(), sweep.begin(), sweep.end());
    return s;
  }();
  return schema;
}

namespace {

Eigen::Vector3d spec_default_vector(const std::string& path) {
  for (const KeySpec& k : spatial_linkage_schema())
    if (k.path == path && k.default_vector)
      return Eigen::Vector3d((*k.default_vector)[0], (*k.default_vector)[1], (*k.default_vector)[2]) * k.to_si;
  fail("spatial_linkage schema: key '{}' has no default vector", path);
}

}  // namespace

sp::Model read_spatial_linkage_model(const CaseFile& c) {
  const Reader r(c);
  sp::Model m;
  m.name = mechanism_case_name(c);

  const std::size_t n_bodies = c.count("body");
  require(n_bodies >= 2,
          "{}: a spatial linkage needs at least two [[body]] tables (a ground and a moving body), got {}",
          c.path().string(), n_bodies);
  std::set<std::string> body_names;
  for (std::size_t k = 0; k < n_bodies; ++k) {
    sp::Body b;
    b.name = r.name_key("body[].name", k, "body", body_names);
    b.fixed = c.boolean("body[].fixed", k);
    b.mass_kg = c.number("body[].mass_kg", k);
    b.com_body = c.vector3("body[].com_mm", k);
    b.inertia_kgm2 = r.inertia("body[].inertia_kgm2", k);
    b.position = c.vector3("body[].position_mm", k);
    sp::set_rotation(b, rotation_rpy(c.vector3("body[].rotation_rpy_deg", k)));
    b.velocity = c.vector3("body[].velocity_mm_s", k);
    b.angular_velocity = c.vector3("body[].angular_velocity_deg_s", k);
    if (!b.fixed) {
      require(b.mass_kg > 0.0,
              "{} = {:g} kg: moving body '{}' needs a mass > 0 (only the ground, fixed = true, may have none)",
              c.where("body[].mass_kg", k), b.mass_kg, b.name);
      require(c.has("body[].inertia_kgm2", k) && smallest_eigenvalue(b.inertia_kgm2) > 0.0,
              "{}: moving body '{}' needs an inertia tensor that is positive definite (smallest principal moment {:g} "
              "kg*m^2)",
              c.where("body[].inertia_kgm2", k), b.name, smallest_eigenvalue(b.inertia_kgm2));
    }
    m.bodies.push_back(b);
  }
  require(std::any_of(m.bodies.begin(), m.bodies.end(), [](const sp::Body& b) { return b.fixed; }),
          "{}: no [[body]] has fixed = true (the ground)", c.path().string());

  for (std::size_t k = 0; k < c.count("point"); ++k) {
    sp::Body& b = m.bodies[r.body(m.bodies, "point[].body", k)];
    const std::string name = c.text_value("point[].name", k);
    require(valid_name(name) && name != "origin",
            "{} = \"{}\": a point name may hold letters, digits, '_', '-' and '.' and is not 'origin'",
            c.where("point[].name", k), name);
    require(!b.points.contains(name), "{} = \"{}\": body '{}' already has a point of that name",
            c.where("point[].name", k), name, b.name);
    b.points[name] = c.vector3("point[].at_mm", k);
  }
  for (std::size_t k = 0; k < c.count("point_mass"); ++k) {
    sp::Body& b = m.bodies[r.body(m.bodies, "point_mass[].body", k)];
    sp::PointMass pm;
    pm.name = c.text_value("point_mass[].name", k);
    pm.mass_kg = c.number("point_mass[].mass_kg", k);
    if (c.has("point_mass[].at_mm", k)) pm.position_body = c.vector3("point_mass[].at_mm", k);
    if (c.has("point_mass[].at_point", k)) {
      require(!c.has("point_mass[].at_mm", k), "{}: give at_mm or at_point, not both",
              c.where("point_mass[].at_point", k));
      const std::string point = r.point(b, "point_mass[].at_point", k);
      pm.position_body = point == "origin" ? Eigen::Vector3d::Zero() : b.points.at(point);
    }
    pm.inertia_kgm2 = r.inertia("point_mass[].inertia_kgm2", k);
    require(smallest_eigenvalue(pm.inertia_kgm2) >= -1e-12 * pm.inertia_kgm2.cwiseAbs().maxCoeff(),
            "{}: the inertia of point mass '{}' has a negative principal moment ({:g} kg*m^2)",
            c.where("point_mass[].inertia_kgm2", k), pm.name, smallest_eigenvalue(pm.inertia_kgm2));
    b.point_masses.push_back(pm);
  }

  std::set<std::string> constraint_names;  // joints and motion drives share one namespace
  std::vector<std::string> joint_names;
  for (std::size_t k = 0; k < c.count("joint"); ++k) {
    sp::Joint j;
    j.name = r.name_key("joint[].name", k, "joint or motion drive", constraint_names);
    joint_names.push_back(j.name);
    const std::string type = c.text_value("joint[].type", k);
    const auto named = sp::joint_type_named(type);
    require(named.has_value() && offered(*named), "{} = \"{}\": unknown joint type", c.where("joint[].type", k), type);
    j.type = *named;
    const sp::JointFacts& facts = sp::joint_facts(j.type);
    const std::size_t bi = r.body(m.bodies, "joint[].body_i", k), bj = r.body(m.bodies, "joint[].body_j", k);
    require(bi != bj, "{} = \"{}\": a joint connects two different bodies", c.where("joint[].body_j", k),
            m.bodies[bj].name);
    j.body_i = m.bodies[bi].name;
    j.body_j = m.bodies[bj].name;
    j.point_i = r.point(m.bodies[bi], "joint[].point_i", k);
    j.point_j = r.point(m.bodies[bj], "joint[].point_j", k);
    const bool axis = uses_axis(j.type);
    // (axis_i at its default, as the template writes it, says nothing)
    const bool axis_i_given =
        c.has("joint[].axis_i", k) && c.vector3("joint[].axis_i", k) != spec_default_vector("joint[].axis_i");
    require(axis || !axis_i_given, "{}: a {} joint has no axis", c.where("joint[].axis_i", k), type);
    require(axis || !c.has("joint[].axis_j", k), "{}: a {} joint has no axis", c.where("joint[].axis_j", k), type);
    require(facts.holds_rotation || !c.has("joint[].rotation_deg", k),
            "{}: only for prismatic and fixed joints (this one is {})", c.where("joint[].rotation_deg", k), type);
    if (axis) {
      j.axis_i = r.axis("joint[].axis_i", k, j.name);
      if (c.has("joint[].axis_j", k)) {
        j.axis_j = r.axis("joint[].axis_j", k, j.name);
      } else {
        require(j.type != sp::JointType::Universal,
                "{}: joint '{}' is universal: give axis_j, the cross axis in body_j's frame",
                c.where("joint[].type", k), j.name);
        const Eigen::Matrix3d ri = sp::rotation(m.bodies[bi].euler_parameters),
                              rj = sp::rotation(m.bodies[bj].euler_parameters);
        j.axis_j = rj.transpose() * ri * j.axis_i;
      }
    }
    if (c.has("joint[].rotation_deg", k)) j.rotation_rad = c.number("joint[].rotation_deg", k);
    m.joints.push_back(j);
  }

  for (std::size_t k = 0; k < c.count("motion_drive"); ++k) {
    const std::string p = "motion_drive[].";
    sp::MotionDrive d;
    d.name = r.name_key(p + "name", k, "joint or motion drive", constraint_names);
    d.joint = c.text_value(p + "joint", k);
    const auto joint =
        std::find_if(m.joints.begin(), m.joints.end(), [&](const sp::Joint& j) { return j.name == d.joint; });
    require(joint != m.joints.end(), "{} = \"{}\": no joint of that name (joints: {})", c.where(p + "joint", k),
            d.joint, join_names(joint_names));
    const sp::JointFacts& facts = sp::joint_facts(joint->type);
    require(facts.drives_rotation || facts.drives_translation,
            "{} = \"{}\": a {} joint has no coordinate to drive (revolute, prismatic and cylindrical joints have)",
            c.where(p + "joint", k), d.joint, facts.name);
    std::string coordinate;
    if (c.has(p + "coordinate", k)) {
      coordinate = c.text_value(p + "coordinate", k);
      const bool takes = coordinate == "rotation" ? facts.drives_rotation : facts.drives_translation;
      require(takes, "{} = \"{}\": joint '{}' is {}, it has no driven {}", c.where(p + "coordinate", k), coordinate,
              d.joint, facts.name, coordinate);
    } else {
      require(!(facts.drives_rotation && facts.drives_translation),
              "{} = \"{}\": joint '{}' is cylindrical: give coordinate = \"rotation\" or \"translation\"",
              c.where(p + "joint", k), d.joint, d.joint);
      coordinate = facts.drives_rotation ? "rotation" : "translation";
    }
    const bool angle = coordinate == "rotation";
    d.coordinate = angle ? sp::DriveCoordinate::Rotation : sp::DriveCoordinate::Translation;
    d.law = read_motion_law(c, p, "law", angle, k);
    d.initial = coordinate_number(c, p, "initial", "_deg", "_mm", angle, k);
    m.motion_drives.push_back(d);
  }

  std::set<std::string> spring_names, force_names;
  for (std::size_t k = 0; k < c.count("spring"); ++k) {
    sp::Spring s;
    s.name = r.name_key("spring[].name", k, "spring", spring_names);
    const std::size_t bi = r.body(m.bodies, "spring[].body_i", k), bj = r.body(m.bodies, "spring[].body_j", k);
    s.body_i = m.bodies[bi].name;
    s.body_j = m.bodies[bj].name;
    s.point_i = r.point(m.bodies[bi], "spring[].point_i", k);
    s.point_j = r.point(m.bodies[bj], "spring[].point_j", k);
    s.stiffness_N_per_m = c.number("spring[].stiffness_n_per_m", k);
    s.damping_Ns_per_m = c.number("spring[].damping_ns_per_m", k);
    s.free_length_m = c.number("spring[].free_length_mm", k);
    m.springs.push_back(s);
  }
  for (std::size_t k = 0; k < c.count("point_force"); ++k) {
    sp::PointForce f;
    f.name = r.name_key("point_force[].name", k, "point force", force_names);
    const std::size_t b = r.body(m.bodies, "point_force[].body", k);
    f.body = m.bodies[b].name;
    f.point = r.point(m.bodies[b], "point_force[].point", k);
    f.force_world = c.vector3("point_force[].force_n", k);
    m.point_forces.push_back(f);
  }

  m.gravity = c.vector3("gravity.vector_m_s2");
  double length = c.number("simulation.characteristic_length_mm");
  if (length == 0.0) {
    const Eigen::Vector3d o = m.bodies.front().position;
    for (const sp::Body& b : m.bodies) {
      length = std::max(length, (b.position - o).norm());
      for (const auto& [n, p] : b.points) length = std::max(length, p.norm());
    }
    if (length == 0.0) length = 1.0;
  }
  m.characteristic_length_m = length;
  return m;
}

EnergyBalance energy_balance(const sp::System& system, const sp::Results& results) {
  EnergyBalance b;
  const std::vector<sp::Frame>& frames = results.frames;
  if (frames.size() < 2) return b;
  const Eigen::MatrixXd mass = system.mass_matrix();
  std::vector<double> t, drive_power, applied_power;
  double peak = 0.0;
  for (const sp::Frame& f : frames) {
    double drive = 0.0;
    for (const sp::DriveState& d : f.drives) drive += d.effort * d.s_dot;
    const double applied = f.v.size() ? f.v.dot(system.forces(f.q, f.v, f.t)) : 0.0;
    const double kinetic_rate = f.v.size() ? f.v.dot(mass * f.v_dot) : 0.0;
    t.push_back(f.t);
    drive_power.push_back(drive);
    applied_power.push_back(applied);
    b.power_residual_W.push_back(kinetic_rate - applied - drive);
    peak = std::max({peak, std::abs(drive), std::abs(applied), std::abs(kinetic_rate)});
  }
  const double power_scale = peak > 0.0 ? peak : 1.0;
  for (double r : b.power_residual_W)
    b.power_balance_error = std::max(b.power_balance_error, std::abs(r) / power_scale);
  b.drive_work_J = integrate(t, drive_power);
  b.applied_work_J = integrate(t, applied_power);
  b.kinetic_gain_J = system.kinetic_energy(frames.back().v) - system.kinetic_energy(frames.front().v);
  b.potential_gain_J = system.potential_energy(frames.back().q) - system.potential_energy(frames.front().q);
  b.nonconservative_work_J = b.applied_work_J + b.potential_gain_J;
  const double work_scale = peak > 0.0 ? peak * (t.back() - t.front()) : 1.0;
  b.work_energy_error = std::abs(b.drive_work_J + b.applied_work_J - b.kinetic_gain_J) / work_scale;
  return b;
}

MechanismCaseSummary run_spatial_linkage(const CaseFile& c, const RunOptions& options) {
  Stopwatch total;
  const std::string name = mechanism_case_name(c);

  // ---- read the case ------------------------------------------------------------
  const sp::Model model = read_spatial_linkage_model(c);
  const std::string method = c.text_value("simulation.method");
  const Log log =
      start_case_log(c, options, name,
                     fmt::format("spatial linkage: {} bodies, {} joints, {} motion drives, {} springs, {} point "
                                 "forces; {}",
                                 model.bodies.size(), model.joints.size(), model.motion_drives.size(),
                                 model.springs.size(), model.point_forces.size(), method));
  const double duration = c.number("simulation.duration_s");
  const long intervals = c.integer("simulation.output_times") - 1;
  // The run's frames: the output times, each interval split evenly so that the
  // energy checks integrate over at least kEnergyCheckIntervals (an even count).
  long split = std::max(1L, (kEnergyCheckIntervals + intervals - 1) / intervals);
  if ((split * intervals) % 2) ++split;
  const std::vector<double> times = mech::equally_spaced_times(duration, split * intervals + 1);
  sp::DynamicsOptions dynamics;
  dynamics.relative_tolerance = c.number("simulation.relative_tolerance");
  dynamics.absolute_tolerance = c.number("simulation.absolute_tolerance");
  dynamics.max_step_s = c.number("simulation.max_step_s");
  dynamics.initial_step_s = c.number("simulation.initial_step_s");

  // ---- compile, assemble, run --------------------------------------------------
  std::unique_ptr<sp::System> system;
  int dof = 0;
  try {
    system = std::make_unique<sp::System>(model);
    const Eigen::VectorXd q0 = sp::assemble(*system, system->initial_positions(), 0.0);
    dof = sp::degrees_of_freedom(*system, q0, 0.0);
  } catch (const Error& e) {
    fail("{}: {}", c.path().string(), e.what());
  }
  require(method != "kinematic" || dof == 0,
          "{} = \"kinematic\": the mechanism has {} degrees of freedom at t = 0 s, a prescribed motion needs 0 (add "
          "[[motion_drive]] tables, or integrate it: simulation.method = \"idas\")",
          c.where("simulation.method"), dof);
  log.info("  assembled at t = 0 s: {} moving bodies, {} constraint rows, {} degrees of freedom", system->n_moving(),
           system->n_constraints(), dof);
  Stopwatch clock;
  sp::Results dense;
  try {
    dense = method == "kinematic" ? sp::run_kinematics(*system, times) : sp::simulate_ggl(*system, times, dynamics);
  } catch (const Error& e) {
    fail("{}: the motion cannot be run: {}", c.path().string(), e.what());
  }
  log.info("  {}: {} frames in {:.2f} s", dense.summary.method, dense.frames.size(), clock.seconds());
  const EnergyBalance energy = energy_balance(*system, dense);
  // A motion too inaccurate to use is refused with its values (the limits of
  // the planar runs, pipeline/motion_stages.hpp), before any results are written.
  const std::string tighten = fmt::format(
      "at relative tolerance {:g} and absolute tolerance {:g}: tighten them (simulation.relative_tolerance, "
      "simulation.absolute_tolerance)",
      dynamics.relative_tolerance, dynamics.absolute_tolerance);
  require(dense.summary.max_drift_relative <= pipeline::kMaxRelativeConstraintDrift,
          "{}: the motion ({}) is not accurate enough to use: its joints drift apart by {:.3g} of the characteristic "
          "length ({:.3g} m), more than the {:g} accepted, {}",
          c.path().string(), dense.summary.method, dense.summary.max_drift_relative, dense.summary.max_drift_position_m,
          pipeline::kMaxRelativeConstraintDrift, tighten);
  require(energy.work_energy_error <= pipeline::kMaxEnergyBalanceError,
          "{}: the motion ({}) is not accurate enough to use: its work-energy balance is off by {:.3g} of the peak "
          "power times the duration, more than the {:g} accepted, {}",
          c.path().string(), dense.summary.method, energy.work_energy_error, pipeline::kMaxEnergyBalanceError, tighten);
  sp::Results results;
  results.summary = dense.summary;
  for (std::size_t k = 0; k < dense.frames.size(); k += std::size_t(split))
    results.frames.push_back(std::move(dense.frames[k]));
  post::FieldMatrix power_residual(Eigen::Index(results.frames.size()), 1);
  for (Eigen::Index k = 0; k < power_residual.rows(); ++k)
    power_residual(k, 0) = energy.power_residual_W[std::size_t(k * split)];

  // ---- results file ----------------------------------------------------------------
  MechanismCaseSummary summary;
  summary.results_file = mechanism_results_path(c, options, name);
  post::ResultsWriter w(summary.results_file, mechanism_provenance(c, options));
  pipeline::write_spatial_mechanism_histories(w, model, results);
  w.write_history("check.power_balance_residual", "W", power_residual);
  w.commit();

  // ---- summary -------------------------------------------------------------------------
  summary.values = {{"duration_s", duration},
                    {"degrees_of_freedom", double(dof)},
                    {"redundant_rows", double(results.summary.redundant_rows)},
                    {"max_drift_relative", results.summary.max_drift_relative},
                    {"drive_work_j", energy.drive_work_J},
                    {"work_energy_error", energy.work_energy_error},
                    {"power_balance_error", energy.power_balance_error}};
  std::printf("\nSummary of '%s' (spatial linkage, %s, %zu output times over %.4g s)\n", name.c_str(), method.c_str(),
              results.frames.size(), duration);
  std::printf(
      "  %zu bodies, %zu joints, %zu motion drives; %d degrees of freedom at t = 0 s, %d redundant constraint "
      "rows\n",
      model.bodies.size(), model.joints.size(), model.motion_drives.size(), dof, results.summary.redundant_rows);
  if (!model.motion_drives.empty()) {
    std::printf("  %-16s %-12s %-11s %18s %10s %16s\n", "drive", "joint", "coordinate", "peak |effort|", "at t s",
                "peak |power| W");
    for (std::size_t d = 0; d < model.motion_drives.size(); ++d) {
      double peak = 0.0, at = 0.0, power = 0.0;
      for (const sp::Frame& f : results.frames) {
        const sp::DriveState& s = f.drives[d];
        if (std::abs(s.effort) > peak) peak = std::abs(s.effort), at = f.t;
        power = std::max(power, std::abs(s.effort * s.s_dot));
      }
      const bool rotation = model.motion_drives[d].coordinate == sp::DriveCoordinate::Rotation;
      std::printf("  %-16s %-12s %-11s %14.4f %-3s %10.4f %16.3f\n", model.motion_drives[d].name.c_str(),
                  model.motion_drives[d].joint.c_str(), rotation ? "rotation" : "translation", peak,
                  rotation ? "N m" : "N", at, power);
      summary.values.push_back({"peak_effort_" + model.motion_drives[d].name, peak});
    }
  }
  std::printf("  %-16s %-12s %14s %10s %16s %10s\n", "joint", "type", "peak |F| N", "at t s", "peak |M| N m", "at t s");
  for (std::size_t j = 0; j < model.joints.size(); ++j) {
    double force = 0.0, force_at = 0.0, moment = 0.0, moment_at = 0.0;
    for (const sp::Frame& f : results.frames) {
      const sp::Reaction& on_j = f.joints[j].on_j;
      if (on_j.force_world.norm() > force) force = on_j.force_world.norm(), force_at = f.t;
      if (on_j.moment_world.norm() > moment) moment = on_j.moment_world.norm(), moment_at = f.t;
    }
    std::printf("  %-16s %-12s %14.4f %10.4f %16.4f %10.4f\n", model.joints[j].name.c_str(),
                sp::joint_facts(model.joints[j].type).name, force, force_at, moment, moment_at);
    summary.values.push_back({"peak_reaction_force_" + model.joints[j].name + "_n", force});
    summary.values.push_back({"peak_reaction_moment_" + model.joints[j].name + "_nm", moment});
  }
  std::printf("  (reactions: the joint's load on body_j, moment about its point on body_j, world axes)\n");
  std::printf("%s", results.format_checks().c_str());
  const long check_intervals = long(times.size()) - 1;
  std::printf(
      "  power balance at every frame: max |dT/dt - applied power - drive power| = %.2e of the peak power "
      "(limit %.0e): %s\n",
      energy.power_balance_error, kPowerBalanceTolerance,
      energy.power_balance_error <= kPowerBalanceTolerance ? "ok" : "ABOVE THE LIMIT");
  std::printf(
      "  work-energy balance over the run (Simpson, %ld intervals): drive work %.6g J = dT %.6g J + dV %.6g J - "
      "dampers and point forces %.6g J; error %.2e of peak power x duration (limit %.0e): %s\n",
      check_intervals, energy.drive_work_J, energy.kinetic_gain_J, energy.potential_gain_J,
      energy.nonconservative_work_J, energy.work_energy_error, kWorkEnergyTolerance,
      energy.work_energy_error <= kWorkEnergyTolerance
          ? "ok"
          : "ABOVE THE LIMIT (a law with jumps in acceleration, e.g. trapezoidal, or a loose idas tolerance)");
  std::printf("  results: %s (+ .xdmf)\n  wall time: %.2f s\n", summary.results_file.string().c_str(), total.seconds());
  return summary;
}

}  // namespace kinetofem::app
