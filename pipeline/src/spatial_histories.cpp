#include "kinetofem/pipeline/spatial_histories.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>
#include <string>
#include <string_view>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/postproc/results_layout.hpp"

namespace kinetofem::pipeline {

namespace spatial = mech::spatial;
namespace layout = post::layout;
using Eigen::Vector3d;

namespace {

// The planar writer's rule (histories.hpp): a model's names may hold any character.
std::string clean(std::string name) {
  for (char& ch : name)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.')) ch = '_';
  return name;
}

// Rows of one history: get(frame, row) fills the row of each frame.
template <class Get>
post::FieldMatrix rows(const spatial::Results& res, int columns, Get&& get) {
  post::FieldMatrix out(Eigen::Index(res.frames.size()), columns);
  for (std::size_t k = 0; k < res.frames.size(); ++k) get(res.frames[k], out.row(Eigen::Index(k)));
  return out;
}

// Writes the 3-vector v(frame) of every frame as history `name`.
template <class Get>
void write_vector(post::ResultsWriter& w, const spatial::Results& res, const std::string& name, const char* units,
                  Get&& v) {
  w.write_history(clean(name), units,
                  rows(res, 3, [&](const spatial::Frame& f, auto row) { row = v(f).transpose(); }),
                  post::kVectorComponents);
}

template <class Get>
void write_scalar(post::ResultsWriter& w, const spatial::Results& res, const std::string& name, const char* units,
                  Get&& s) {
  w.write_history(clean(name), units, rows(res, 1, [&](const spatial::Frame& f, auto row) { row(0) = s(f); }));
}

std::string joined(const std::initializer_list<std::string_view> parts) {
  std::string out;
  for (std::string_view p : parts) out += p;
  return out;
}

void write_bodies(post::ResultsWriter& w, const spatial::Model& m, const spatial::Results& res) {
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const std::string p = joined({layout::kBodyHistoryPrefix, m.bodies[b].name, "."});
    auto body = [b](const spatial::Frame& f) -> const spatial::BodyState& { return f.bodies[b]; };
    // The origin's velocity and acceleration from the centre of mass's: c = o + R c_body,
    // so o' = c' + w x (o - c), o'' = c'' + a x (o - c) + w x (w x (o - c)).
    auto to_origin = [&](const spatial::Frame& f) { return Vector3d(body(f).origin - body(f).com); };
    write_vector(w, res, p + layout::kOrigin, "m", [&](const spatial::Frame& f) { return body(f).origin; });
    w.write_history(clean(p + layout::kEulerParameters), layout::kDimensionless,
                    rows(res, 4, [&](const spatial::Frame& f, auto row) { row = body(f).euler_parameters.transpose(); }),
                    post::kEulerParameterComponents);
    w.write_history(clean(p + layout::kRotation), layout::kDimensionless,
                    rows(res, 9,
                         [&](const spatial::Frame& f, auto row) {
                           for (int i = 0; i < 3; ++i)
                             for (int j = 0; j < 3; ++j) row(3 * i + j) = body(f).rotation(i, j);
                         }),
                    post::kRotationComponents);
    write_vector(w, res, p + layout::kVelocity, "m/s", [&](const spatial::Frame& f) {
      return Vector3d(body(f).com_velocity + body(f).angular_velocity.cross(to_origin(f)));
    });
    write_vector(w, res, p + layout::kAcceleration, "m/s^2", [&](const spatial::Frame& f) {
      const spatial::BodyState& s = body(f);
      const Vector3d r = to_origin(f);
      return Vector3d(s.com_acceleration + s.angular_acceleration.cross(r) +
                      s.angular_velocity.cross(s.angular_velocity.cross(r)));
    });
    write_vector(w, res, p + layout::kAngularVelocity, "rad/s",
                 [&](const spatial::Frame& f) { return body(f).angular_velocity; });
    write_vector(w, res, p + layout::kAngularAcceleration, "rad/s^2",
                 [&](const spatial::Frame& f) { return body(f).angular_acceleration; });
    write_vector(w, res, p + layout::kComPosition, "m", [&](const spatial::Frame& f) { return body(f).com; });
    write_vector(w, res, p + layout::kComVelocity, "m/s", [&](const spatial::Frame& f) { return body(f).com_velocity; });
    write_vector(w, res, p + layout::kComAcceleration, "m/s^2",
                 [&](const spatial::Frame& f) { return body(f).com_acceleration; });
  }
}

// The load of a joint or drive on one body: force, moment about its point, the point.
template <class Get>
void write_load(post::ResultsWriter& w, const spatial::Results& res, const std::string& owner, const std::string& body,
                Get&& reaction) {
  const std::string p = joined({owner, layout::kOnBodyPrefix, body, "."});
  write_vector(w, res, p + layout::kForceWorld, "N", [&](const spatial::Frame& f) { return reaction(f).force_world; });
  write_vector(w, res, p + layout::kMomentWorld, "N*m", [&](const spatial::Frame& f) { return reaction(f).moment_world; });
  write_vector(w, res, p + layout::kLoadPoint, "m", [&](const spatial::Frame& f) { return reaction(f).point_world; });
}

void write_joints(post::ResultsWriter& w, const spatial::Model& m, const spatial::Results& res) {
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    const std::string owner = joined({layout::kJointHistoryPrefix, m.joints[j].name, "."});
    write_load(w, res, owner, m.joints[j].body_i, [j](const spatial::Frame& f) -> const spatial::Reaction& { return f.joints[j].on_i; });
    write_load(w, res, owner, m.joints[j].body_j, [j](const spatial::Frame& f) -> const spatial::Reaction& { return f.joints[j].on_j; });
  }
}

// The model's motion drive of that name (the frames hold the motion drives).
const spatial::MotionDrive& motion_drive(const spatial::Model& m, const std::string& name) {
  for (const auto& d : m.motion_drives)
    if (d.name == name) return d;
  fail("spatial model '{}': the run has a drive '{}' that the model does not", m.name, name);
}

struct DriveUnits {
  const char *s, *s_dot, *s_ddot, *effort;
};

DriveUnits units_of(spatial::DriveCoordinate c) {
  switch (c) {
    case spatial::DriveCoordinate::Rotation: return {"rad", "rad/s", "rad/s^2", "N*m"};
    case spatial::DriveCoordinate::Translation: return {"m", "m/s", "m/s^2", "N"};
  }
  fail("unknown spatial drive coordinate {}", int(c));
}

void write_drives(post::ResultsWriter& w, const spatial::Model& m, const spatial::Results& res) {
  const spatial::Frame& first = res.frames.front();
  for (std::size_t d = 0; d < first.drives.size(); ++d) {
    const spatial::DriveState& drive = first.drives[d];
    const DriveUnits u = units_of(motion_drive(m, drive.name).coordinate);
    const std::string p = joined({layout::kDriveHistoryPrefix, drive.name, "."});
    auto state = [d](const spatial::Frame& f) -> const spatial::DriveState& { return f.drives[d]; };
    write_scalar(w, res, p + layout::kDriveCoordinate, u.s, [&](const spatial::Frame& f) { return state(f).s; });
    write_scalar(w, res, p + layout::kDriveRate, u.s_dot, [&](const spatial::Frame& f) { return state(f).s_dot; });
    write_scalar(w, res, p + layout::kDriveAcceleration, u.s_ddot, [&](const spatial::Frame& f) { return state(f).s_ddot; });
    write_scalar(w, res, p + layout::kDriveEffort, u.effort, [&](const spatial::Frame& f) { return state(f).effort; });
    write_scalar(w, res, p + layout::kDrivePower, "W",
                 [&](const spatial::Frame& f) { return state(f).effort * state(f).s_dot; });
    write_load(w, res, p, drive.on_i.body, [&](const spatial::Frame& f) -> const spatial::Reaction& { return state(f).on_i; });
    write_load(w, res, p, drive.on_j.body, [&](const spatial::Frame& f) -> const spatial::Reaction& { return state(f).on_j; });
  }
  if (m.force_drives.empty()) return;
  // A motor's effort is a function of the state, which only the compiled system evaluates.
  const spatial::System system(m);
  for (std::size_t d = 0; d < m.force_drives.size(); ++d)
    write_scalar(w, res, joined({layout::kDriveHistoryPrefix, m.force_drives[d].name, ".", layout::kDriveEffort}),
                 units_of(m.force_drives[d].coordinate).effort,
                 [&](const spatial::Frame& f) { return system.force_drive_effort(int(d), f.q, f.v, f.t); });
}

void write_checks(post::ResultsWriter& w, const spatial::Results& res) {
  write_scalar(w, res, layout::kKineticEnergy, "J", [](const spatial::Frame& f) { return f.kinetic_energy_J; });
  write_scalar(w, res, layout::kPotentialEnergy, "J", [](const spatial::Frame& f) { return f.potential_energy_J; });
  write_scalar(w, res, layout::kDriftPosition, "m", [](const spatial::Frame& f) { return f.drift_position_m; });
  write_scalar(w, res, layout::kDriftVelocity, "m/s", [](const spatial::Frame& f) { return f.drift_velocity_m_per_s; });
  write_scalar(w, res, layout::kEquilibriumResidual, layout::kDimensionless,
               [](const spatial::Frame& f) { return f.equilibrium_residual; });
  write_scalar(w, res, layout::kRedundantRows, layout::kDimensionless,
               [](const spatial::Frame& f) { return double(f.redundant_rows); });
}

// Appends an octahedron with tips a and b (nodes of `mesh`) and its square section at
// `ring` of the way from a, half-diagonal `width`: 4 new nodes, 4 TET4 of positive volume.
void add_bone(fem::Mesh& mesh, fem::Index a, fem::Index b, double ring, double width) {
  const Vector3d pa = mesh.nodes.row(a).transpose(), pb = mesh.nodes.row(b).transpose();
  const Vector3d axis = (pb - pa).normalized();
  const Vector3d u = spatial::perpendicular(axis).normalized(), v = axis.cross(u);
  const Vector3d centre = pa + ring * (pb - pa);
  const fem::Index first = mesh.node_count();
  mesh.nodes.conservativeResize(first + 4, Eigen::NoChange);
  const std::array<Vector3d, 4> corners = {u, v, -u, -v};
  for (int k = 0; k < 4; ++k) mesh.nodes.row(first + k) = (centre + width * corners[size_t(k)]).transpose();
  fem::ElementBlock& block = mesh.blocks.front();
  for (int k = 0; k < 4; ++k) {
    std::array<fem::Index, 4> tet = {a, b, first + k, first + (k + 1) % 4};
    auto at = [&](int i) -> Vector3d { return mesh.nodes.row(tet[size_t(i)]).transpose(); };
    if ((at(1) - at(0)).cross(at(2) - at(0)).dot(at(3) - at(0)) < 0) std::swap(tet[2], tet[3]);
    block.connectivity.insert(block.connectivity.end(), tet.begin(), tet.end());
  }
}

// Each body's node positions (world) and velocities at a frame.
struct SkeletonPose {
  post::FieldMatrix position, velocity, speed;
};

SkeletonPose skeleton_pose(const fem::Mesh& mesh, const spatial::BodyState& s) {
  const fem::Index n_nodes = mesh.node_count();
  SkeletonPose out{post::FieldMatrix(n_nodes, 3), post::FieldMatrix(n_nodes, 3), post::FieldMatrix(n_nodes, 1)};
  for (fem::Index n = 0; n < n_nodes; ++n) {
    const Vector3d x = s.origin + s.rotation * mesh.nodes.row(n).transpose();
    const Vector3d v = s.com_velocity + s.angular_velocity.cross(x - s.com);
    out.position.row(n) = x.transpose();
    out.velocity.row(n) = v.transpose();
    out.speed(n, 0) = v.norm();
  }
  return out;
}

void write_skeletons(post::ResultsWriter& w, const spatial::Model& m, const spatial::Results& res) {
  const std::string speed = layout::magnitude_name(layout::kVelocity);
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const fem::Mesh mesh = spatial_skeleton_mesh(m, b);
    post::BodyWriter& body = w.add_body(clean(layout::kSkeletonBodyPrefix + m.bodies[b].name), mesh);
    body.write_static(layout::kBodyPosition, "m", mesh.nodes, post::kVectorComponents);
    body.begin_series({{.name = layout::kPosition, .units = "m", .components = 3,
                        .component_names = post::kVectorComponents, .geometry = true},
                       {layout::kVelocity, "m/s", 3, post::kVectorComponents},
                       {speed, "m/s", 1, {}}});
    for (const spatial::Frame& f : res.frames) {
      const SkeletonPose pose = skeleton_pose(mesh, f.bodies[b]);
      body.write_step(f.t, {{layout::kPosition, pose.position}, {layout::kVelocity, pose.velocity}, {speed, pose.speed}});
    }
  }
}

}  // namespace

fem::Mesh spatial_skeleton_mesh(const spatial::Model& model, std::size_t body) {
  require(body < model.bodies.size(), "spatial model '{}' has {} bodies, no body {}", model.name, model.bodies.size(),
          body);
  require(model.characteristic_length_m > 0, "spatial model '{}': characteristic length {} m is not positive",
          model.name, model.characteristic_length_m);
  const spatial::Body& b = model.bodies[body];
  const double scale = model.characteristic_length_m;
  fem::Mesh mesh;
  mesh.blocks.push_back({fem::ElementType::Tet4, {}});
  std::vector<Vector3d> nodes = {Vector3d::Zero()};
  mesh.node_sets["origin"] = {0};
  for (const auto& [name, at] : b.points) {
    fem::Index node = -1;
    for (std::size_t n = 0; n < nodes.size() && node < 0; ++n)
      if ((nodes[n] - at).norm() <= kSkeletonMergeFraction * scale) node = fem::Index(n);
    if (node < 0) {
      node = fem::Index(nodes.size());
      nodes.push_back(at);
    }
    auto& set = mesh.node_sets[clean(name)];
    if (std::find(set.begin(), set.end(), node) == set.end()) set.push_back(node);
    std::sort(set.begin(), set.end());
  }
  mesh.nodes.resize(fem::Index(nodes.size()), 3);
  for (std::size_t n = 0; n < nodes.size(); ++n) mesh.nodes.row(fem::Index(n)) = nodes[n].transpose();
  const fem::Index points = mesh.node_count();
  if (points == 1) {
    // No bone: a marker about the origin, tips on the body's z axis.
    const double half = kSkeletonWidthPerModel * scale;
    mesh.nodes.conservativeResize(3, Eigen::NoChange);
    mesh.nodes.row(1) << 0.0, 0.0, -half;
    mesh.nodes.row(2) << 0.0, 0.0, half;
    add_bone(mesh, 1, 2, 0.5, half);
    return mesh;
  }
  // Prim's shortest tree from the origin: each step joins the node nearest to the tree.
  std::vector<bool> in_tree(std::size_t(points), false);
  std::vector<double> distance(std::size_t(points), std::numeric_limits<double>::infinity());
  std::vector<fem::Index> parent(std::size_t(points), 0);
  distance[0] = 0.0;
  for (fem::Index step = 0; step < points; ++step) {
    fem::Index next = -1;
    for (fem::Index n = 0; n < points; ++n)
      if (!in_tree[size_t(n)] && (next < 0 || distance[size_t(n)] < distance[size_t(next)])) next = n;
    in_tree[size_t(next)] = true;
    if (next != 0) {
      const double length = distance[size_t(next)];
      add_bone(mesh, parent[size_t(next)], next, kSkeletonRingFraction,
               std::min(kSkeletonWidthPerLength * length, kSkeletonWidthPerModel * scale));
    }
    for (fem::Index n = 0; n < points; ++n) {
      const double d = (mesh.nodes.row(n) - mesh.nodes.row(next)).norm();
      if (!in_tree[size_t(n)] && d < distance[size_t(n)]) {
        distance[size_t(n)] = d;
        parent[size_t(n)] = next;
      }
    }
  }
  return mesh;
}

void write_spatial_mechanism_histories(post::ResultsWriter& writer, const spatial::Model& model,
                                       const spatial::Results& results) {
  require(!results.frames.empty(), "spatial model '{}': no output frames to write", model.name);
  std::vector<double> times;
  for (const spatial::Frame& f : results.frames) {
    require(f.bodies.size() == model.bodies.size() && f.joints.size() == model.joints.size(),
            "spatial model '{}': the frame at t = {} s has {} bodies and {} joints, the model {} and {}", model.name,
            f.t, f.bodies.size(), f.joints.size(), model.bodies.size(), model.joints.size());
    times.push_back(f.t);
  }
  writer.set_mechanism_time(times);
  write_bodies(writer, model, results);
  write_joints(writer, model, results);
  write_drives(writer, model, results);
  write_checks(writer, results);
  write_skeletons(writer, model, results);
}

}  // namespace kinetofem::pipeline
