#include "kinetofem/loads/link_loads.hpp"

#include "kinetofem/solver/rigid_body.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/iso_fit.hpp"

namespace kinetofem::loads {

namespace {

Eigen::Vector3d lift(const Eigen::Vector2d& v) { return Eigen::Vector3d(v.x(), v.y(), 0.0); }

// World -> body rotation of a planar body at angle theta (R^T).
Eigen::Matrix3d to_body(double theta) {
  return Eigen::AngleAxisd(-theta, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// The link's FE model; an Error if it has none.
const fem::FeModel& model_of(const LinkDefinition& link) {
  require(link.model != nullptr, "link '{}' has no FE model", link.body);
  return *link.model;
}

}  // namespace

void assign_mass_properties(mech::Body& body, const fem::FeModel& model) {
  const fem::MassProperties mp = fem::mass_properties(model.mesh, fem::element_materials(model));
  body.mass_kg = mp.mass_kg;
  body.com_body = mp.centre_of_mass_m.head<2>();
  body.inertia_kgm2 = mp.inertia_about_com_kgm2(2, 2);
}

LinkLoads::LinkLoads(const LinkDefinition& link, const mech::MultibodyModel& model,
                     double equilibrium_tolerance)
    : link_(link),
      tolerance_(equilibrium_tolerance),
      patterns_(model_of(link)) {
  const fem::Mesh& mesh = link.model->mesh;
  for (size_t b = 0; b < model.bodies.size(); ++b)
    if (model.bodies[b].name == link.body) body_index_ = int(b);
  require(body_index_ >= 0, "link '{}': the mechanism has no body of that name", link.body);
  const mech::Body& body = model.bodies[size_t(body_index_)];
  gravity_world_ = lift(model.gravity);
  const double length_scale = patterns_.length_scale_m();
  // The z of a face's centroid: where the loads through it act along the
  // pins (header). A face centred on the mid-plane to within 1e-6 of the
  // part's size lies on it: the unstructured mesh of a symmetric bore puts
  // its centroid a few 1e-9 m off z = 0, a difference of discretisation,
  // not of design, that would otherwise give every planar link spurious
  // out-of-plane moments.
  auto face_z = [&](int coupling) {
    const double z = patterns_.coupling(coupling).centroid().z();
    return std::abs(z) <= 1e-6 * length_scale ? 0.0 : z;
  };

  for (const auto& attachment : link.joints) {
    Attached a;
    a.joint = attachment.joint;
    a.distribution = attachment.distribution;
    for (size_t j = 0; j < model.joints.size(); ++j)
      if (model.joints[j].name == attachment.joint) a.joint_index = int(j);
    require(a.joint_index >= 0, "link '{}': the mechanism has no joint '{}'", link.body,
            attachment.joint);
    const mech::Joint& joint = model.joints[size_t(a.joint_index)];
    require(joint.body_i == link.body || joint.body_j == link.body,
            "link '{}': joint '{}' does not act on it (it joins '{}' and '{}')", link.body,
            joint.name, joint.body_i, joint.body_j);
    a.on_i = joint.body_i == link.body;
    const std::string& point = a.on_i ? joint.point_i : joint.point_j;
    Eigen::Vector2d p = Eigen::Vector2d::Zero();
    if (point != "origin") {
      auto it = body.points.find(point);
      require(it != body.points.end(), "link '{}': joint '{}' names point '{}' the body lacks",
              link.body, joint.name, point);
      p = it->second;
    }
    a.bore = {attachment.face_set, lift(p), Eigen::Vector3d::UnitZ()};
    switch (a.distribution) {
      case BoreLoad::DistributingCoupling:
        break;
      case BoreLoad::BearingPressure:
        require(mech::joint_facts(joint.type).bearing_pressure,
                "link '{}': joint '{}': a bearing pressure needs a revolute (pin) joint", link.body, joint.name);
        break;
      case BoreLoad::Contact:
        require(mech::joint_facts(joint.type).bearing_pressure,
                "link '{}': joint '{}': contact needs a revolute (pin) joint", link.body, joint.name);
        require(std::isfinite(attachment.clearance_m) && attachment.clearance_m >= 0,
                "link '{}': joint '{}': the pin's clearance {} m is negative (an interference fit is not supported)",
                link.body, joint.name, attachment.clearance_m);
        break;
    }
    mesh.face_set(attachment.face_set);  // throws naming the sets present
    a.coupling = patterns_.coupling_on(attachment.face_set);
    a.bore.axis_point_m.z() = face_z(a.coupling);
    has_bearing_pressure_ = has_bearing_pressure_ || a.distribution == BoreLoad::BearingPressure;
    if (a.distribution == BoreLoad::Contact) {
      for (const auto& other : contact_bores_)
        require(other.bore.face_set != attachment.face_set,
                "link '{}': joints '{}' and '{}' are both in contact with face set '{}': one pin per bore",
                link.body, other.joint, joint.name, attachment.face_set);
      const Eigen::Vector3d centre = patterns_.coupling(a.coupling).centroid();
      double radius = 0.0;
      for (const fem::Index n : patterns_.coupling(a.coupling).nodes())
        radius += (mesh.nodes.row(n).transpose() - centre).head<2>().norm() /
                  double(patterns_.coupling(a.coupling).nodes().size());
      double clearance = 0.0;
      try {
        clearance = radial_clearance(attachment.clearance_m, attachment.fit, 2 * radius);
      } catch (const Error& e) {
        fail("link '{}': joint '{}' on face set '{}': {}", link.body, joint.name, attachment.face_set, e.what());
      }
      contact_bores_.push_back({joint.name, {attachment.face_set, centre, Eigen::Vector3d::UnitZ()},
                                12 + 6 * a.coupling, clearance, 2 * radius, attachment.pin_material});
    }
    a.revolute = mech::joint_facts(joint.type).out_of_plane_pin;
    joints_.push_back(std::move(a));
  }
  require(!(has_bearing_pressure_ && !contact_bores_.empty()),
          "link '{}': a cosine bearing pressure and a pin in contact on one part are not supported together "
          "(the contact needs fixed load patterns): use coupling or contact for joint '{}'",
          link.body, contact_bores_.empty() ? std::string() : contact_bores_.front().joint);
  for (const auto& attachment : link.point_masses) {
    Mass m;
    m.name = attachment.point_mass;
    bool found = false;
    for (const auto& pm : body.point_masses)
      if (pm.name == attachment.point_mass) {
        m.mass_kg = pm.mass_kg;
        m.position_body = lift(pm.position_body);
        found = true;
      }
    require(found, "link '{}': the body carries no point mass '{}'", link.body,
            attachment.point_mass);
    m.coupling = patterns_.coupling_on(attachment.face_set);
    m.position_body.z() = face_z(m.coupling);
    masses_.push_back(std::move(m));
  }
  auto body_of = [&](const std::string& name) {
    for (size_t b = 0; b < model.bodies.size(); ++b)
      if (model.bodies[b].name == name) return int(b);
    fail("link '{}': the mechanism has no body '{}'", link.body, name);
  };
  auto point_of = [&](int b, const std::string& point) -> Eigen::Vector2d {
    if (point == "origin") return Eigen::Vector2d::Zero();
    const auto& points = model.bodies[size_t(b)].points;
    const auto it = points.find(point);
    require(it != points.end(), "link '{}': body '{}' has no point '{}'", link.body, model.bodies[size_t(b)].name,
            point);
    return it->second;
  };
  for (const auto& attachment : link.drives) {
    Drive d;
    d.name = attachment.drive;
    int index = 0;
    const mech::RelativeCoordinate* coordinate = nullptr;
    for (const auto& drive : model.motion_drives) {
      if (drive.name == d.name) {
        d.drive_index = index;
        coordinate = &drive.coordinate;
      }
      ++index;
    }
    for (const auto& drive : model.force_drives) {
      if (drive.name == d.name) {
        d.drive_index = index;
        coordinate = &drive.coordinate;
      }
      ++index;
    }
    require(coordinate != nullptr, "link '{}': the mechanism has no drive '{}'", link.body, d.name);
    require(coordinate->body_i == link.body || coordinate->body_j == link.body,
            "link '{}': drive '{}' does not act on it", link.body, d.name);
    d.on_j = coordinate->body_j == link.body;
    d.coupling = patterns_.coupling_on(attachment.face_set);
    if (coordinate->type == mech::CoordinateType::Displacement) {
      const double length = coordinate->axis_i.norm();
      require(length > 0 && std::isfinite(length), "link '{}': drive '{}': its axis has zero length", link.body, d.name);
      d.displacement = true;
      d.axis_i = coordinate->axis_i / length;
      d.body_i = body_of(coordinate->body_i);
      d.body_j = body_of(coordinate->body_j);
      d.point_i = point_of(d.body_i, coordinate->point_i);
      d.point_j = point_of(d.body_j, coordinate->point_j);
    }
    drives_.push_back(std::move(d));
  }
  for (const auto& attachment : link.transmissions) {
    TransmissionLoad t;
    t.name = attachment.transmission;
    t.side = attachment.side;
    const mech::Transmission* found = nullptr;
    for (size_t k = 0; k < model.transmissions.size(); ++k)
      if (model.transmissions[k].name == t.name) {
        found = &model.transmissions[k];
        t.transmission_index = int(k);
      }
    require(found != nullptr, "link '{}': the mechanism has no transmission '{}'", link.body, t.name);
    const bool input = t.side == TransmissionSide::Input;
    const mech::RelativeCoordinate& coordinate = input ? found->input : found->output;
    require(coordinate.body_i == link.body || coordinate.body_j == link.body,
            "link '{}': transmission '{}' does not act on it through its {} coordinate", link.body, t.name,
            input ? "input" : "output");
    t.on_j = coordinate.body_j == link.body;
    t.coupling = patterns_.coupling_on(attachment.face_set);
    transmissions_.push_back(std::move(t));
  }
  model_springs_ = model.springs;
  for (const auto& sp : model.springs) {
    spring_body_i_.push_back(body_of(sp.body_i));
    spring_body_j_.push_back(body_of(sp.body_j));
    spring_point_i_.push_back(point_of(spring_body_i_.back(), sp.point_i));
    spring_point_j_.push_back(point_of(spring_body_j_.back(), sp.point_j));
  }
  for (const auto& attachment : link.springs) {
    Spring s;
    s.name = attachment.spring;
    for (size_t k = 0; k < model.springs.size(); ++k)
      if (model.springs[k].name == s.name) s.spring_index = int(k);
    require(s.spring_index >= 0, "link '{}': the mechanism has no spring '{}'", link.body, s.name);
    const mech::Spring& sp = model.springs[size_t(s.spring_index)];
    require(sp.body_i == link.body || sp.body_j == link.body, "link '{}': spring '{}' does not act on it", link.body,
            s.name);
    s.on_i = sp.body_i == link.body;
    s.point_body = lift(s.on_i ? spring_point_i_[size_t(s.spring_index)] : spring_point_j_[size_t(s.spring_index)]);
    s.coupling = patterns_.coupling_on(attachment.face_set);
    s.point_body.z() = face_z(s.coupling);
    springs_.push_back(std::move(s));
  }
  for (const auto& attachment : link.point_forces) {
    PointForce f;
    f.name = attachment.point_force;
    const mech::PointForce* found = nullptr;
    for (const auto& pf : model.point_forces)
      if (pf.name == f.name) found = &pf;
    require(found != nullptr, "link '{}': the mechanism has no point force '{}'", link.body, f.name);
    require(found->body == link.body, "link '{}': point force '{}' acts on body '{}'", link.body, f.name, found->body);
    f.force_world = lift(found->force_world);
    f.point_body = lift(point_of(body_index_, found->point));
    f.coupling = patterns_.coupling_on(attachment.face_set);
    f.point_body.z() = face_z(f.coupling);
    point_forces_.push_back(std::move(f));
  }
}

LinkLoads::LoadState LinkLoads::state_at(const mech::Frame& frame) const {
  const fem::Mesh& mesh = link_.model->mesh;
  const mech::BodyFrame& state = frame.bodies.at(size_t(body_index_));
  const double theta = state.q.z();
  const Eigen::Matrix3d R_T = to_body(theta);
  const Eigen::Vector3d omega(0, 0, state.q_dot.z()), alpha(0, 0, state.q_ddot.z());
  const Eigen::Vector3d origin_world = lift(state.q.head<2>());
  const Eigen::Vector3d a_origin_world = lift(state.q_ddot.head<2>());

  LoadState out;
  out.body_force = fem::RigidBodyMotionLoads::coefficients(R_T * gravity_world_, R_T * a_origin_world, omega, alpha);
  out.coupling.assign(size_t(patterns_.coupling_count()), Vector6d::Zero());
  const double length_scale = patterns_.length_scale_m();
  // A resultant (force, moment about `point`) entering through coupling j,
  // kept as force and moment about the coupling's centroid.
  auto through = [&](int j, const Eigen::Vector3d& force, const Eigen::Vector3d& moment, const Eigen::Vector3d& point) {
    Vector6d& r = out.coupling[size_t(j)];
    r.head<3>() += force;
    r.tail<3>() += moment + (point - patterns_.coupling(j).centroid()).cross(force);
  };
  double magnitude = patterns_.body_force().mass_kg() *
                     (gravity_world_.norm() + a_origin_world.norm() +
                      length_scale * (alpha.norm() + omega.squaredNorm()));

  for (const auto& a : joints_) {
    const mech::JointFrame& jf = frame.joints.at(size_t(a.joint_index));
    const mech::Reaction& r = a.on_i ? jf.on_i : jf.on_j;
    const Eigen::Vector3d force = lift(r.force_body);
    Eigen::Vector3d point = R_T * (lift(r.point_world) - origin_world);
    point.z() = a.bore.axis_point_m.z();  // in the bore (header)
    const Eigen::Vector3d moment(0, 0, r.moment_Nm);
    if (a.distribution == BoreLoad::BearingPressure) {
      if (out.bearing_forces.size() == 0) out.bearing_forces = Eigen::VectorXd::Zero(3 * mesh.node_count());
      fem::BoreGeometry bore = a.bore;
      bore.axis_point_m = point;
      fem::add_bearing_pressure(mesh, bore, force, out.bearing_forces);
    } else {
      through(a.coupling, force, moment, point);
    }
    magnitude += force.norm() + std::abs(r.moment_Nm) / length_scale;
  }
  for (const auto& m : masses_) {
    const Eigen::Vector3d r_world = R_T.transpose() * m.position_body;
    const Eigen::Vector3d a_world =
        a_origin_world + alpha.cross(r_world) + omega.cross(omega.cross(r_world));
    const Eigen::Vector3d force = R_T * (m.mass_kg * (gravity_world_ - a_world));
    through(m.coupling, force, Eigen::Vector3d::Zero(), m.position_body);
    magnitude += force.norm();
  }
  for (const auto& d : drives_) {
    const double effort = frame.drives.at(size_t(d.drive_index)).effort;
    if (!d.displacement) {
      const Eigen::Vector3d moment(0, 0, d.on_j ? effort : -effort);
      through(d.coupling, Eigen::Vector3d::Zero(), moment, patterns_.coupling(d.coupling).centroid());
      magnitude += std::abs(effort) / length_scale;
      continue;
    }
    // s = t . (r_Pj - r_Pi), t = axis_i turned with body_i: the effort pushes
    // body_j along t at P_j and body_i back at P_i, and, since t turns with
    // body_i, adds the couple effort (t x (P_j - P_i)) . e_z on body_i (the
    // generalised force of d s / d theta_i); the pair is self-equilibrated.
    auto world = [&](int b, const Eigen::Vector2d& p) {
      const mech::BodyFrame& bf = frame.bodies.at(size_t(b));
      return Eigen::Vector2d(bf.q.head<2>() + Eigen::Rotation2Dd(bf.q.z()) * p);
    };
    const Eigen::Vector2d t = Eigen::Rotation2Dd(frame.bodies.at(size_t(d.body_i)).q.z()) * d.axis_i;
    const Eigen::Vector2d span = world(d.body_j, d.point_j) - world(d.body_i, d.point_i);
    const double sign = d.on_j ? 1.0 : -1.0;
    const Eigen::Vector3d force_world(sign * effort * t.x(), sign * effort * t.y(), 0.0);
    const double couple = d.on_j ? 0.0 : effort * (t.x() * span.y() - t.y() * span.x());
    Eigen::Vector3d point = lift(d.on_j ? d.point_j : d.point_i);
    point.z() = patterns_.coupling(d.coupling).centroid().z();
    through(d.coupling, R_T * force_world, Eigen::Vector3d(0, 0, couple), point);
    magnitude += std::abs(effort) + std::abs(couple) / length_scale;
  }
  for (const auto& tr : transmissions_) {
    const mech::TransmissionFrame& tf = frame.transmissions.at(size_t(tr.transmission_index));
    const double side_moment = tr.side == TransmissionSide::Input ? tf.moment_input_Nm : tf.moment_output_Nm;
    const Eigen::Vector3d moment(0, 0, tr.on_j ? side_moment : -side_moment);
    through(tr.coupling, Eigen::Vector3d::Zero(), moment, patterns_.coupling(tr.coupling).centroid());
    magnitude += std::abs(side_moment) / length_scale;
  }

  for (const auto& sp : springs_) {
    // Tension k (L - L0) + c L' as the multibody model applies it
    // (MultibodySystem::applied_loads): +N e on point_i, -N e on point_j.
    const size_t k = size_t(sp.spring_index);
    auto world_point = [&](int b, const Eigen::Vector2d& p, Eigen::Vector2d& velocity) {
      const mech::BodyFrame& bf = frame.bodies.at(size_t(b));
      const Eigen::Vector2d r = Eigen::Rotation2Dd(bf.q.z()) * p;
      velocity = bf.q_dot.head<2>() + bf.q_dot.z() * Eigen::Vector2d(-r.y(), r.x());
      return Eigen::Vector2d(bf.q.head<2>() + r);
    };
    Eigen::Vector2d vi, vj;
    const Eigen::Vector2d pi = world_point(spring_body_i_[k], spring_point_i_[k], vi);
    const Eigen::Vector2d pj = world_point(spring_body_j_[k], spring_point_j_[k], vj);
    const double length = (pj - pi).norm();
    require(length > 0, "link '{}' at t = {:.6g} s: spring '{}' has zero length", link_.body, frame.t, sp.name);
    const Eigen::Vector2d e = (pj - pi) / length;
    const mech::Spring& model_spring = model_springs_[k];
    const double tension = model_spring.stiffness_N_per_m * (length - model_spring.free_length_m) +
                           model_spring.damping_Ns_per_m * e.dot(vj - vi);
    const Eigen::Vector3d force = R_T * lift(sp.on_i ? Eigen::Vector2d(tension * e) : Eigen::Vector2d(-tension * e));
    through(sp.coupling, force, Eigen::Vector3d::Zero(), sp.point_body);
    magnitude += force.norm();
  }
  for (const auto& pf : point_forces_) {
    const Eigen::Vector3d force = R_T * pf.force_world;
    through(pf.coupling, force, Eigen::Vector3d::Zero(), pf.point_body);
    magnitude += force.norm();
  }

  // Resultant (force; moment about the origin) of everything so far.
  auto total_resultant = [&] {
    Vector6d total = patterns_.resultant(out.body_force, out.coupling);
    if (out.bearing_forces.size() > 0) {
      Eigen::Vector3d F, M;
      fem::resultant(mesh, out.bearing_forces, Eigen::Vector3d::Zero(), F, M);
      total.head<3>() += F;
      total.tail<3>() += M;
    }
    return total;
  };

  // Out of the plane: the planar multibody model gives no force along the
  // pins and no moment about the in-plane axes, but a part whose loads do not
  // lie in its mid-plane z = 0 (a CAD part not symmetric about it, a mass
  // mounted off it) needs them, and a pin carries them (a revolute joint holds
  // the moments normal to its axis). They are given to the pins of the part,
  // split equally (one statically admissible choice; the planar components
  // are untouched and checked below).
  if (!link_.held_on_foundation) {
    std::vector<int> pins;
    for (const auto& a : joints_)
      if (a.revolute) pins.push_back(a.coupling);
    if (pins.empty())
      for (const auto& a : joints_) pins.push_back(a.coupling);
    if (!pins.empty()) {
      Eigen::Vector3d centre = Eigen::Vector3d::Zero();
      for (const int p : pins) centre += patterns_.coupling(p).centroid();
      centre /= double(pins.size());
      const Vector6d total = total_resultant();
      const Eigen::Vector3d F_all = total.head<3>();
      const Eigen::Vector3d M_centre = total.tail<3>() - centre.cross(F_all);
      const double n = double(pins.size());
      const Eigen::Vector3d force(0.0, 0.0, -F_all.z() / n);
      const Eigen::Vector3d moment(-M_centre.x() / n, -M_centre.y() / n, 0.0);
      for (const int p : pins) through(p, force, moment, patterns_.coupling(p).centroid());
      out.out_of_plane_moment_nm = M_centre.head<2>().norm();
      out.out_of_plane_force_n = std::abs(F_all.z());
    }
  }

  const Vector6d total = total_resultant();
  out.equilibrium_residual =
      magnitude > 0 ? std::max(total.head<3>().norm(), total.tail<3>().norm() / length_scale) / magnitude : 0.0;
  if (!(out.equilibrium_residual <= tolerance_) && !link_.held_on_foundation)
    fail("link '{}' at t = {:.6g} s: the transferred loads are out of equilibrium by {:.2e} of "
         "their magnitude (resultant {:.4g} N, {:.4g} N m; tolerance {:.0e}): the multibody body "
         "and the FE model disagree in mass properties, or a load is missing",
         link_.body, frame.t, out.equilibrium_residual, total.head<3>().norm(), total.tail<3>().norm(), tolerance_);
  return out;
}

LinkLoadResult LinkLoads::loads_at(const mech::Frame& frame) const {
  const LoadState state = state_at(frame);
  LinkLoadResult out;
  out.forces = patterns_.nodal_forces(state.body_force, state.coupling);
  if (state.bearing_forces.size() > 0) out.forces += state.bearing_forces;
  out.equilibrium_residual = state.equilibrium_residual;
  out.out_of_plane_moment_nm = state.out_of_plane_moment_nm;
  out.out_of_plane_force_n = state.out_of_plane_force_n;
  return out;
}

LinkLoadCoefficients LinkLoads::coefficients_at(const mech::Frame& frame) const {
  require(superposable(), "link '{}': a bearing pressure is not a combination of fixed load patterns (it turns with "
          "the force); solve it step by step", link_.body);
  const LoadState state = state_at(frame);
  LinkLoadCoefficients out;
  out.coefficients = patterns_.coefficients(state.body_force, state.coupling);
  out.equilibrium_residual = state.equilibrium_residual;
  out.out_of_plane_moment_nm = state.out_of_plane_moment_nm;
  out.out_of_plane_force_n = state.out_of_plane_force_n;
  return out;
}

}  // namespace kinetofem::loads
