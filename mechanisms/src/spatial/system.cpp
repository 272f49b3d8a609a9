#include "kinetofem/mechanisms/spatial/system.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"

namespace kinetofem::mech::spatial {

using Eigen::Matrix3d;
using Eigen::MatrixXd;
using Eigen::Vector3d;
using Eigen::Vector4d;
using Eigen::VectorXd;

namespace {

// One body of a block at a state (a fixed body: its pose, at rest).
struct Side {
  Vector3d r, r_dot, w;  // centre of mass (world), its velocity, angular velocity (body axes)
  Vector4d p;
  Matrix3d a;
};

// A world vector of a block (a body vector, the point difference or a
// constant) with its rate, quadratic acceleration term and Jacobians over the
// block's two bodies (jq: 14 columns, pi: 12 columns; system.hpp).
struct WorldVector {
  Vector3d value = Vector3d::Zero(), rate = Vector3d::Zero(), quad = Vector3d::Zero();
  Eigen::Matrix<double, 3, 14> jq = Eigen::Matrix<double, 3, 14>::Zero();
  Eigen::Matrix<double, 3, 12> pi = Eigen::Matrix<double, 3, 12>::Zero();
};

// A scalar row: value, rate (Pi v), quadratic term (Phi'' - Pi v') and Jacobians.
struct Row {
  double value = 0.0, rate = 0.0, quad = 0.0;
  Eigen::Matrix<double, 1, 14> jq;
  Eigen::Matrix<double, 1, 12> pi;
};

// a = A a' of side k (0: body i, 1: body j).
WorldVector body_vector(int k, const Side& s, const Vector3d& a_body) {
  WorldVector u;
  u.value = s.a * a_body;
  u.rate = s.a * s.w.cross(a_body);
  u.quad = s.a * s.w.cross(s.w.cross(a_body));
  u.jq.block<3, 4>(0, 7 * k + 3) = b_matrix(s.p, a_body);
  u.pi.block<3, 3>(0, 6 * k + 3) = -s.a * skew(a_body);
  return u;
}

// d = r_Pj - r_Pi.
WorldVector point_difference(const Side& si, const Vector3d& s_i, const Side& sj, const Vector3d& s_j) {
  WorldVector d;
  d.value = sj.r + sj.a * s_j - si.r - si.a * s_i;
  d.rate = sj.r_dot + sj.a * sj.w.cross(s_j) - si.r_dot - si.a * si.w.cross(s_i);
  d.quad = sj.a * sj.w.cross(sj.w.cross(s_j)) - si.a * si.w.cross(si.w.cross(s_i));
  d.jq.block<3, 3>(0, 0) = -Matrix3d::Identity();
  d.jq.block<3, 4>(0, 3) = -b_matrix(si.p, s_i);
  d.jq.block<3, 3>(0, 7) = Matrix3d::Identity();
  d.jq.block<3, 4>(0, 10) = b_matrix(sj.p, s_j);
  d.pi.block<3, 3>(0, 0) = -Matrix3d::Identity();
  d.pi.block<3, 3>(0, 3) = si.a * skew(s_i);
  d.pi.block<3, 3>(0, 6) = Matrix3d::Identity();
  d.pi.block<3, 3>(0, 9) = -sj.a * skew(s_j);
  return d;
}

WorldVector constant(const Vector3d& e) {
  WorldVector u;
  u.value = e;
  return u;
}

Row dot(const WorldVector& u, const WorldVector& w) {
  Row r;
  r.value = u.value.dot(w.value);
  r.rate = u.rate.dot(w.value) + u.value.dot(w.rate);
  r.quad = u.quad.dot(w.value) + 2.0 * u.rate.dot(w.rate) + u.value.dot(w.quad);
  r.jq = u.value.transpose() * w.jq + w.value.transpose() * u.jq;
  r.pi = u.value.transpose() * w.pi + w.value.transpose() * u.pi;
  return r;
}

// theta = atan2(sine, cosine) of two dot rows: the angle of f_j from f_i about h_i.
Row angle(const Row& sine, const Row& cosine) {
  const double s = sine.value, c = cosine.value, r2 = s * s + c * c;
  Row a;
  a.value = std::atan2(s, c);
  a.rate = (c * sine.rate - s * cosine.rate) / r2;
  a.quad = (c * sine.quad - s * cosine.quad) / r2 - 2.0 * a.rate * (s * sine.rate + c * cosine.rate) / r2;
  a.jq = (c * sine.jq - s * cosine.jq) / r2;
  a.pi = (c * sine.pi - s * cosine.pi) / r2;
  return a;
}

double wrap_angle(double x) { return std::remainder(x, 2.0 * std::numbers::pi); }

Row operator+(Row a, const Row& b) {
  a.value += b.value;
  a.rate += b.rate;
  a.quad += b.quad;
  a.jq += b.jq;
  a.pi += b.pi;
  return a;
}

Row operator*(double c, Row a) {
  a.value *= c;
  a.rate *= c;
  a.quad *= c;
  a.jq *= c;
  a.pi *= c;
  return a;
}

// f(x, y) of two rows by the chain rule, given f's value, gradient (fx, fy)
// and Hessian (fxx, fxy, fyy) there: f'' = fx x'' + fy y'' + [x' y'] H [x' y']^T,
// so the quadratic term adds the Hessian form to fx x_quad + fy y_quad.
struct Smooth2 {
  double value, fx, fy, fxx, fxy, fyy;
};
Row compose(const Smooth2& f, const Row& x, const Row& y) {
  Row out;
  out.value = f.value;
  out.rate = f.fx * x.rate + f.fy * y.rate;
  out.quad = f.fx * x.quad + f.fy * y.quad + f.fxx * x.rate * x.rate + 2.0 * f.fxy * x.rate * y.rate +
             f.fyy * y.rate * y.rate;
  out.jq = f.fx * x.jq + f.fy * y.jq;
  out.pi = f.fx * x.pi + f.fy * y.pi;
  return out;
}

// The chain's function of the hinge's in-plane coordinates (x, y) about the
// roller centre (system.hpp): F = G(rho) - r sigma atan2(y, x),
// G = sqrt(rho^2 - r^2) - r acos(r / rho), with its gradient and Hessian.
Smooth2 chain_function(double x, double y, double r, double sigma) {
  const double rho2 = x * x + y * y, rho = std::sqrt(rho2), b = std::sqrt(rho2 - r * r);
  const double g1 = b / rho, g2 = r * r / (rho2 * b);  // G', G''
  const double rho3 = rho2 * rho, rho4 = rho2 * rho2;
  // rho's and psi's second derivatives (psi = atan2(y, x)).
  const double rxx = y * y / rho3, rxy = -x * y / rho3, ryy = x * x / rho3;
  const double pxx = 2.0 * x * y / rho4, pxy = (y * y - x * x) / rho4, pyy = -2.0 * x * y / rho4;
  const double rx = x / rho, ry = y / rho;
  Smooth2 f;
  f.value = b - r * std::acos(r / rho) - r * sigma * std::atan2(y, x);
  f.fx = (b * x + sigma * r * y) / rho2;
  f.fy = (b * y - sigma * r * x) / rho2;
  f.fxx = g2 * rx * rx + g1 * rxx - r * sigma * pxx;
  f.fxy = g2 * rx * ry + g1 * rxy - r * sigma * pxy;
  f.fyy = g2 * ry * ry + g1 * ryy - r * sigma * pyy;
  return f;
}

}  // namespace

System::System(Model model) : model_(std::move(model)) {
  const std::string& mname = model_.name;
  require(model_.characteristic_length_m > 0.0 && std::isfinite(model_.characteristic_length_m),
          "spatial model '{}': characteristic_length_m must be > 0, got {}", mname, model_.characteristic_length_m);
  require(model_.gravity.allFinite(), "spatial model '{}': gravity is not finite", mname);
  const int nb = n_bodies();
  moving_index_.assign(nb, -1);
  for (int b = 0; b < nb; ++b) {
    Body& body = model_.bodies[b];
    for (int other = 0; other < b; ++other)
      require(model_.bodies[other].name != body.name, "spatial model '{}': two bodies named '{}'", mname, body.name);
    const double norm = body.euler_parameters.norm();
    require(norm > 1e-12 && std::isfinite(norm), "spatial model '{}', body '{}': Euler parameters of zero length",
            mname, body.name);
    body.euler_parameters /= norm;
    fixed_p_.push_back(body.euler_parameters);
    EffectiveBody eff;
    if (!body.fixed) {
      require(body.mass_kg >= 0.0, "spatial model '{}', body '{}': negative mass {} kg", mname, body.name,
              body.mass_kg);
      double m = body.mass_kg;
      Vector3d first = body.mass_kg * body.com_body;
      for (const PointMass& pm : body.point_masses) {
        require(pm.mass_kg >= 0.0, "spatial model '{}', body '{}': point mass '{}' is negative ({} kg)", mname,
                body.name, pm.name, pm.mass_kg);
        m += pm.mass_kg;
        first += pm.mass_kg * pm.position_body;
      }
      require(m > 0.0, "spatial model '{}', body '{}': a moving body needs a mass > 0", mname, body.name);
      eff.mass_kg = m;
      eff.com_body = first / m;
      const auto shift = [](double mass, const Vector3d& d) {
        return Matrix3d(mass * (d.squaredNorm() * Matrix3d::Identity() - d * d.transpose()));
      };
      eff.inertia_kgm2 = body.inertia_kgm2 + shift(body.mass_kg, body.com_body - eff.com_body);
      for (const PointMass& pm : body.point_masses)
        eff.inertia_kgm2 += pm.inertia_kgm2 + shift(pm.mass_kg, pm.position_body - eff.com_body);
      const Eigen::LLT<Matrix3d> llt(0.5 * (eff.inertia_kgm2 + eff.inertia_kgm2.transpose()));
      // J must be positive definite: M is inverted in the index-1 solve.
      require(llt.info() == Eigen::Success && eff.inertia_kgm2.allFinite(),
              "spatial model '{}', body '{}': the inertia tensor with point masses is not positive definite", mname,
              body.name);
      moving_index_[b] = static_cast<int>(moving_.size());
      moving_.push_back(b);
    }
    effective_.push_back(eff);
  }

  const VectorXd q0 = initial_positions();
  const VectorXd v0 = VectorXd::Zero(n_velocities());
  const auto unit = [&](const Vector3d& a, const std::string& what, const std::string& joint) {
    const double norm = a.norm();
    require(norm > 1e-12 && a.allFinite(), "spatial model '{}', joint '{}': {} of zero length", mname, joint, what);
    return Vector3d(a / norm);
  };
  for (int c = 0; c < static_cast<int>(model_.joints.size()); ++c) {
    const Joint& j = model_.joints[c];
    ConstraintBlock blk;
    blk.name = j.name;
    blk.kind = BlockKind::Joint;
    blk.joint = j.type;
    blk.source = c;
    blk.body_i = body_index(j.body_i);
    blk.body_j = body_index(j.body_j);
    require(blk.body_i != blk.body_j, "spatial model '{}', joint '{}': body_i and body_j are the same body '{}'", mname,
            j.name, j.body_i);
    require(!(model_.bodies[blk.body_i].fixed && model_.bodies[blk.body_j].fixed),
            "spatial model '{}', joint '{}': both bodies are fixed", mname, j.name);
    blk.s_i = relative_point(blk.body_i, j.point_i);
    blk.s_j = relative_point(blk.body_j, j.point_j);
    blk.h_i = unit(j.axis_i, "axis_i", j.name);
    blk.h_j = unit(j.axis_j, "axis_j", j.name);
    const auto across = [&](const Vector3d& a, const Vector3d& h) { return Vector3d(a - a.dot(h) * h); };
    blk.f_i = j.reference_i ? unit(across(*j.reference_i, blk.h_i), "reference_i across axis_i", j.name)
                            : perpendicular(blk.h_i);
    blk.g_i = blk.h_i.cross(blk.f_i);
    if (j.reference_j) {
      blk.f_j = unit(across(*j.reference_j, blk.h_j), "reference_j across axis_j", j.name);
    } else {
      const Vector3d carried = across(rotation(blk.body_j, q0).transpose() * rotation(blk.body_i, q0) * blk.f_i, blk.h_j);
      blk.f_j = carried.norm() > 1e-6 ? Vector3d(carried.normalized()) : perpendicular(blk.h_j);
    }
    const JointFacts& facts = joint_facts(j.type);
    blk.rows = facts.rows;
    blk.length_row.assign(facts.length_row.begin(), facts.length_row.begin() + facts.rows);
    blk.first_row = n_rows_;
    if (facts.holds_rotation) {
      // The angle row is the last one; with reference 0 it evaluates to the initial angle.
      blk.reference = j.rotation_rad ? *j.rotation_rad : evaluate(blk, q0, v0, 0.0).phi(blk.rows - 1);
    }
    if (facts.holds_length) {
      require(std::isfinite(j.radius_m) && j.radius_m >= 0.0,
              "spatial model '{}', chain '{}': the roller radius must be >= 0, got {} m", mname, j.name, j.radius_m);
      require(!j.length_m || std::isfinite(*j.length_m), "spatial model '{}', chain '{}': the length is not finite",
              mname, j.name);
      blk.radius_m = j.radius_m;
      blk.sigma = j.wrap_ccw ? 1.0 : -1.0;
      // The length row is the last one; with reference 0 it evaluates to the initial length.
      blk.reference = j.length_m ? *j.length_m : evaluate(blk, q0, v0, 0.0).phi(blk.rows - 1);
    }
    n_rows_ += blk.rows;
    blocks_.push_back(std::move(blk));
  }
  for (int d = 0; d < static_cast<int>(model_.motion_drives.size()); ++d) {
    const MotionDrive& drive = model_.motion_drives[d];
    require(drive.law != nullptr, "spatial model '{}', drive '{}': no motion law", mname, drive.name);
    const ConstraintBlock* joint = nullptr;
    for (const ConstraintBlock& b : blocks_)
      if (b.kind == BlockKind::Joint && b.name == drive.joint) joint = &b;
    require(joint != nullptr, "spatial model '{}', drive '{}': no joint named '{}'", mname, drive.name, drive.joint);
    const JointFacts& facts = joint_facts(joint->joint);
    const bool takes = drive.coordinate == DriveCoordinate::Rotation ? facts.drives_rotation : facts.drives_translation;
    require(takes, "spatial model '{}', drive '{}': a {} joint ('{}') has no driven {}", mname, drive.name,
            facts.name, drive.joint, drive.coordinate == DriveCoordinate::Rotation ? "rotation" : "translation");
    ConstraintBlock blk = *joint;
    blk.name = drive.name;
    blk.kind = BlockKind::Drive;
    blk.coordinate = drive.coordinate;
    blk.source = d;
    blk.rows = 1;
    blk.length_row = {drive.coordinate == DriveCoordinate::Translation};
    blk.first_row = n_rows_;
    blk.law = drive.law.get();
    blk.reference = 0.0;
    blk.reference = drive.initial ? *drive.initial : evaluate(blk, q0, v0, 0.0).phi(0);
    n_rows_ += 1;
    blocks_.push_back(std::move(blk));
  }
  for (const ForceDrive& drive : model_.force_drives) {
    const ConstraintBlock* joint = nullptr;
    for (const ConstraintBlock& b : blocks_)
      if (b.kind == BlockKind::Joint && b.name == drive.joint) joint = &b;
    require(joint != nullptr, "spatial model '{}', force drive '{}': no joint named '{}'", mname, drive.name,
            drive.joint);
    const JointFacts& facts = joint_facts(joint->joint);
    const bool takes = drive.coordinate == DriveCoordinate::Rotation ? facts.drives_rotation : facts.drives_translation;
    require(takes, "spatial model '{}', force drive '{}': a {} joint ('{}') has no driven {}", mname, drive.name,
            facts.name, drive.joint, drive.coordinate == DriveCoordinate::Rotation ? "rotation" : "translation");
    switch (drive.law_type) {
      case EffortLaw::Constant:
        require(std::isfinite(drive.value), "spatial model '{}', force drive '{}': the effort is not finite", mname,
                drive.name);
        break;
      case EffortLaw::DcMotor:
        require(std::isfinite(drive.stall) && std::isfinite(drive.no_load_speed) && drive.no_load_speed != 0.0,
                "spatial model '{}', force drive '{}': a DC motor needs a finite stall effort and a finite non-zero "
                "no-load speed",
                mname, drive.name);
        break;
      case EffortLaw::PdServo:
        require(drive.law != nullptr && std::isfinite(drive.kp) && std::isfinite(drive.kd),
                "spatial model '{}', force drive '{}': a PD servo needs a reference motion law and finite gains", mname,
                drive.name);
        break;
    }
    ConstraintBlock blk = *joint;
    blk.name = drive.name;
    blk.kind = BlockKind::Drive;
    blk.coordinate = drive.coordinate;
    blk.source = static_cast<int>(force_blocks_.size());
    blk.rows = 1;
    blk.length_row = {drive.coordinate == DriveCoordinate::Translation};
    blk.first_row = -1;
    blk.law = nullptr;
    blk.reference = 0.0;
    const double law0 = drive.law ? drive.law->at(0.0).s : 0.0;
    blk.reference = drive.initial ? *drive.initial : evaluate(blk, q0, v0, 0.0).phi(0) - law0;
    force_blocks_.push_back(std::move(blk));
  }
  for (const PointForce& f : model_.point_forces) {
    const int b = body_index(f.body);
    named_point(b, f.point);
    require(f.force_world.allFinite(), "spatial model '{}', point force '{}': not finite", mname, f.name);
  }
  for (const Spring& sp : model_.springs) {
    named_point(body_index(sp.body_i), sp.point_i);
    named_point(body_index(sp.body_j), sp.point_j);
    require(std::isfinite(sp.stiffness_N_per_m) && std::isfinite(sp.damping_Ns_per_m) &&
                std::isfinite(sp.free_length_m),
            "spatial model '{}', spring '{}': stiffness, damping and free length must be finite", mname, sp.name);
  }
}

int System::body_index(const std::string& name) const {
  for (int b = 0; b < n_bodies(); ++b)
    if (model_.bodies[b].name == name) return b;
  fail("spatial model '{}': no body named '{}'", model_.name, name);
}

const ConstraintBlock& System::block(const std::string& name) const {
  for (const ConstraintBlock& b : blocks_)
    if (b.name == name) return b;
  fail("spatial model '{}': no joint or drive named '{}'", model_.name, name);
}

Vector3d System::named_point(int body, const std::string& point) const {
  const Body& b = model_.bodies[body];
  if (point == "origin") return Vector3d::Zero();
  const auto it = b.points.find(point);
  require(it != b.points.end(), "spatial model '{}': body '{}' has no point '{}'", model_.name, b.name, point);
  return it->second;
}

Vector3d System::relative_point(int body, const std::string& point) const {
  return named_point(body, point) - effective_[body].com_body;
}

VectorXd System::initial_positions() const {
  VectorXd q(n_positions());
  for (int k = 0; k < n_moving(); ++k) {
    const Body& b = model_.bodies[moving_[k]];
    q.segment<3>(7 * k) = b.position + spatial::rotation(fixed_p_[moving_[k]]) * effective_[moving_[k]].com_body;
    q.segment<4>(7 * k + 3) = fixed_p_[moving_[k]];
  }
  return q;
}

VectorXd System::initial_velocities() const {
  VectorXd v(n_velocities());
  for (int k = 0; k < n_moving(); ++k) {
    const Body& b = model_.bodies[moving_[k]];
    const Matrix3d a = spatial::rotation(fixed_p_[moving_[k]]);
    v.segment<3>(6 * k) = b.velocity + b.angular_velocity.cross(a * effective_[moving_[k]].com_body);
    v.segment<3>(6 * k + 3) = a.transpose() * b.angular_velocity;
  }
  return v;
}

Vector3d System::com(int body, const VectorXd& q) const {
  const int k = moving_index_[body];
  if (k >= 0) return q.segment<3>(7 * k);
  return model_.bodies[body].position + spatial::rotation(fixed_p_[body]) * effective_[body].com_body;
}

Vector4d System::euler_parameters(int body, const VectorXd& q) const {
  const int k = moving_index_[body];
  return k >= 0 ? Vector4d(q.segment<4>(7 * k + 3)) : fixed_p_[body];
}

Matrix3d System::rotation(int body, const VectorXd& q) const { return spatial::rotation(euler_parameters(body, q)); }

Vector3d System::com_velocity(int body, const VectorXd& v) const {
  const int k = moving_index_[body];
  return k >= 0 ? Vector3d(v.segment<3>(6 * k)) : Vector3d::Zero();
}

Vector3d System::angular_velocity_body(int body, const VectorXd& v) const {
  const int k = moving_index_[body];
  return k >= 0 ? Vector3d(v.segment<3>(6 * k + 3)) : Vector3d::Zero();
}

Vector3d System::point_world(int body, const std::string& point, const VectorXd& q) const {
  return com(body, q) + rotation(body, q) * relative_point(body, point);
}

BlockValues System::evaluate(const ConstraintBlock& blk, const VectorXd& q, const VectorXd& v, double t) const {
  const auto side = [&](int body) {
    Side s;
    s.r = com(body, q);
    s.p = euler_parameters(body, q);
    s.a = spatial::rotation(s.p);
    s.r_dot = com_velocity(body, v);
    s.w = angular_velocity_body(body, v);
    return s;
  };
  const Side si = side(blk.body_i), sj = side(blk.body_j);
  const WorldVector h_i = body_vector(0, si, blk.h_i), f_i = body_vector(0, si, blk.f_i),
                    g_i = body_vector(0, si, blk.g_i), h_j = body_vector(1, sj, blk.h_j),
                    f_j = body_vector(1, sj, blk.f_j);
  const WorldVector d = point_difference(si, blk.s_i, sj, blk.s_j);
  const auto relative_angle = [&] { return angle(dot(g_i, f_j), dot(f_i, f_j)); };

  std::vector<Row> rows;
  // Rows whose value is an angle, compared with a reference, are wrapped; so
  // is the chain's length row, modulo one turn of the roller (2 pi r).
  bool last_is_angle = false, last_is_chain = false;
  const auto point_rows = [&] {
    for (int k = 0; k < 3; ++k) rows.push_back(dot(constant(Vector3d::Unit(k)), d));
  };
  const auto parallel_rows = [&] {
    rows.push_back(dot(f_i, h_j));
    rows.push_back(dot(g_i, h_j));
  };
  if (blk.kind == BlockKind::Drive) {
    switch (blk.coordinate) {
      case DriveCoordinate::Rotation:
        rows.push_back(relative_angle());
        last_is_angle = true;
        break;
      case DriveCoordinate::Translation:
        rows.push_back(dot(h_i, d));
        break;
    }
  } else {
    switch (blk.joint) {
      case JointType::Spherical:
        point_rows();
        break;
      case JointType::Revolute:
        point_rows();
        parallel_rows();
        break;
      case JointType::Cylindrical:
        parallel_rows();
        rows.push_back(dot(f_i, d));
        rows.push_back(dot(g_i, d));
        break;
      case JointType::Prismatic:
        parallel_rows();
        rows.push_back(dot(f_i, d));
        rows.push_back(dot(g_i, d));
        rows.push_back(relative_angle());
        last_is_angle = true;
        break;
      case JointType::Universal:
        point_rows();
        rows.push_back(dot(h_i, h_j));
        break;
      case JointType::Fixed:
        point_rows();
        parallel_rows();
        rows.push_back(relative_angle());
        last_is_angle = true;
        break;
      case JointType::Chain: {
        // The hinge seen from the roller centre, e = -d, in body_i's (f_i, g_i).
        const Row x = -1.0 * dot(f_i, d), y = -1.0 * dot(g_i, d);
        const double rho = std::hypot(x.value, y.value), r = blk.radius_m;
        require(rho > r && rho > 0.0,
                "spatial model '{}', chain '{}': the hinge lies within the roller at t = {} s (distance {} m in the "
                "chain's plane, r = {} m)",
                model_.name, blk.name, t, rho, r);
        rows.push_back(compose(chain_function(x.value, y.value, r, blk.sigma), x, y) +
                       (r * blk.sigma) * relative_angle());
        last_is_chain = true;
        break;
      }
    }
  }
  const int n = static_cast<int>(rows.size());
  BlockValues out;
  out.phi.resize(n);
  out.nu = VectorXd::Zero(n);
  out.gamma.resize(n);
  out.jq.resize(n, 14);
  out.pi.resize(n, 12);
  for (int k = 0; k < n; ++k) {
    out.phi(k) = rows[k].value;
    out.gamma(k) = -rows[k].quad;
    out.jq.row(k) = rows[k].jq;
    out.pi.row(k) = rows[k].pi;
  }
  if (last_is_angle || blk.kind == BlockKind::Drive) {
    double target = blk.reference;
    if (blk.kind == BlockKind::Drive && blk.law != nullptr) {
      const MotionState law = blk.law->at(t);
      target += law.s;
      out.nu(n - 1) = law.s_dot;
      out.gamma(n - 1) += law.s_ddot;
    }
    out.phi(n - 1) -= target;
    if (last_is_angle) out.phi(n - 1) = wrap_angle(out.phi(n - 1));
  }
  if (last_is_chain) {
    out.phi(n - 1) -= blk.reference;
    const double period = 2.0 * std::numbers::pi * blk.radius_m;
    if (period > 0.0) out.phi(n - 1) = std::remainder(out.phi(n - 1), period);
  }
  return out;
}

void System::scatter_q(const ConstraintBlock& blk, const MatrixXd& local, Eigen::Ref<MatrixXd> rows) const {
  const int ki = moving_index_[blk.body_i], kj = moving_index_[blk.body_j];
  if (ki >= 0) rows.middleCols(7 * ki, 7) += local.leftCols(7);
  if (kj >= 0) rows.middleCols(7 * kj, 7) += local.rightCols(7);
}

void System::scatter_v(const ConstraintBlock& blk, const MatrixXd& local, Eigen::Ref<MatrixXd> rows) const {
  const int ki = moving_index_[blk.body_i], kj = moving_index_[blk.body_j];
  if (ki >= 0) rows.middleCols(6 * ki, 6) += local.leftCols(6);
  if (kj >= 0) rows.middleCols(6 * kj, 6) += local.rightCols(6);
}

VectorXd System::phi(const VectorXd& q, double t) const {
  VectorXd out(n_rows_);
  const VectorXd v = VectorXd::Zero(n_velocities());
  for (const ConstraintBlock& blk : blocks_) out.segment(blk.first_row, blk.rows) = evaluate(blk, q, v, t).phi;
  return out;
}

MatrixXd System::jacobian_q(const VectorXd& q, double t) const {
  MatrixXd out = MatrixXd::Zero(n_rows_, n_positions());
  const VectorXd v = VectorXd::Zero(n_velocities());
  for (const ConstraintBlock& blk : blocks_)
    scatter_q(blk, evaluate(blk, q, v, t).jq, out.middleRows(blk.first_row, blk.rows));
  return out;
}

MatrixXd System::jacobian_v(const VectorXd& q, double t) const {
  MatrixXd out = MatrixXd::Zero(n_rows_, n_velocities());
  const VectorXd v = VectorXd::Zero(n_velocities());
  for (const ConstraintBlock& blk : blocks_)
    scatter_v(blk, evaluate(blk, q, v, t).pi, out.middleRows(blk.first_row, blk.rows));
  return out;
}

VectorXd System::nu(const VectorXd& q, double t) const {
  VectorXd out(n_rows_);
  const VectorXd v = VectorXd::Zero(n_velocities());
  for (const ConstraintBlock& blk : blocks_) out.segment(blk.first_row, blk.rows) = evaluate(blk, q, v, t).nu;
  return out;
}

VectorXd System::gamma(const VectorXd& q, const VectorXd& v, double t) const {
  VectorXd out(n_rows_);
  for (const ConstraintBlock& blk : blocks_) out.segment(blk.first_row, blk.rows) = evaluate(blk, q, v, t).gamma;
  return out;
}

VectorXd System::norm_phi(const VectorXd& q) const {
  VectorXd out(n_moving());
  for (int k = 0; k < n_moving(); ++k) out(k) = q.segment<4>(7 * k + 3).squaredNorm() - 1.0;
  return out;
}

MatrixXd System::norm_jacobian(const VectorXd& q) const {
  MatrixXd out = MatrixXd::Zero(n_moving(), n_positions());
  for (int k = 0; k < n_moving(); ++k) out.block<1, 4>(k, 7 * k + 3) = 2.0 * q.segment<4>(7 * k + 3).transpose();
  return out;
}

VectorXd System::position_rates(const VectorXd& q, const VectorXd& v) const {
  VectorXd out(n_positions());
  for (int k = 0; k < n_moving(); ++k) {
    out.segment<3>(7 * k) = v.segment<3>(6 * k);
    out.segment<4>(7 * k + 3) = 0.5 * g_matrix(q.segment<4>(7 * k + 3)).transpose() * v.segment<3>(6 * k + 3);
  }
  return out;
}

double System::position_drift_m(const VectorXd& q, double t) const {
  const double l = model_.characteristic_length_m;
  double drift = norm_phi(q).size() ? l * norm_phi(q).cwiseAbs().maxCoeff() : 0.0;
  const VectorXd v = VectorXd::Zero(n_velocities());
  for (const ConstraintBlock& blk : blocks_) {
    const VectorXd p = evaluate(blk, q, v, t).phi;
    for (int k = 0; k < blk.rows; ++k) drift = std::max(drift, std::abs(p(k)) * (blk.length_row[k] ? 1.0 : l));
  }
  return drift;
}

double System::velocity_drift_m_per_s(const VectorXd& q, const VectorXd& v, double t) const {
  const double l = model_.characteristic_length_m;
  double drift = 0.0;
  for (const ConstraintBlock& blk : blocks_) {
    const BlockValues b = evaluate(blk, q, v, t);
    MatrixXd rows = MatrixXd::Zero(blk.rows, n_velocities());
    scatter_v(blk, b.pi, rows);
    const VectorXd r = rows * v - b.nu;
    for (int k = 0; k < blk.rows; ++k) drift = std::max(drift, std::abs(r(k)) * (blk.length_row[k] ? 1.0 : l));
  }
  return drift;
}

MatrixXd System::mass_matrix() const {
  MatrixXd m = MatrixXd::Zero(n_velocities(), n_velocities());
  for (int k = 0; k < n_moving(); ++k) {
    const EffectiveBody& e = effective_[moving_[k]];
    m.block<3, 3>(6 * k, 6 * k) = e.mass_kg * Matrix3d::Identity();
    m.block<3, 3>(6 * k + 3, 6 * k + 3) = e.inertia_kgm2;
  }
  return m;
}

double System::force_drive_effort(int d, const VectorXd& q, const VectorXd& v, double t) const {
  const ForceDrive& drive = model_.force_drives.at(d);
  const ConstraintBlock& blk = force_blocks_.at(d);
  const BlockValues b = evaluate(blk, q, v, t);
  // s - s_0 (wrapped for a rotation) and s'.
  Eigen::Matrix<double, 12, 1> local = Eigen::Matrix<double, 12, 1>::Zero();
  const int ki = moving_index_[blk.body_i], kj = moving_index_[blk.body_j];
  if (ki >= 0) local.head<6>() = v.segment<6>(6 * ki);
  if (kj >= 0) local.tail<6>() = v.segment<6>(6 * kj);
  const double offset = b.phi(0), rate = b.pi.row(0).dot(local);
  switch (drive.law_type) {
    case EffortLaw::Constant:
      return drive.value;
    case EffortLaw::DcMotor:
      return drive.stall * (1.0 - rate / drive.no_load_speed);
    case EffortLaw::PdServo: {
      const MotionState m = drive.law->at(t);
      // The tracking error s_0 + law - s, an angle taken in (-pi, pi] so that
      // the wrapped s does not jump it by a turn.
      const double error = blk.coordinate == DriveCoordinate::Rotation ? -wrap_angle(offset - m.s) : m.s - offset;
      return drive.kp * error + drive.kd * (m.s_dot - rate);
    }
  }
  return 0.0;  // unreachable for a valid enum value
}

VectorXd System::forces(const VectorXd& q, const VectorXd& v, double t) const {
  VectorXd out(n_velocities());
  for (int k = 0; k < n_moving(); ++k) {
    const EffectiveBody& e = effective_[moving_[k]];
    const Vector3d w = v.segment<3>(6 * k + 3);
    out.segment<3>(6 * k) = e.mass_kg * model_.gravity;
    out.segment<3>(6 * k + 3) = -w.cross(e.inertia_kgm2 * w);
  }
  // A world force at a body point: the force, and its moment about the centre of mass in body axes.
  const auto add_force = [&](int b, const Vector3d& s_body, const Vector3d& force) {
    const int k = moving_index_[b];
    if (k < 0) return;
    out.segment<3>(6 * k) += force;
    out.segment<3>(6 * k + 3) += s_body.cross(rotation(b, q).transpose() * force);
  };
  for (const PointForce& f : model_.point_forces) {
    const int b = body_index(f.body);
    add_force(b, relative_point(b, f.point), f.force_world);
  }
  for (int d = 0; d < static_cast<int>(force_blocks_.size()); ++d) {
    // The load the drive row's multiplier -effort would give: Pi^T effort.
    const ConstraintBlock& blk = force_blocks_[d];
    const Eigen::Matrix<double, 12, 1> load =
        evaluate(blk, q, v, t).pi.row(0).transpose() * force_drive_effort(d, q, v, t);
    const int ki = moving_index_[blk.body_i], kj = moving_index_[blk.body_j];
    if (ki >= 0) out.segment<6>(6 * ki) += load.head<6>();
    if (kj >= 0) out.segment<6>(6 * kj) += load.tail<6>();
  }
  for (const Spring& sp : model_.springs) {
    const int bi = body_index(sp.body_i), bj = body_index(sp.body_j);
    const Vector3d s_i = relative_point(bi, sp.point_i), s_j = relative_point(bj, sp.point_j);
    const Matrix3d a_i = rotation(bi, q), a_j = rotation(bj, q);
    const Vector3d d = com(bj, q) + a_j * s_j - com(bi, q) - a_i * s_i;
    const Vector3d d_dot = com_velocity(bj, v) + a_j * angular_velocity_body(bj, v).cross(s_j) - com_velocity(bi, v) -
                           a_i * angular_velocity_body(bi, v).cross(s_i);
    const double length = d.norm();
    require(length > 0.0, "spatial model '{}', spring '{}': zero length, no direction", model_.name, sp.name);
    const Vector3d u = d / length;
    const double tension = sp.stiffness_N_per_m * (length - sp.free_length_m) + sp.damping_Ns_per_m * u.dot(d_dot);
    add_force(bi, s_i, tension * u);
    add_force(bj, s_j, -tension * u);
  }
  return out;
}

double System::kinetic_energy(const VectorXd& v) const {
  double t = 0.0;
  for (int k = 0; k < n_moving(); ++k) {
    const EffectiveBody& e = effective_[moving_[k]];
    const Vector3d w = v.segment<3>(6 * k + 3);
    t += 0.5 * e.mass_kg * v.segment<3>(6 * k).squaredNorm() + 0.5 * w.dot(e.inertia_kgm2 * w);
  }
  return t;
}

double System::potential_energy(const VectorXd& q) const {
  double u = 0.0;
  for (int k = 0; k < n_moving(); ++k) u -= effective_[moving_[k]].mass_kg * model_.gravity.dot(q.segment<3>(7 * k));
  for (const Spring& sp : model_.springs) {
    const int bi = body_index(sp.body_i), bj = body_index(sp.body_j);
    const double stretch = (point_world(bj, sp.point_j, q) - point_world(bi, sp.point_i, q)).norm() - sp.free_length_m;
    u += 0.5 * sp.stiffness_N_per_m * stretch * stretch;
  }
  return u;
}

Vector3d System::angular_momentum(const VectorXd& q, const VectorXd& v, const Vector3d& about_world) const {
  Vector3d h = Vector3d::Zero();
  for (int k = 0; k < n_moving(); ++k) {
    const EffectiveBody& e = effective_[moving_[k]];
    h += (q.segment<3>(7 * k) - about_world).cross(e.mass_kg * v.segment<3>(6 * k)) +
         spatial::rotation(q.segment<4>(7 * k + 3)) * (e.inertia_kgm2 * v.segment<3>(6 * k + 3));
  }
  return h;
}

}  // namespace kinetofem::mech::spatial
