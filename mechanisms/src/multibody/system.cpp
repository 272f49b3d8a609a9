#include "kinetofem/mechanisms/multibody/system.hpp"

#include "kinetofem/mechanisms/multibody/chain_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"
#include "planar.hpp"

namespace kinetofem::mech {

using Eigen::Matrix2d;
using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

namespace {

using planar::cross;
using planar::perp;
using planar::rotation;

// A body point at a state: position, rotated offset A s, B s = rot90(A s),
// velocity, and the body's angular velocity.
struct PointState {
  Vector2d r, as, bs, v;
  double theta = 0.0, omega = 0.0;
};

}  // namespace

MultibodySystem::MultibodySystem(MultibodyModel model) : model_(std::move(model)) {
  require(model_.characteristic_length_m > 0.0, "multibody model '{}': characteristic length must be positive",
          model_.name);
  std::set<std::string> names;
  offset_.assign(model_.bodies.size(), -1);
  for (std::size_t b = 0; b < model_.bodies.size(); ++b) {
    const Body& body = model_.bodies[b];
    require(!body.name.empty(), "multibody model '{}': body {} has no name", model_.name, b);
    require(names.insert(body.name).second, "multibody model '{}': duplicate body name '{}'", model_.name, body.name);
    EffectiveBody eff;
    require(body.mass_kg >= 0.0 && body.inertia_kgm2 >= 0.0, "body '{}': negative mass or inertia", body.name);
    eff.mass_kg = body.mass_kg;
    Vector2d moment = body.mass_kg * body.com_body;
    for (const PointMass& pm : body.point_masses) {
      require(pm.mass_kg >= 0.0, "body '{}': point mass '{}' is negative ({} kg)", body.name, pm.name, pm.mass_kg);
      eff.mass_kg += pm.mass_kg;
      moment += pm.mass_kg * pm.position_body;
    }
    eff.com_body = eff.mass_kg > 0.0 ? Vector2d(moment / eff.mass_kg) : body.com_body;
    // Parallel-axis rule about the combined centre of mass.
    eff.inertia_kgm2 = body.inertia_kgm2 + body.mass_kg * (body.com_body - eff.com_body).squaredNorm();
    for (const PointMass& pm : body.point_masses)
      eff.inertia_kgm2 += pm.mass_kg * (pm.position_body - eff.com_body).squaredNorm();
    effective_.push_back(eff);
    if (!body.fixed) {
      offset_[b] = 3 * static_cast<int>(moving_.size());
      moving_.push_back(static_cast<int>(b));
    }
  }

  const VectorXd q0 = initial_coordinates();
  const VectorXd qd0 = VectorXd::Zero(n_coordinates());
  names.clear();
  auto unique_name = [&](const std::string& name, const char* what) {
    require(!name.empty(), "multibody model '{}': a {} has no name", model_.name, what);
    require(names.insert(name).second, "multibody model '{}': duplicate constraint name '{}'", model_.name, name);
  };

  for (std::size_t k = 0; k < model_.joints.size(); ++k) {
    const Joint& joint = model_.joints[k];
    unique_name(joint.name, "joint");
    ConstraintBlock blk;
    blk.name = joint.name;
    blk.source = static_cast<int>(k);
    blk.body_i = body_index(joint.body_i);
    blk.body_j = body_index(joint.body_j);
    require(blk.body_i != blk.body_j, "joint '{}': both ends on body '{}'", joint.name, joint.body_i);
    blk.s_i = relative_point(blk.body_i, joint.point_i);
    blk.s_j = relative_point(blk.body_j, joint.point_j);
    const JointFacts& facts = joint_facts(joint.type);
    blk.kind = ConstraintKind::Joint;
    blk.joint = joint.type;
    blk.rows = facts.rows;
    blk.length_row.assign(facts.length_row.begin(), facts.length_row.begin() + facts.rows);
    switch (joint.type) {
      case JointType::Revolute:
        break;
      case JointType::Prismatic:
        require(joint.axis_i.norm() > 0.0, "joint '{}': prismatic axis is zero", joint.name);
        blk.axis_i = joint.axis_i.normalized();
        blk.reference = joint.reference.value_or(com_pose(blk.body_j, q0).z() - com_pose(blk.body_i, q0).z());
        break;
      case JointType::Fixed:
        blk.reference = joint.reference.value_or(com_pose(blk.body_j, q0).z() - com_pose(blk.body_i, q0).z());
        break;
      case JointType::Chain: {
        require(joint.radius_m > 0.0, "joint '{}': chain roller radius must be positive, got {} m", joint.name,
                joint.radius_m);
        blk.radius_m = joint.radius_m;
        blk.sigma = joint.wrap_ccw ? 1.0 : -1.0;
        if (joint.reference) {
          blk.reference = *joint.reference;
        } else {
          const Vector3d pi = com_pose(blk.body_i, q0), pj = com_pose(blk.body_j, q0);
          const Vector2d hinge = pi.head<2>() + rotation(pi.z()) * blk.s_i;
          const Vector2d centre = pj.head<2>() + rotation(pj.z()) * blk.s_j;
          const double d = (hinge - centre).norm(), r = blk.radius_m;
          require(d > r, "joint '{}': chain hinge lies within the roller in the initial poses (|A B0| = {} m, r = {} m)",
                  joint.name, d, r);
          const ChainTangent tangent = chain_tangent(hinge, centre, r, blk.sigma);
          blk.reference = tangent.free_length_m + r * blk.sigma * (pj.z() - tangent.tangent_angle_rad);
        }
        break;
      }
    }
    blk.first_row = n_rows_;
    n_rows_ += blk.rows;
    blocks_.push_back(blk);
  }

  for (std::size_t k = 0; k < model_.motion_drives.size(); ++k) {
    const MotionDrive& drive = model_.motion_drives[k];
    unique_name(drive.name, "motion drive");
    require(drive.law != nullptr, "motion drive '{}': no motion law", drive.name);
    const CompiledCoordinate c = compile(drive.coordinate, drive.name);
    ConstraintBlock blk;
    blk.name = drive.name;
    blk.kind = ConstraintKind::Drive;
    blk.source = static_cast<int>(k);
    blk.rows = 1;
    blk.body_i = c.body_i;
    blk.body_j = c.body_j;
    blk.s_i = c.s_i;
    blk.s_j = c.s_j;
    blk.axis_i = c.axis_i;
    blk.coordinate = c.type;
    blk.law = drive.law.get();
    blk.length_row = {c.type == CoordinateType::Displacement};
    blk.reference = drive.initial.value_or(coordinate(c, q0, qd0).value - drive.law->at(0.0).s);
    blk.first_row = n_rows_;
    n_rows_ += 1;
    blocks_.push_back(blk);
    drive_coords_.push_back(c);
  }

  for (std::size_t k = 0; k < model_.transmissions.size(); ++k) {
    const Transmission& tr = model_.transmissions[k];
    unique_name(tr.name, "transmission");
    require(std::isfinite(tr.ratio) && tr.ratio != 0.0,
            "transmission '{}': the ratio must be a finite non-zero number, got {}", tr.name, tr.ratio);
    require(std::isfinite(tr.radius_m) && tr.radius_m > 0.0,
            "transmission '{}': the output's pulley or pitch radius must be positive, got {} m", tr.name, tr.radius_m);
    require(!tr.reference || std::isfinite(*tr.reference), "transmission '{}': the reference must be finite, got {} rad",
            tr.name, tr.reference.value_or(0.0));
    const auto compile_side = [&](const RelativeCoordinate& rc, const char* side) {
      for (const std::string& body : {rc.body_i, rc.body_j})
        require(std::any_of(model_.bodies.begin(), model_.bodies.end(), [&](const Body& b) { return b.name == body; }),
                "transmission '{}': its {} coordinate names body '{}', which the model '{}' does not have", tr.name,
                side, body, model_.name);
      require(rc.type == CoordinateType::Angle, "transmission '{}': its {} coordinate must be an angle (theta_j - theta_i)",
              tr.name, side);
      return compile(rc, fmt::format("transmission '{}' ({})", tr.name, side));
    };
    const CompiledCoordinate in = compile_side(tr.input, "input"), out = compile_side(tr.output, "output");
    ConstraintBlock blk;
    blk.name = tr.name;
    blk.kind = ConstraintKind::Transmission;
    blk.source = static_cast<int>(k);
    blk.rows = 1;
    blk.body_i = out.body_i;
    blk.body_j = out.body_j;
    blk.input_i = in.body_i;
    blk.input_j = in.body_j;
    blk.s_i = out.s_i;
    blk.s_j = out.s_j;
    blk.ratio = tr.ratio;
    blk.length_row = {false};
    blk.reference = tr.reference.value_or(coordinate(out, q0, qd0).value - tr.ratio * coordinate(in, q0, qd0).value);
    blk.first_row = n_rows_;
    n_rows_ += 1;
    blocks_.push_back(blk);
  }

  for (const ForceDrive& drive : model_.force_drives) {
    unique_name(drive.name, "force drive");
    force_coords_.push_back(compile(drive.coordinate, drive.name));
    if (drive.law_type == ForceLaw::PdServo)
      require(drive.law != nullptr, "force drive '{}': a PD servo needs a reference motion law", drive.name);
    if (drive.law_type == ForceLaw::DcMotor)
      require(drive.no_load_speed != 0.0, "force drive '{}': DC motor no-load speed must be non-zero", drive.name);
    const double law0 = drive.law ? drive.law->at(0.0).s : 0.0;
    force_initial_.push_back(drive.initial.value_or(coordinate(force_coords_.back(), q0, qd0).value - law0));
  }
  for (const Spring& spring : model_.springs) {
    unique_name(spring.name, "spring");
    relative_point(body_index(spring.body_i), spring.point_i);
    relative_point(body_index(spring.body_j), spring.point_j);
  }
  for (const PointForce& force : model_.point_forces) {
    unique_name(force.name, "point force");
    relative_point(body_index(force.body), force.point);
  }
}

int MultibodySystem::body_index(const std::string& name) const {
  for (std::size_t b = 0; b < model_.bodies.size(); ++b)
    if (model_.bodies[b].name == name) return static_cast<int>(b);
  fail("multibody model '{}': no body named '{}'", model_.name, name);
}

const ConstraintBlock& MultibodySystem::block(const std::string& name) const {
  for (const ConstraintBlock& b : blocks_)
    if (b.name == name) return b;
  fail("multibody model '{}': no joint, motion drive or transmission named '{}'", model_.name, name);
}

Vector2d MultibodySystem::named_point(int body, const std::string& point) const {
  if (point == "origin" || point.empty()) return Vector2d::Zero();
  const Body& b = model_.bodies[body];
  const auto it = b.points.find(point);
  require(it != b.points.end(), "body '{}' has no point named '{}'", b.name, point);
  return it->second;
}

Vector2d MultibodySystem::relative_point(int body, const std::string& point) const {
  return named_point(body, point) - effective_[body].com_body;
}

MultibodySystem::CompiledCoordinate MultibodySystem::compile(const RelativeCoordinate& c,
                                                              const std::string& owner) const {
  CompiledCoordinate out;
  out.type = c.type;
  out.body_i = body_index(c.body_i);
  out.body_j = body_index(c.body_j);
  require(out.body_i != out.body_j, "'{}': relative coordinate between body '{}' and itself", owner, c.body_i);
  out.s_i = relative_point(out.body_i, c.point_i);
  out.s_j = relative_point(out.body_j, c.point_j);
  require(c.axis_i.norm() > 0.0, "'{}': coordinate axis is zero", owner);
  out.axis_i = c.axis_i.normalized();
  return out;
}

VectorXd MultibodySystem::initial_coordinates() const {
  VectorXd q(n_coordinates());
  for (int b : moving_) {
    const Vector3d& pose = model_.bodies[b].pose;
    q.segment<2>(offset_[b]) = pose.head<2>() + rotation(pose.z()) * effective_[b].com_body;
    q(offset_[b] + 2) = pose.z();
  }
  return q;
}

VectorXd MultibodySystem::initial_velocities() const {
  VectorXd qd(n_coordinates());
  for (int b : moving_) {
    const Vector3d& pose = model_.bodies[b].pose;
    const Vector3d& vel = model_.bodies[b].velocity;
    qd.segment<2>(offset_[b]) = vel.head<2>() + perp(rotation(pose.z()) * effective_[b].com_body) * vel.z();
    qd(offset_[b] + 2) = vel.z();
  }
  return qd;
}

Vector3d MultibodySystem::com_pose(int body, const VectorXd& q) const {
  if (offset_[body] >= 0) return q.segment<3>(offset_[body]);
  const Vector3d& pose = model_.bodies[body].pose;
  Vector3d out;
  out.head<2>() = pose.head<2>() + rotation(pose.z()) * effective_[body].com_body;
  out.z() = pose.z();
  return out;
}

Vector3d MultibodySystem::com_velocity(int body, const VectorXd& qd) const {
  if (offset_[body] >= 0) return qd.segment<3>(offset_[body]);
  return Vector3d::Zero();
}

Vector3d MultibodySystem::origin_pose(int body, const VectorXd& q) const {
  const Vector3d c = com_pose(body, q);
  Vector3d out;
  out.head<2>() = c.head<2>() - rotation(c.z()) * effective_[body].com_body;
  out.z() = c.z();
  return out;
}

Vector2d MultibodySystem::point_world(int body, const Vector2d& p_body, const VectorXd& q) const {
  const Vector3d c = com_pose(body, q);
  return c.head<2>() + rotation(c.z()) * (p_body - effective_[body].com_body);
}

namespace {

PointState point_state(const Vector3d& pose, const Vector3d& vel, const Vector2d& s) {
  PointState p;
  p.theta = pose.z();
  p.omega = vel.z();
  p.as = rotation(pose.z()) * s;
  p.bs = perp(p.as);
  p.r = pose.head<2>() + p.as;
  p.v = vel.head<2>() + p.bs * p.omega;
  return p;
}

}  // namespace

MultibodySystem::CoordinateValues MultibodySystem::coordinate(const CompiledCoordinate& c, const VectorXd& q,
                                                              const VectorXd& qd) const {
  CoordinateValues out;
  const PointState pi = point_state(com_pose(c.body_i, q), com_velocity(c.body_i, qd), c.s_i);
  const PointState pj = point_state(com_pose(c.body_j, q), com_velocity(c.body_j, qd), c.s_j);
  out.grad.setZero();
  if (c.type == CoordinateType::Angle) {
    out.value = pj.theta - pi.theta;
    out.grad(2) = -1.0;
    out.grad(5) = 1.0;
    out.rate = pj.omega - pi.omega;
    out.quadratic = 0.0;
    return out;
  }
  const Vector2d u = rotation(pi.theta) * c.axis_i, n = perp(u);
  const Vector2d d = pj.r - pi.r, dd = pj.v - pi.v;
  out.value = u.dot(d);
  out.grad.segment<2>(0) = -u.transpose();
  out.grad(2) = n.dot(d) - u.dot(pi.bs);
  out.grad.segment<2>(3) = u.transpose();
  out.grad(5) = u.dot(pj.bs);
  out.rate = u.dot(dd) + pi.omega * n.dot(d);
  const double wi = pi.omega, wj = pj.omega;
  out.quadratic = -u.dot(d) * wi * wi + 2.0 * wi * n.dot(dd) + u.dot(pi.as * wi * wi - pj.as * wj * wj);
  return out;
}

BlockValues MultibodySystem::evaluate(const ConstraintBlock& blk, const VectorXd& q, const VectorXd& qd,
                                      double t) const {
  BlockValues out;
  out.phi = VectorXd::Zero(blk.rows);
  out.nu = VectorXd::Zero(blk.rows);
  out.gamma = VectorXd::Zero(blk.rows);
  out.jac = MatrixXd::Zero(blk.rows, 6);
  const PointState pi = point_state(com_pose(blk.body_i, q), com_velocity(blk.body_i, qd), blk.s_i);
  const PointState pj = point_state(com_pose(blk.body_j, q), com_velocity(blk.body_j, qd), blk.s_j);
  const double wi = pi.omega, wj = pj.omega;

  auto revolute_rows = [&]() {
    out.phi.head<2>() = pi.r - pj.r;
    out.jac.block<2, 2>(0, 0).setIdentity();
    out.jac.block<2, 1>(0, 2) = pi.bs;
    out.jac.block<2, 2>(0, 3) = -Matrix2d::Identity();
    out.jac.block<2, 1>(0, 5) = -pj.bs;
    out.gamma.head<2>() = pi.as * wi * wi - pj.as * wj * wj;
  };
  auto angle_row = [&](int row) {
    out.phi(row) = pj.theta - pi.theta - blk.reference;
    out.jac(row, 2) = -1.0;
    out.jac(row, 5) = 1.0;
  };

  switch (blk.kind) {
    case ConstraintKind::Transmission: {
      // Both coordinates are angles (checked on compile): linear, so nu = gamma = 0.
      const double theta_in = com_pose(blk.input_j, q).z() - com_pose(blk.input_i, q).z();
      out.phi(0) = (pj.theta - pi.theta) - blk.ratio * theta_in - blk.reference;
      out.jac(0, 2) = -1.0;
      out.jac(0, 5) = 1.0;
      out.jac_input = MatrixXd::Zero(1, 6);
      out.jac_input(0, 2) = blk.ratio;
      out.jac_input(0, 5) = -blk.ratio;
      break;
    }
    case ConstraintKind::Drive: {
      const CompiledCoordinate c{blk.coordinate, blk.body_i, blk.body_j, blk.s_i, blk.s_j, blk.axis_i};
      const CoordinateValues cv = coordinate(c, q, qd);
      const MotionState m = blk.law->at(t);
      out.phi(0) = cv.value - blk.reference - m.s;
      out.jac.row(0) = cv.grad;
      out.nu(0) = m.s_dot;
      out.gamma(0) = m.s_ddot - cv.quadratic;
      break;
    }
    case ConstraintKind::Joint:
      switch (blk.joint) {
        case JointType::Revolute:
          revolute_rows();
          break;
        case JointType::Fixed:
          revolute_rows();
          angle_row(2);
          break;
        case JointType::Prismatic: {
          const Vector2d u = rotation(pi.theta) * blk.axis_i, n = perp(u);
          const Vector2d d = pj.r - pi.r, dd = pj.v - pi.v;
          out.phi(0) = n.dot(d);
          out.jac.block<1, 2>(0, 0) = -n.transpose();
          out.jac(0, 2) = -u.dot(d) - n.dot(pi.bs);
          out.jac.block<1, 2>(0, 3) = n.transpose();
          out.jac(0, 5) = n.dot(pj.bs);
          out.gamma(0) = n.dot(d) * wi * wi + 2.0 * wi * u.dot(dd) + n.dot(pj.as * wj * wj - pi.as * wi * wi);
          angle_row(1);
          break;
        }
        case JointType::Chain: {
          const double r = blk.radius_m, sg = blk.sigma;
          const Vector2d e = pi.r - pj.r, ed = pi.v - pj.v;
          const double d2 = e.squaredNorm(), d = std::sqrt(d2);
          require(d > r, "chain '{}': hinge point within the roller (|A B0| = {} m, r = {} m) at t = {} s", blk.name, d, r,
                  t);
          const ChainTangent tangent = chain_tangent(pi.r, pj.r, r, sg);
          const double b = tangent.free_length_m;
          const double raw = b + r * sg * (pj.theta - tangent.tangent_angle_rad) - blk.reference;
          const double period = 2.0 * std::numbers::pi * r;
          out.phi(0) = raw - period * std::round(raw / period);
          const Vector2d g = (b * e - sg * r * perp(e)) / d2;
          out.jac.block<1, 2>(0, 0) = g.transpose();
          out.jac(0, 2) = g.dot(pi.bs);
          out.jac.block<1, 2>(0, 3) = -g.transpose();
          out.jac(0, 5) = -g.dot(pj.bs) + sg * r;
          const double bd = e.dot(ed) / b;
          const Vector2d gd = (bd * e + b * ed - sg * r * perp(ed)) / d2 - 2.0 * e.dot(ed) / d2 * g;
          out.gamma(0) = g.dot(pi.as * wi * wi - pj.as * wj * wj) - gd.dot(ed);
          break;
        }
      }
      break;
  }
  return out;
}

void MultibodySystem::scatter(int body_i, int body_j, const MatrixXd& local, Eigen::Ref<MatrixXd> global) const {
  if (offset_[body_i] >= 0) global.middleCols(offset_[body_i], 3) += local.leftCols(3);
  if (offset_[body_j] >= 0) global.middleCols(offset_[body_j], 3) += local.rightCols(3);
}

void MultibodySystem::scatter(const ConstraintBlock& blk, const BlockValues& values, Eigen::Ref<MatrixXd> rows) const {
  scatter(blk.body_i, blk.body_j, values.jac, rows);
  if (values.jac_input.size() > 0) scatter(blk.input_i, blk.input_j, values.jac_input, rows);
}

Eigen::Matrix<double, 6, 1> MultibodySystem::gather(int body_i, int body_j, const VectorXd& v) const {
  Eigen::Matrix<double, 6, 1> out = Eigen::Matrix<double, 6, 1>::Zero();
  if (offset_[body_i] >= 0) out.head<3>() = v.segment<3>(offset_[body_i]);
  if (offset_[body_j] >= 0) out.tail<3>() = v.segment<3>(offset_[body_j]);
  return out;
}

namespace {

// One part (phi, nu or gamma) of every block's values, stacked over all rows.
VectorXd stacked(const MultibodySystem& system, const VectorXd& q, const VectorXd& qd, double t,
                 VectorXd BlockValues::*part) {
  VectorXd out(system.n_constraints());
  for (const ConstraintBlock& blk : system.blocks())
    out.segment(blk.first_row, blk.rows) = system.evaluate(blk, q, qd, t).*part;
  return out;
}

// The largest |residual| over all rows, angle rows scaled by the characteristic length (m).
double worst_scaled(const std::vector<ConstraintBlock>& blocks, const VectorXd& residual, double length_m) {
  double worst = 0.0;
  for (const ConstraintBlock& blk : blocks)
    for (int r = 0; r < blk.rows; ++r)
      worst = std::max(worst, std::abs(residual(blk.first_row + r)) * (blk.length_row[r] ? 1.0 : length_m));
  return worst;
}

}  // namespace

VectorXd MultibodySystem::phi(const VectorXd& q, double t) const {
  return stacked(*this, q, VectorXd::Zero(n_coordinates()), t, &BlockValues::phi);
}

MatrixXd MultibodySystem::jacobian(const VectorXd& q, double t) const {
  MatrixXd out = MatrixXd::Zero(n_rows_, n_coordinates());
  const VectorXd qd = VectorXd::Zero(n_coordinates());
  for (const ConstraintBlock& blk : blocks_)
    scatter(blk, evaluate(blk, q, qd, t), out.middleRows(blk.first_row, blk.rows));
  return out;
}

VectorXd MultibodySystem::nu(const VectorXd& q, double t) const {
  return stacked(*this, q, VectorXd::Zero(n_coordinates()), t, &BlockValues::nu);
}

VectorXd MultibodySystem::gamma(const VectorXd& q, const VectorXd& qd, double t) const {
  return stacked(*this, q, qd, t, &BlockValues::gamma);
}

double MultibodySystem::position_drift_m(const VectorXd& q, double t) const {
  return worst_scaled(blocks_, phi(q, t), model_.characteristic_length_m);
}

double MultibodySystem::velocity_drift_m_per_s(const VectorXd& q, const VectorXd& qd, double t) const {
  return worst_scaled(blocks_, jacobian(q, t) * qd - nu(q, t), model_.characteristic_length_m);
}

VectorXd MultibodySystem::mass_diagonal() const {
  VectorXd m(n_coordinates());
  for (int b : moving_) {
    m(offset_[b]) = m(offset_[b] + 1) = effective_[b].mass_kg;
    m(offset_[b] + 2) = effective_[b].inertia_kgm2;
  }
  return m;
}

double MultibodySystem::force_drive_effort(int d, const VectorXd& q, const VectorXd& qd, double t) const {
  const ForceDrive& drive = model_.force_drives[d];
  switch (drive.law_type) {
    case ForceLaw::Constant:
      return drive.value;
    case ForceLaw::DcMotor:
      return drive.stall * (1.0 - coordinate(force_coords_[d], q, qd).rate / drive.no_load_speed);
    case ForceLaw::PdServo: {
      const CoordinateValues cv = coordinate(force_coords_[d], q, qd);
      const MotionState m = drive.law->at(t);
      return drive.kp * (force_initial_[d] + m.s - cv.value) + drive.kd * (m.s_dot - cv.rate);
    }
  }
  return 0.0;
}

namespace {

// Adds a force (world) acting at a body point to the body's load (Fx, Fy, M about the centre of mass).
void add_point_force(std::vector<Vector3d>& loads, int body, const Vector2d& arm, const Vector2d& force) {
  loads[body].head<2>() += force;
  loads[body].z() += cross(arm, force);
}

}  // namespace

std::vector<Vector3d> MultibodySystem::applied_loads(const VectorXd& q, const VectorXd& qd, double t) const {
  std::vector<Vector3d> loads(model_.bodies.size(), Vector3d::Zero());
  for (std::size_t b = 0; b < model_.bodies.size(); ++b)
    loads[b].head<2>() = effective_[b].mass_kg * model_.gravity;
  for (const Spring& sp : model_.springs) {
    const int bi = body_index(sp.body_i), bj = body_index(sp.body_j);
    const PointState pi = point_state(com_pose(bi, q), com_velocity(bi, qd), relative_point(bi, sp.point_i));
    const PointState pj = point_state(com_pose(bj, q), com_velocity(bj, qd), relative_point(bj, sp.point_j));
    const Vector2d d = pj.r - pi.r;
    const double length = d.norm();
    require(length > 0.0, "spring '{}': zero length at t = {} s", sp.name, t);
    const Vector2d e = d / length;
    const double tension = sp.stiffness_N_per_m * (length - sp.free_length_m) + sp.damping_Ns_per_m * e.dot(pj.v - pi.v);
    add_point_force(loads, bi, pi.as, tension * e);
    add_point_force(loads, bj, pj.as, -tension * e);
  }
  for (const PointForce& pf : model_.point_forces) {
    const int b = body_index(pf.body);
    const Vector3d pose = com_pose(b, q);
    add_point_force(loads, b, rotation(pose.z()) * relative_point(b, pf.point), pf.force_world);
  }
  for (std::size_t d = 0; d < model_.force_drives.size(); ++d) {
    const CompiledCoordinate& c = force_coords_[d];
    const double effort = force_drive_effort(static_cast<int>(d), q, qd, t);
    const CoordinateValues cv = coordinate(c, q, qd);
    loads[c.body_i] += cv.grad.head<3>().transpose() * effort;
    loads[c.body_j] += cv.grad.tail<3>().transpose() * effort;
  }
  return loads;
}

VectorXd MultibodySystem::applied_forces(const VectorXd& q, const VectorXd& qd, double t) const {
  VectorXd out(n_coordinates());
  const std::vector<Vector3d> loads = applied_loads(q, qd, t);
  for (int b : moving_) out.segment<3>(offset_[b]) = loads[b];
  return out;
}

double MultibodySystem::kinetic_energy(const VectorXd& qd) const {
  const VectorXd m = mass_diagonal();
  return 0.5 * qd.dot(m.cwiseProduct(qd));
}

double MultibodySystem::potential_energy(const VectorXd& q) const {
  double v = 0.0;
  for (int b : moving_) v -= effective_[b].mass_kg * model_.gravity.dot(q.segment<2>(offset_[b]));
  for (const Spring& sp : model_.springs) {
    const int bi = body_index(sp.body_i), bj = body_index(sp.body_j);
    const double length =
        (point_world(bj, named_point(bj, sp.point_j), q) - point_world(bi, named_point(bi, sp.point_i), q)).norm();
    v += 0.5 * sp.stiffness_N_per_m * (length - sp.free_length_m) * (length - sp.free_length_m);
  }
  return v;
}

double MultibodySystem::force_drive_power(const VectorXd& q, const VectorXd& qd, double t) const {
  double p = 0.0;
  for (std::size_t d = 0; d < model_.force_drives.size(); ++d)
    p += force_drive_effort(static_cast<int>(d), q, qd, t) * coordinate(force_coords_[d], q, qd).rate;
  return p;
}

double MultibodySystem::other_power(const VectorXd& q, const VectorXd& qd) const {
  double p = 0.0;
  for (const Spring& sp : model_.springs) {
    if (sp.damping_Ns_per_m == 0.0) continue;
    const int bi = body_index(sp.body_i), bj = body_index(sp.body_j);
    const PointState pi = point_state(com_pose(bi, q), com_velocity(bi, qd), relative_point(bi, sp.point_i));
    const PointState pj = point_state(com_pose(bj, q), com_velocity(bj, qd), relative_point(bj, sp.point_j));
    const Vector2d e = (pj.r - pi.r).normalized();
    const double rate = e.dot(pj.v - pi.v);
    p -= sp.damping_Ns_per_m * rate * rate;
  }
  for (const PointForce& pf : model_.point_forces) {
    const int b = body_index(pf.body);
    const PointState ps = point_state(com_pose(b, q), com_velocity(b, qd), relative_point(b, pf.point));
    p += pf.force_world.dot(ps.v);
  }
  return p;
}

}  // namespace kinetofem::mech
