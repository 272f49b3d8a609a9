#include "kinetofem/loads/spatial_link_loads.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <Eigen/Geometry>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/rigid_body.hpp"

namespace kinetofem::loads {

namespace spatial = mech::spatial;

namespace {

const fem::FeModel& model_of(const SpatialLinkDefinition& link) {
  require(link.model != nullptr, "part '{}' has no FE model", link.body);
  return *link.model;
}

}  // namespace

void assign_mass_properties(spatial::Body& body, const fem::FeModel& model) {
  const fem::MassProperties mp = fem::mass_properties(model.mesh, fem::element_materials(model));
  body.mass_kg = mp.mass_kg;
  body.com_body = mp.centre_of_mass_m;
  body.inertia_kgm2 = mp.inertia_about_com_kgm2;
}

SpatialLinkLoads::SpatialLinkLoads(const SpatialLinkDefinition& link, const spatial::Model& model,
                                   double equilibrium_tolerance)
    : link_(link), patterns_(model_of(link)), tolerance_(equilibrium_tolerance) {
  for (std::size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == link.body) body_index_ = int(b);
  require(body_index_ >= 0, "part '{}': the mechanism has no body of that name", link.body);
  const spatial::Body& body = model.bodies[std::size_t(body_index_)];
  gravity_world_ = model.gravity;
  auto point_of = [&](const std::string& point) -> Eigen::Vector3d {
    if (point == "origin") return Eigen::Vector3d::Zero();
    const auto it = body.points.find(point);
    require(it != body.points.end(), "part '{}': the body has no point '{}'", link.body, point);
    return it->second;
  };

  for (const SpatialAttachment& a : link.joints) {
    Constraint c;
    c.name = a.name;
    for (std::size_t j = 0; j < model.joints.size(); ++j)
      if (model.joints[j].name == a.name) {
        c.index = int(j);
        c.on_i = model.joints[j].body_i == link.body;
        require(c.on_i || model.joints[j].body_j == link.body,
                "part '{}': joint '{}' does not act on it (it joins '{}' and '{}')", link.body, a.name,
                model.joints[j].body_i, model.joints[j].body_j);
      }
    for (std::size_t d = 0; d < model.motion_drives.size() && c.index < 0; ++d)
      if (model.motion_drives[d].name == a.name) {
        c.drive = true;
        c.index = int(d);
        const std::string& joint = model.motion_drives[d].joint;
        const auto it = std::find_if(model.joints.begin(), model.joints.end(),
                                     [&](const spatial::Joint& j) { return j.name == joint; });
        require(it != model.joints.end(), "part '{}': drive '{}' drives joint '{}' the model lacks", link.body, a.name,
                joint);
        c.on_i = it->body_i == link.body;
        require(c.on_i || it->body_j == link.body,
                "part '{}': drive '{}' does not act on it (it drives '{}' "
                "between '{}' and '{}')",
                link.body, a.name, joint, it->body_i, it->body_j);
      }
    require(c.index >= 0, "part '{}': the mechanism has no joint or motion drive '{}'", link.body, a.name);
    c.coupling = patterns_.coupling_on(a.face_set);
    constraints_.push_back(std::move(c));
  }
  for (const SpatialAttachment& a : link.point_masses) {
    const auto it = std::find_if(body.point_masses.begin(), body.point_masses.end(),
                                 [&](const spatial::PointMass& m) { return m.name == a.name; });
    require(it != body.point_masses.end(), "part '{}': the body carries no point mass '{}'", link.body, a.name);
    masses_.push_back({a.name, it->mass_kg, it->position_body, it->inertia_kgm2, patterns_.coupling_on(a.face_set)});
  }
  for (const SpatialAttachment& a : link.point_forces) {
    const auto it = std::find_if(model.point_forces.begin(), model.point_forces.end(),
                                 [&](const spatial::PointForce& f) { return f.name == a.name; });
    require(it != model.point_forces.end(), "part '{}': the mechanism has no point force '{}'", link.body, a.name);
    require(it->body == link.body, "part '{}': point force '{}' acts on body '{}'", link.body, a.name, it->body);
    forces_.push_back({a.name, it->force_world, point_of(it->point), patterns_.coupling_on(a.face_set)});
  }
  for (const SpatialSlideAttachment& a : link.slides) {
    Slide sl;
    sl.attachment = a;
    const auto joint = std::find_if(model.joints.begin(), model.joints.end(),
                                    [&](const spatial::Joint& j) { return j.name == a.joint; });
    require(joint != model.joints.end(), "part '{}': the mechanism has no joint '{}'", link.body, a.joint);
    require(joint->type == spatial::JointType::Prismatic, "part '{}': slide '{}' is a {} joint, not a prismatic one",
            link.body, a.joint, spatial::joint_facts(joint->type).name);
    sl.joint = int(joint - model.joints.begin());
    sl.guide = joint->body_i == link.body;
    require(sl.guide || joint->body_j == link.body, "part '{}': slide '{}' does not act on it (it joins '{}' and '{}')",
            link.body, a.joint, joint->body_i, joint->body_j);
    for (std::size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == joint->body_i) sl.guide_body = int(b);
    const double axis_length = joint->axis_i.norm();
    require(axis_length > 0 && std::isfinite(axis_length), "part '{}': slide '{}': its axis has zero length",
            link.body, a.joint);
    sl.axis_i = joint->axis_i / axis_length;
    if (!a.drive.empty()) {
      for (std::size_t d = 0; d < model.motion_drives.size(); ++d)
        if (model.motion_drives[d].name == a.drive) sl.drive = int(d);
      require(sl.drive >= 0 && model.motion_drives[std::size_t(sl.drive)].joint == a.joint,
              "part '{}': slide '{}': '{}' is not a motion drive of that joint", link.body, a.joint, a.drive);
    }
    require(std::isfinite(a.front_m) && std::isfinite(a.rear_m) && a.front_m != a.rear_m,
            "part '{}': slide '{}': the lands at {} m and {} m along the axis must be distinct", link.body, a.joint,
            a.front_m, a.rear_m);
    if (sl.guide) {
      sl.front = patterns_.coupling_on(a.front_face_set);
      sl.rear = patterns_.coupling_on(a.rear_face_set);
    } else {
      require(!a.stations.face_sets.empty(), "part '{}': slide '{}': the slide face has no stations", link.body,
              a.joint);
      for (const std::string& station : a.stations.face_sets) sl.stations.push_back(patterns_.coupling_on(station));
    }
    slides_.push_back(std::move(sl));
  }
}

SpatialLinkLoads::State SpatialLinkLoads::state_at(const spatial::Frame& frame) const {
  require(std::size_t(body_index_) < frame.bodies.size() && frame.bodies[std::size_t(body_index_)].name == link_.body,
          "part '{}' at t = {:.6g} s: the frame is not of the model the loads "
          "were built for",
          link_.body, frame.t);
  const spatial::BodyState& s = frame.bodies[std::size_t(body_index_)];
  const Eigen::Matrix3d R_T = s.rotation.transpose();
  const Eigen::Vector3d omega = s.angular_velocity,
                        alpha = s.angular_acceleration;  // world
  // Acceleration of a point r (world) of the body.
  auto acceleration = [&](const Eigen::Vector3d& r) -> Eigen::Vector3d {
    const Eigen::Vector3d arm = r - s.com;
    return s.com_acceleration + alpha.cross(arm) + omega.cross(omega.cross(arm));
  };
  const Eigen::Vector3d a_origin = acceleration(s.origin);
  const Eigen::Vector3d omega_b = R_T * omega, alpha_b = R_T * alpha;
  const double length_scale = patterns_.length_scale_m();

  State out;
  out.body_force = fem::RigidBodyMotionLoads::coefficients(R_T * gravity_world_, R_T * a_origin, omega_b, alpha_b);
  out.coupling.assign(std::size_t(patterns_.coupling_count()), Vector6d::Zero());
  // A load (force; moment about `point`, all body frame) entering through
  // coupling j, kept as force and moment about the coupling's centroid.
  auto through = [&](int j, const Eigen::Vector3d& force, const Eigen::Vector3d& moment, const Eigen::Vector3d& point) {
    Vector6d& r = out.coupling[std::size_t(j)];
    r.head<3>() += force;
    r.tail<3>() += moment + (point - patterns_.coupling(j).centroid()).cross(force);
  };
  double magnitude = patterns_.body_force().mass_kg() *
                     (gravity_world_.norm() + a_origin.norm() + length_scale * (alpha.norm() + omega.squaredNorm()));

  for (const Constraint& c : constraints_) {
    const spatial::Reaction& r =
        c.drive ? (c.on_i ? frame.drives.at(std::size_t(c.index)).on_i : frame.drives.at(std::size_t(c.index)).on_j)
                : (c.on_i ? frame.joints.at(std::size_t(c.index)).on_i : frame.joints.at(std::size_t(c.index)).on_j);
    through(c.coupling, R_T * r.force_world, R_T * r.moment_world, R_T * (r.point_world - s.origin));
    magnitude += r.force_world.norm() + r.moment_world.norm() / length_scale;
  }
  for (const Mass& m : masses_) {
    const Eigen::Vector3d force =
        R_T * (m.mass_kg * (gravity_world_ - acceleration(s.origin + s.rotation * m.position_body)));
    const Eigen::Vector3d moment = -(m.inertia_kgm2 * alpha_b + omega_b.cross(m.inertia_kgm2 * omega_b));
    through(m.coupling, force, moment, m.position_body);
    magnitude += force.norm() + moment.norm() / length_scale;
  }
  for (const Slide& sl : slides_) {
    // The joint's (and drive's) load on the guide, about its joint point.
    const spatial::JointState& joint = frame.joints.at(std::size_t(sl.joint));
    const Eigen::Vector3d p_i = joint.on_i.point_world;
    Eigen::Vector3d force = joint.on_i.force_world, moment = joint.on_i.moment_world;
    if (sl.drive >= 0) {
      const spatial::Reaction& d = frame.drives.at(std::size_t(sl.drive)).on_i;
      force += d.force_world;
      moment += d.moment_world + (d.point_world - p_i).cross(d.force_world);
    }
    const Eigen::Vector3d h = frame.bodies.at(std::size_t(sl.guide_body)).rotation * sl.axis_i;
    const Eigen::Vector3d force_along = force.dot(h) * h, moment_along = moment.dot(h) * h;
    const Eigen::Vector3d force_across = force - force_along, moment_across = moment - moment_along;
    const double x_front = sl.attachment.front_m, x_rear = sl.attachment.rear_m;
    const Eigen::Vector3d w = moment_across.cross(h);
    const Eigen::Vector3d front_across = (w - x_rear * force_across) / (x_front - x_rear);
    const std::array<Eigen::Vector3d, 2> land_force = {front_across + 0.5 * force_along,
                                                       force_across - front_across + 0.5 * force_along};
    const std::array<Eigen::Vector3d, 2> land_point = {p_i + x_front * h, p_i + x_rear * h};
    const Eigen::Vector3d land_moment = 0.5 * moment_along;
    magnitude += force.norm() + moment.norm() / length_scale;
    if (sl.guide) {
      const std::array<int, 2> coupling = {sl.front, sl.rear};
      for (int k = 0; k < 2; ++k)
        through(coupling[std::size_t(k)], R_T * land_force[std::size_t(k)], R_T * land_moment,
                R_T * (land_point[std::size_t(k)] - s.origin));
      continue;
    }
    // The slider: the same loads reversed, at the stations bracketing each land.
    const Eigen::Vector3d p_j = joint.on_j.point_world;
    for (int k = 0; k < 2; ++k) {
      const double along = h.dot(land_point[std::size_t(k)] - p_j);
      const StationBracket b = bracket_station(
          sl.attachment.stations, along,
          fmt::format("part '{}' at t = {:.6g} s: slide '{}', {} land", link_.body, frame.t, sl.attachment.joint,
                      k == 0 ? "front" : "rear"));
      const Eigen::Vector3d f = -(R_T * land_force[std::size_t(k)]), m = -(R_T * land_moment);
      const Eigen::Vector3d at = R_T * (land_point[std::size_t(k)] - s.origin);
      through(sl.stations[std::size_t(b.a)], (1.0 - b.weight_b) * f, (1.0 - b.weight_b) * m, at);
      if (b.b != b.a) through(sl.stations[std::size_t(b.b)], b.weight_b * f, b.weight_b * m, at);
    }
  }
  for (const Force& f : forces_) {
    through(f.coupling, R_T * f.force_world, Eigen::Vector3d::Zero(), f.point_body);
    magnitude += f.force_world.norm();
  }

  const Vector6d total = patterns_.resultant(out.body_force, out.coupling);
  out.equilibrium_residual =
      magnitude > 0 ? std::max(total.head<3>().norm(), total.tail<3>().norm() / length_scale) / magnitude : 0.0;
  if (!(out.equilibrium_residual <= tolerance_) && !link_.held_on_foundation)
    fail(
        "part '{}' at t = {:.6g} s: the transferred loads are out of "
        "equilibrium by {:.2e} of their magnitude "
        "(resultant {:.4g} N, {:.4g} N m; tolerance {:.0e}): the multibody "
        "body and the FE model disagree in mass "
        "properties, or a load is missing",
        link_.body, frame.t, out.equilibrium_residual, total.head<3>().norm(), total.tail<3>().norm(), tolerance_);
  return out;
}

LinkLoadCoefficients SpatialLinkLoads::coefficients_at(const spatial::Frame& frame) const {
  const State state = state_at(frame);
  LinkLoadCoefficients out;
  out.coefficients = patterns_.coefficients(state.body_force, state.coupling);
  out.equilibrium_residual = state.equilibrium_residual;
  return out;
}

Eigen::VectorXd SpatialLinkLoads::loads_at(const spatial::Frame& frame) const {
  const State state = state_at(frame);
  return patterns_.nodal_forces(state.body_force, state.coupling);
}

PatternLoadHistory SpatialLinkLoads::history(const std::vector<spatial::Frame>& frames) const {
  PatternLoadHistory h;
  h.part = link_.body;
  h.names = pattern_names();
  h.patterns = pattern_forces();
  h.coefficients.resize(pattern_count(), Eigen::Index(frames.size()));
  for (std::size_t t = 0; t < frames.size(); ++t) {
    const LinkLoadCoefficients c = coefficients_at(frames[t]);
    h.coefficients.col(Eigen::Index(t)) = c.coefficients;
    h.worst_equilibrium_residual = std::max(h.worst_equilibrium_residual, c.equilibrium_residual);
    h.times.push_back(frames[t].t);
  }
  return h;
}

}  // namespace kinetofem::loads
