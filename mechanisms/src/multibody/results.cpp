#include "kinetofem/mechanisms/multibody/results.hpp"

#include "kinetofem/mechanisms/multibody/chain_geometry.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "kinetofem/core/error.hpp"
#include "planar.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"

namespace kinetofem::mech {

using Eigen::Matrix2d;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::VectorXd;

using planar::cross;
using planar::perp;
using planar::rotation;

Frame make_frame(const MultibodySystem& system, double t, const VectorXd& q, const VectorXd& qd,
                 const FrameOptions& options, RunSummary* summary) {
  const MultibodyModel& model = system.model();
  Frame frame;
  frame.t = t;
  frame.jacobian_condition = jacobian_condition(system, q, t);
  if (!(frame.jacobian_condition * options.singular_tolerance < 1.0)) check_regular(system, q, t, options.singular_tolerance);
  const Accelerations acc = solve_accelerations(system, q, qd, t);
  frame.q = q;
  frame.q_dot = qd;
  frame.q_ddot = acc.q_ddot;
  frame.lambda = acc.lambda;

  // Bodies: centre-of-mass coordinates back to the body frame origin.
  const int nb = system.n_bodies();
  std::vector<Vector3d> com_acc(nb, Vector3d::Zero());
  for (int b = 0; b < nb; ++b) {
    BodyFrame bf;
    bf.name = model.bodies[b].name;
    const Vector3d pose = system.com_pose(b, q), vel = system.com_velocity(b, qd);
    const Vector3d accel = system.offset(b) >= 0 ? Vector3d(acc.q_ddot.segment<3>(system.offset(b))) : Vector3d::Zero();
    com_acc[b] = accel;
    const Vector2d ac = rotation(pose.z()) * system.effective(b).com_body;  // origin -> centre of mass
    bf.com = pose.head<2>();
    bf.com_velocity = vel.head<2>();
    bf.com_acceleration = accel.head<2>();
    bf.q << pose.head<2>() - ac, pose.z();
    bf.q_dot << vel.head<2>() - perp(ac) * vel.z(), vel.z();
    bf.q_ddot << accel.head<2>() - perp(ac) * accel.z() + ac * vel.z() * vel.z(), accel.z();
    frame.bodies.push_back(bf);
  }

  // Loads on each body for the d'Alembert check: applied + constraint - inertia.
  std::vector<Vector3d> balance(nb, Vector3d::Zero());
  double load_scale = 0.0;
  const std::vector<Vector3d> applied_loads = system.applied_loads(q, qd, t);
  for (int b = 0; b < nb; ++b) {
    if (system.offset(b) < 0) continue;
    const Vector3d& applied = applied_loads[b];
    const EffectiveBody& eff = system.effective(b);
    const Vector3d inertia(eff.mass_kg * com_acc[b].x(), eff.mass_kg * com_acc[b].y(), eff.inertia_kgm2 * com_acc[b].z());
    balance[b] = applied - inertia;
    load_scale = std::max({load_scale, applied.cwiseAbs().maxCoeff(), inertia.cwiseAbs().maxCoeff()});
  }

  auto make_reaction = [&](int body, const Vector2d& s, const Vector3d& load) {
    Reaction r;
    r.body = model.bodies[body].name;
    const Vector3d pose = system.com_pose(body, q);
    const Vector2d as = rotation(pose.z()) * s;
    r.point_world = pose.head<2>() + as;
    r.force_world = load.head<2>();
    r.force_body = rotation(pose.z()).transpose() * r.force_world;
    r.moment_Nm = load.z() - cross(as, r.force_world);
    return r;
  };

  const double force_scale = std::max(load_scale, acc.lambda.size() ? acc.lambda.cwiseAbs().maxCoeff() : 0.0);
  for (const ConstraintBlock& blk : system.blocks()) {
    const BlockValues values = system.evaluate(blk, q, qd, t);
    const VectorXd lambda = acc.lambda.segment(blk.first_row, blk.rows);
    const Eigen::Matrix<double, 6, 1> load = -values.jac.transpose() * lambda;
    if (system.offset(blk.body_i) >= 0) balance[blk.body_i] += load.head<3>();
    if (system.offset(blk.body_j) >= 0) balance[blk.body_j] += load.tail<3>();
    load_scale = std::max(load_scale, load.cwiseAbs().maxCoeff());
    switch (blk.kind) {
      case ConstraintKind::Transmission: {
        const Eigen::Matrix<double, 6, 1> input_load = -values.jac_input.transpose() * lambda;
        if (system.offset(blk.input_i) >= 0) balance[blk.input_i] += input_load.head<3>();
        if (system.offset(blk.input_j) >= 0) balance[blk.input_j] += input_load.tail<3>();
        load_scale = std::max(load_scale, input_load.cwiseAbs().maxCoeff());
        const Transmission& tr = model.transmissions[blk.source];
        TransmissionFrame tf;
        tf.name = blk.name;
        const Vector3d in_i = system.com_pose(blk.input_i, q), in_j = system.com_pose(blk.input_j, q);
        const Vector3d out_i = system.com_pose(blk.body_i, q), out_j = system.com_pose(blk.body_j, q);
        tf.s_in = in_j.z() - in_i.z();
        tf.s_out = out_j.z() - out_i.z();
        tf.s_in_dot = system.com_velocity(blk.input_j, qd).z() - system.com_velocity(blk.input_i, qd).z();
        tf.s_out_dot = system.com_velocity(blk.body_j, qd).z() - system.com_velocity(blk.body_i, qd).z();
        tf.moment_output_Nm = -lambda(0);
        tf.moment_input_Nm = blk.ratio * lambda(0);
        tf.force_N = tf.moment_output_Nm / tr.radius_m;
        frame.transmissions.push_back(tf);
        continue;
      }
      case ConstraintKind::Drive:
      case ConstraintKind::Joint:
        break;
    }
    if (blk.kind == ConstraintKind::Drive) {
      DriveFrame df;
      df.name = blk.name;
      df.prescribed = true;
      const MultibodySystem::CompiledCoordinate c{blk.coordinate, blk.body_i, blk.body_j, blk.s_i, blk.s_j, blk.axis_i};
      const auto cv = system.coordinate(c, q, qd);
      df.s = cv.value;
      df.s_dot = cv.rate;
      df.s_ddot = cv.grad.dot(system.gather(blk.body_i, blk.body_j, acc.q_ddot)) + cv.quadratic;
      df.effort = -lambda(0);
      df.power_W = df.effort * df.s_dot;
      frame.drives.push_back(df);
      continue;
    }
    JointFrame jf;
    jf.name = blk.name;
    jf.type = blk.joint;
    jf.on_i = make_reaction(blk.body_i, blk.s_i, load.head<3>());
    jf.on_j = make_reaction(blk.body_j, blk.s_j, load.tail<3>());
    frame.joints.push_back(jf);
    if (blk.joint == JointType::Chain) {
      ChainFrame cf;
      cf.name = blk.name;
      cf.tension_N = lambda(0);
      const double r = blk.radius_m;
      const ChainTangent tangent = chain_tangent(jf.on_i.point_world, jf.on_j.point_world, r, blk.sigma);
      cf.free_length_m = tangent.free_length_m;
      const double theta_j = system.com_pose(blk.body_j, q).z();
      cf.wrap_angle_rad = blk.sigma * (theta_j - tangent.tangent_angle_rad);
      // Nearest to the constraint's value, as in system.cpp.
      const double target = (blk.reference - cf.free_length_m) / r;
      cf.wrap_angle_rad += 2.0 * M_PI * std::round((target - cf.wrap_angle_rad) / (2.0 * M_PI));
      if (cf.tension_N < -1e-9 * std::max(force_scale, 1.0)) {
        const std::string what = fmt::format("chain '{}' goes slack at t = {} s (tension {:.6g} N)", blk.name, t, cf.tension_N);
        if (options.slack_is_error) fail("mechanism '{}': {}", model.name, what);
        if (summary) summary->slack_chains.push_back(what);
      }
      frame.chains.push_back(cf);
    }
  }
  for (std::size_t d = 0; d < model.force_drives.size(); ++d) {
    DriveFrame df;
    df.name = model.force_drives[d].name;
    const auto& c = system.force_drive_coordinate(static_cast<int>(d));
    const auto cv = system.coordinate(c, q, qd);
    df.s = cv.value;
    df.s_dot = cv.rate;
    df.s_ddot = cv.grad.dot(system.gather(c.body_i, c.body_j, acc.q_ddot)) + cv.quadratic;
    df.effort = system.force_drive_effort(static_cast<int>(d), q, qd, t);
    df.power_W = df.effort * df.s_dot;
    frame.drives.push_back(df);
  }

  double worst = 0.0;
  for (int b = 0; b < nb; ++b)
    if (system.offset(b) >= 0) worst = std::max(worst, balance[b].cwiseAbs().maxCoeff());
  frame.equilibrium_residual = load_scale > 0.0 ? worst / load_scale : worst;
  frame.kinetic_energy_J = system.kinetic_energy(qd);
  frame.potential_energy_J = system.potential_energy(q);
  frame.drift_position_m = system.position_drift_m(q, t);
  frame.drift_velocity_m_per_s = system.velocity_drift_m_per_s(q, qd, t);
  return frame;
}

void summarize(const MultibodySystem& system, Results& results, bool energy_balance) {
  RunSummary& s = results.summary;
  double energy_scale = 0.0, energy_error = 0.0;
  const Frame* first = results.frames.empty() ? nullptr : &results.frames.front();
  for (const Frame& f : results.frames) {
    s.max_drift_position_m = std::max(s.max_drift_position_m, f.drift_position_m);
    s.max_drift_velocity_m_per_s = std::max(s.max_drift_velocity_m_per_s, f.drift_velocity_m_per_s);
    s.max_equilibrium_residual = std::max(s.max_equilibrium_residual, f.equilibrium_residual);
    const double d_kinetic = f.kinetic_energy_J - first->kinetic_energy_J;
    const double d_potential = f.potential_energy_J - first->potential_energy_J;
    energy_scale = std::max({energy_scale, std::abs(f.kinetic_energy_J), std::abs(d_potential),
                             std::abs(f.work_drives_J), std::abs(f.work_other_J)});
    energy_error = std::max(energy_error, std::abs(d_kinetic + d_potential - f.work_drives_J - f.work_other_J));
  }
  s.max_drift_relative = s.max_drift_position_m / system.characteristic_length();
  s.energy_balance_error = energy_balance ? (energy_scale > 0.0 ? energy_error / energy_scale : energy_error) : 0.0;
}

std::string Results::format_checks() const {
  const RunSummary& s = summary;
  std::string out = fmt::format("{}: {} output frames\n", s.method, frames.size());
  out += fmt::format("  constraint drift: position {:.3e} m ({:.3e} of the characteristic length), velocity {:.3e} m/s\n",
                     s.max_drift_position_m, s.max_drift_relative, s.max_drift_velocity_m_per_s);
  out += fmt::format("  d'Alembert equilibrium of each body: max relative residual {:.3e}\n", s.max_equilibrium_residual);
  out += fmt::format("  energy balance |dT + dV - W| / scale: {:.3e}\n", s.energy_balance_error);
  if (s.steps > 0)
    out += fmt::format("  solver: {} steps, {} residual/rhs evaluations, {} Jacobians, {} error-test and {} nonlinear "
                       "failures\n",
                       s.steps, s.residual_evaluations, s.jacobian_evaluations, s.error_test_failures,
                       s.nonlinear_failures);
  for (const std::string& slack : s.slack_chains) out += fmt::format("  warning: {}\n", slack);
  return out;
}

std::string Results::format_final_reactions() const {
  std::string out;
  if (!frames.empty()) {
    const Frame& f = frames.back();
    for (const JointFrame& j : f.joints)
      out += fmt::format("  t = {:.4g} s, {} '{}': on {} F = ({:.6g}, {:.6g}) N, M = {:.6g} N m\n", f.t,
                         joint_facts(j.type).name, j.name, j.on_j.body, j.on_j.force_world.x(), j.on_j.force_world.y(),
                         j.on_j.moment_Nm);
  }
  return out;
}

}  // namespace kinetofem::mech
