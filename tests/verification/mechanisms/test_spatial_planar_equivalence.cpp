// The planar cases keep working through the spatial core: the SPEC §1
// lever-chain manipulator and the SPEC §2 lever manipulator, built by
// mech::make_manipulator_model as the app builds them, lifted into the
// spatial core by spatial::from_planar (z = 0 plane, axes along z) and run
// through both cores at the same output times. Reference: the planar core
// (multibody/), whose runs on these models are verified against the closed
// forms of SPEC §1/§2 (test_dynamics_lever_chain.cpp, test_spec2_four_bar.cpp).
// Also: the spatial chain row with a roller in a general spatial pose against
// finite differences (the joint-table tests use the r = 0 tie), springs and
// dampers against the planar core at the same states, and a changed mass that
// must move the results (the comparison can fail).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/manipulator_models.hpp"
#include "kinetofem/mechanisms/manipulator_names.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/dynamics.hpp"
#include "kinetofem/mechanisms/spatial/from_planar.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/rotation.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"

namespace kinetofem::mech {
namespace {

using Eigen::MatrixXd;
using Eigen::Vector2d;
using Eigen::Vector3d;
using Eigen::Vector4d;
using Eigen::VectorXd;

constexpr double kDeg = std::numbers::pi / 180.0;

// The SPEC §1/§2 manipulator as the bundled cases give it to
// make_manipulator_model (cases/lever_chain_manipulator, cases/lever_manipulator):
// the published example geometry (a = 500 mm, c = 350 mm, h = 100 mm,
// r = 75 mm), gripper 20 kg and casting 15 kg at H, gravity 9.80665 m/s^2
// along -y, the lever turned by the 3-4-5 polynomial in 2 s, 80 deg for the
// lever-chain manipulator and 30 deg for the lever manipulator (the four-bar
// assembles only up to +36.4 deg). The links' mass properties, which the app
// takes from their meshes, are uniform rods here (lever 8 kg, arm 5 kg,
// rocker 3 kg).
MultibodyModel manipulator(ManipulatorType type) {
  const LeverChainGeometry g = verification::spec1::example_geometry();
  ManipulatorDefinition d;
  d.type = type;
  d.geometry = g;
  d.lever = {8.0, {0.0, 0.5 * g.a_m}, 8.0 * g.a_m * g.a_m / 12.0};
  d.arm = {5.0, {-0.5 * g.c_m, 0.0}, 5.0 * g.c_m * g.c_m / 12.0};
  d.rocker = {3.0, {0.0, 0.5 * g.b0_m}, 3.0 * g.b0_m * g.b0_m / 12.0};
  d.gripper_mass_kg = 20.0;
  d.casting_mass_kg = 15.0;
  d.gravity_m_s2 = {0.0, -9.80665};
  const double stroke_deg = type == ManipulatorType::LeverChain ? 80.0 : 30.0;
  d.lever_motion = std::make_shared<Polynomial345Law>(stroke_deg * kDeg, 2.0);
  return make_manipulator_model(d);
}

std::vector<double> output_times() {
  std::vector<double> t;
  for (int k = 0; k <= 40; ++k) t.push_back(2.0 * k / 40);
  return t;
}

// The chain's tension is its row's multiplier (spatial/system.hpp).
double spatial_tension(const spatial::System& sys, const spatial::Frame& f, const std::string& chain) {
  return f.lambda(sys.block(chain).first_row);
}

// Worst differences over all output times, each relative to the largest of its
// kind in the planar run; the out-of-plane components relative to the same scales.
struct Agreement {
  double force = 0.0, moment = 0.0, point = 0.0, tension = 0.0, torque = 0.0, pose = 0.0;
  double out_of_plane_force = 0.0, out_of_plane_moment = 0.0;
  double force_scale = 0.0, moment_scale = 0.0;
};

Agreement compare(const MultibodySystem& planar, const Results& p, const spatial::System& spatial,
                  const spatial::Results& s) {
  Agreement a;
  const double length = planar.characteristic_length();
  double tension_scale = 0.0, torque_scale = 0.0;
  for (const Frame& f : p.frames) {
    for (const JointFrame& j : f.joints)
      for (const Reaction* r : {&j.on_i, &j.on_j}) {
        a.force_scale = std::max(a.force_scale, r->force_world.norm());
        a.moment_scale = std::max(a.moment_scale, std::abs(r->moment_Nm));
      }
    for (const ChainFrame& c : f.chains) tension_scale = std::max(tension_scale, std::abs(c.tension_N));
    torque_scale = std::max(torque_scale, std::abs(f.drives.at(0).effort));
  }
  // A revolute carries no moment: the moments' scale is then that of a force on the lever's arm.
  a.moment_scale = std::max(a.moment_scale, a.force_scale * length);
  EXPECT_EQ(p.frames.size(), s.frames.size());
  for (std::size_t k = 0; k < std::min(p.frames.size(), s.frames.size()); ++k) {
    const Frame& fp = p.frames[k];
    const spatial::Frame& fs = s.frames[k];
    EXPECT_EQ(fp.t, fs.t);
    EXPECT_EQ(fp.joints.size(), fs.joints.size());
    for (std::size_t j = 0; j < fp.joints.size(); ++j) {
      EXPECT_EQ(fp.joints[j].name, fs.joints[j].name);
      const Reaction* rp[2] = {&fp.joints[j].on_i, &fp.joints[j].on_j};
      const spatial::Reaction* rs[2] = {&fs.joints[j].on_i, &fs.joints[j].on_j};
      for (int side = 0; side < 2; ++side) {
        a.force = std::max(a.force, (rp[side]->force_world - rs[side]->force_world.head<2>()).norm() / a.force_scale);
        a.moment = std::max(a.moment, std::abs(rp[side]->moment_Nm - rs[side]->moment_world.z()) / a.moment_scale);
        a.point = std::max(a.point, (rp[side]->point_world - rs[side]->point_world.head<2>()).norm() / length);
        a.out_of_plane_force = std::max(a.out_of_plane_force, std::abs(rs[side]->force_world.z()) / a.force_scale);
        a.out_of_plane_moment =
            std::max(a.out_of_plane_moment, rs[side]->moment_world.head<2>().norm() / a.moment_scale);
      }
    }
    for (const ChainFrame& c : fp.chains)
      a.tension = std::max(a.tension, std::abs(c.tension_N - spatial_tension(spatial, fs, c.name)) / tension_scale);
    a.torque = std::max(a.torque, std::abs(fp.drives.at(0).effort - fs.drives.at(0).effort) / torque_scale);
    for (std::size_t b = 0; b < fp.bodies.size(); ++b) {
      const Vector3d& qp = fp.bodies[b].q;
      const spatial::BodyState& bs = fs.bodies[b];
      const double angle = std::atan2(bs.rotation(1, 0), bs.rotation(0, 0));
      a.pose = std::max({a.pose, (qp.head<2>() - bs.origin.head<2>()).norm() / length, std::abs(bs.origin.z()) / length,
                         std::abs(std::remainder(qp.z() - angle, 2.0 * std::numbers::pi))});
    }
  }
  return a;
}

void print(const char* what, const Agreement& a) {
  std::printf(
      "%s, spatial vs planar (relative): forces %.2e, moments %.2e, joint points %.2e, chain tension %.2e, drive "
      "effort %.2e, poses %.2e; out of plane: forces %.2e, moments %.2e (scales %.4g N, %.4g N m)\n",
      what, a.force, a.moment, a.point, a.tension, a.torque, a.pose, a.out_of_plane_force, a.out_of_plane_moment,
      a.force_scale, a.moment_scale);
}

// Reference: the planar core's kinetostatics of the same model (SPEC §1/§2).
// Both cores assemble to 1e-13 of the lever length and solve the same in-plane
// equations; 1e-9 of the largest value of each kind leaves room for the
// conditioning of the two Jacobians, round-off is ~1e-13. The out-of-plane
// components vanish exactly in exact arithmetic: 1e-12 of the same scales.
void expect_agreement(const Agreement& a) {
  EXPECT_LT(a.force, 1e-9);
  EXPECT_LT(a.moment, 1e-9);
  EXPECT_LT(a.point, 1e-9);
  EXPECT_LT(a.tension, 1e-9);
  EXPECT_LT(a.torque, 1e-9);
  EXPECT_LT(a.pose, 1e-9);
  EXPECT_LT(a.out_of_plane_force, 1e-12);
  EXPECT_LT(a.out_of_plane_moment, 1e-12);
}

TEST(SpatialPlanarEquivalence, LeverChainManipulatorSpec1) {
  const MultibodySystem planar(manipulator(ManipulatorType::LeverChain));
  const spatial::System spatial(spatial::from_planar(planar.model()));
  const Results p = run_kinematics(planar, output_times());
  const spatial::Results s = spatial::run_kinematics(spatial, output_times());
  ASSERT_EQ(p.frames.front().chains.size(), 1u);
  const Agreement a = compare(planar, p, spatial, s);
  print("SPEC §1 lever-chain manipulator", a);
  std::printf("%s", s.format_checks().c_str());
  expect_agreement(a);
  // One chain, two revolutes and a drive on two links: no redundant row.
  EXPECT_EQ(s.summary.redundant_rows, 0);
  EXPECT_LT(s.summary.max_drift_relative, 1e-12);
}

TEST(SpatialPlanarEquivalence, LeverManipulatorSpec2) {
  const MultibodySystem planar(manipulator(ManipulatorType::Lever));
  const spatial::System spatial(spatial::from_planar(planar.model()));
  const Results p = run_kinematics(planar, output_times());
  const spatial::Results s = spatial::run_kinematics(spatial, output_times());
  const Agreement a = compare(planar, p, spatial, s);
  print("SPEC §2 lever manipulator", a);
  std::printf("%s", s.format_checks().c_str());
  expect_agreement(a);
  // The four-bar loop of spatial revolutes: 3 redundant (out-of-plane) rows.
  EXPECT_EQ(s.summary.redundant_rows, 3);
}

// A slider-crank on a guide tilted by 20 deg, the slider turned 0.3 rad
// against the guide and a payload welded to it (prismatic and fixed joints
// lifted, and a Translation drive), a spring from the ground to the crank and
// a point force on the payload, driven by the slider's displacement.
MultibodyModel tilted_slider_crank() {
  const double r = 0.2, l = 0.6, phi = 60.0 * kDeg, slide = 20.0 * kDeg, turn = 0.3;
  const Vector2d u(std::cos(slide), std::sin(slide)), g0(0.1, -0.05), a(r * std::cos(phi), r * std::sin(phi));
  // The assembled pose: the slider point on the guide at distance l from the crank pin.
  const Vector2d w = g0 - a;
  const double s0 = -w.dot(u) + std::sqrt(w.dot(u) * w.dot(u) - w.squaredNorm() + l * l);
  const Vector2d p = g0 + s0 * u;
  MultibodyModel m;
  m.name = "tilted slider-crank";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["g0"] = g0;
  ground.points["anchor"] = {-0.3, 0.4};
  Body crank;
  crank.name = "crank";
  crank.mass_kg = 1.5;
  crank.inertia_kgm2 = 1.5 * r * r / 12.0;
  crank.com_body = {0.5 * r, 0.0};
  crank.points["pin"] = {r, 0.0};
  crank.pose = {0.0, 0.0, phi};
  Body rod;
  rod.name = "rod";
  rod.mass_kg = 2.0;
  rod.inertia_kgm2 = 2.0 * l * l / 12.0;
  rod.com_body = {0.5 * l, 0.0};
  rod.points["end"] = {l, 0.0};
  rod.pose = {a.x(), a.y(), std::atan2(p.y() - a.y(), p.x() - a.x())};
  Body slider;
  slider.name = "slider";
  slider.mass_kg = 3.0;
  slider.inertia_kgm2 = 0.02;
  slider.com_body = {0.02, -0.01};
  slider.points["top"] = {0.0, 0.1};
  slider.pose = {p.x(), p.y(), turn};
  Body payload;
  payload.name = "payload";
  payload.mass_kg = 4.0;
  payload.inertia_kgm2 = 0.05;
  payload.com_body = {0.15, 0.05};
  payload.point_masses.push_back({"tool", 1.0, {0.3, 0.0}});
  const Vector2d top = p + Eigen::Rotation2Dd(turn) * Vector2d(0.0, 0.1);
  payload.pose = {top.x(), top.y(), turn + 0.2};
  m.bodies = {ground, crank, rod, slider, payload};
  m.joints.push_back(make_revolute("O", "ground", "origin", "crank", "origin"));
  m.joints.push_back(make_revolute("A", "crank", "pin", "rod", "origin"));
  m.joints.push_back(make_revolute("B", "rod", "end", "slider", "origin"));
  m.joints.push_back(make_prismatic("guide", "ground", "g0", "slider", "origin", u));
  m.joints.push_back(make_fixed("weld", "slider", "top", "payload", "origin"));
  MotionDrive push;
  push.name = "push";
  push.coordinate = {CoordinateType::Displacement, "ground", "g0", "slider", "origin", u};
  push.law = std::make_shared<Polynomial345Law>(-0.15, 1.0);  // pulled back: away from the dead centre
  m.motion_drives.push_back(push);
  m.springs.push_back({"spring", "ground", "anchor", "crank", "pin", 300.0, 0.0, 0.2});
  m.point_forces.push_back({"load", "payload", "origin", {-20.0, 15.0}});
  m.characteristic_length_m = l;
  return m;
}

TEST(SpatialPlanarEquivalence, TiltedSliderCrankWithWeldedPayload) {
  const MultibodySystem planar(tilted_slider_crank());
  const spatial::System spatial(spatial::from_planar(planar.model()));
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(0.05 * k);
  const Results p = run_kinematics(planar, times);
  const spatial::Results s = spatial::run_kinematics(spatial, times);
  const Agreement a = compare(planar, p, spatial, s);
  print("tilted slider-crank (prismatic, fixed, translation drive, spring)", a);
  std::printf("%s", s.format_checks().c_str());
  // Reference: the planar core's kinetostatics; tolerances as for the manipulators.
  expect_agreement(a);
  // The loop crank-rod-slider of spatial revolutes and a prismatic: 3 redundant rows.
  EXPECT_EQ(s.summary.redundant_rows, 3);
}

// The comparison can fail: 1 % more arm mass in the spatial model only moves
// the reactions, the chain tension and the drive torque far beyond 1e-9.
TEST(SpatialPlanarEquivalence, ChangedArmMassIsSeen) {
  const MultibodySystem planar(manipulator(ManipulatorType::LeverChain));
  spatial::Model lifted = spatial::from_planar(planar.model());
  for (spatial::Body& b : lifted.bodies)
    if (b.name == manipulator::kArm) b.mass_kg *= 1.01;
  const spatial::System spatial(lifted);
  const Agreement a = compare(planar, run_kinematics(planar, output_times()), spatial,
                              spatial::run_kinematics(spatial, output_times()));
  print("arm mass +1 % in the spatial model only", a);
  EXPECT_GT(a.force, 1e-4);
  EXPECT_GT(a.tension, 1e-4);
  EXPECT_GT(a.torque, 1e-4);
  EXPECT_LT(a.pose, 1e-9);  // the motion is prescribed: the poses still agree
}

// Hamilton product: A(a (x) b) = A(a) A(b).
Vector4d quaternion_product(const Vector4d& a, const Vector4d& b) {
  Vector4d c;
  c(0) = a(0) * b(0) - a.tail<3>().dot(b.tail<3>());
  c.tail<3>() = a(0) * b.tail<3>() + b(0) * a.tail<3>() + a.tail<3>().cross(b.tail<3>());
  return c;
}

// A chain from a hinge on one tilted moving body to a roller of r = 0.07 m on
// another, in general spatial poses (the hinge off the roller's plane).
spatial::Model chain_model(bool wrap_ccw) {
  spatial::Model m;
  m.name = "chain in space";
  spatial::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  spatial::Body a;
  a.name = "a";
  a.mass_kg = 2.0;
  a.inertia_kgm2 = Vector3d(0.1, 0.2, 0.15).asDiagonal();
  a.com_body = {0.1, 0.05, -0.02};
  a.points["hinge"] = {0.4, -0.1, 0.05};
  a.euler_parameters = spatial::axis_angle(Vector3d(1, 2, 3).normalized(), 0.5);
  spatial::Body b = a;
  b.name = "b";
  b.points["centre"] = {-0.05, 0.02, 0.03};
  b.position = {0.6, 0.3, -0.1};
  b.euler_parameters = spatial::axis_angle(Vector3d(-1, 0.4, 1).normalized(), 1.2);
  m.bodies = {ground, a, b};
  m.joints.push_back(spatial::make_joint("hold", spatial::JointType::Spherical, "ground", "origin", "a", "origin"));
  spatial::Joint c = spatial::make_joint("chain", spatial::JointType::Chain, "a", "hinge", "b", "centre",
                                         Vector3d(0.2, 0.3, 1.0), Vector3d(0.1, -0.2, 1.0));
  c.radius_m = 0.07;
  c.wrap_ccw = wrap_ccw;
  m.joints.push_back(c);
  return m;
}

TEST(SpatialPlanarEquivalence, ChainHingeInsideTheRollerIsNamed) {
  spatial::Model m = chain_model(true);
  m.joints.back().radius_m = 2.0;  // larger than the hinge's distance from the centre
  try {
    const spatial::System sys(m);
    ADD_FAILURE() << "a hinge inside the roller was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("chain 'chain'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("within the roller"), std::string::npos) << e.what();
  }
  m.joints.back().radius_m = -0.1;
  EXPECT_THROW(spatial::System{m}, Error);
}

TEST(SpatialPlanarEquivalence, ChainRowJacobianAndGammaWithARoller) {
  for (bool ccw : {true, false}) {
    const spatial::System sys(chain_model(ccw));
    const VectorXd q0 = sys.initial_positions();
    const MatrixXd jac = sys.jacobian_q(q0, 0.0);
    MatrixXd fd(jac.rows(), jac.cols());
    const double h = 1e-6;
    for (int k = 0; k < q0.size(); ++k) {
      VectorXd qp = q0, qm = q0;
      qp(k) += h;
      qm(k) -= h;
      fd.col(k) = (sys.phi(qp, 0.0) - sys.phi(qm, 0.0)) / (2.0 * h);
    }
    const double jac_error = (jac - fd).cwiseAbs().maxCoeff() / jac.cwiseAbs().maxCoeff();
    // A known motion with v' = 0: r = r0 + u t, constant body-axes angular
    // velocity w, p(t) = p0 (x) (cos(|w| t / 2), sin(|w| t / 2) w / |w|); then
    // Phi'' = -gamma (system.hpp).
    const int nb = sys.n_moving();
    VectorXd v(sys.n_velocities());
    v << 0.3, -0.5, 0.2, 1.1, -0.7, 0.4, -0.6, 0.8, 0.2, 2.0, 0.5, -1.5;
    const auto q_at = [&](double t) {
      VectorXd q = q0;
      for (int k = 0; k < nb; ++k) {
        q.segment<3>(7 * k) += t * v.segment<3>(6 * k);
        const Vector3d w = v.segment<3>(6 * k + 3);
        Vector4d turn;
        turn << std::cos(0.5 * w.norm() * t), std::sin(0.5 * w.norm() * t) * w.normalized();
        q.segment<4>(7 * k + 3) = quaternion_product(q0.segment<4>(7 * k + 3), turn);
      }
      return q;
    };
    const double dt = 1e-4;
    const VectorXd second = (sys.phi(q_at(dt), 0.0) - 2.0 * sys.phi(q_at(0.0), 0.0) + sys.phi(q_at(-dt), 0.0)) / (dt * dt);
    const VectorXd gamma = sys.gamma(q0, v, 0.0);
    const int row = sys.block("chain").first_row;
    const double gamma_error = std::abs(second(row) + gamma(row)) / std::max(1.0, std::abs(gamma(row)));
    std::printf("chain row with r = 0.07 m, %s wrap: Phi_q vs central differences %.2e, gamma vs second difference "
                "%.2e (gamma %.4g)\n",
                ccw ? "counter-clockwise" : "clockwise", jac_error, gamma_error, gamma(row));
    // Reference: central differences, truncation O(h^2) ~ 1e-12 and round-off
    // ~ eps / h ~ 1e-10 (Jacobian); second differences, truncation O(dt^2) and
    // round-off eps / dt^2 ~ 1e-8 (gamma): the joint-table test's tolerances.
    EXPECT_LT(jac_error, 1e-7);
    EXPECT_LT(gamma_error, 1e-6);
    // Pi = Phi_q L on unit Euler parameters.
    MatrixXd l = MatrixXd::Zero(sys.n_positions(), sys.n_velocities());
    for (int k = 0; k < sys.n_velocities(); ++k) l.col(k) = sys.position_rates(q0, VectorXd::Unit(sys.n_velocities(), k));
    EXPECT_LT((sys.jacobian_v(q0, 0.0) - jac * l).cwiseAbs().maxCoeff(), 1e-13);
  }
}

// A pendulum held by a spring-damper to the ground, in the plane: IDAS in the
// planar core; the spatial core's accelerations, reactions and spring loads at
// the planar run's states (q, q') lifted (the same state: exact in exact
// arithmetic), and the spatial IDAS run against the planar one.
MultibodyModel spring_pendulum() {
  MultibodyModel m;
  m.name = "spring pendulum";
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["anchor"] = {0.8, 0.3};
  Body rod;
  rod.name = "rod";
  rod.mass_kg = 3.0;
  rod.inertia_kgm2 = 3.0 * 0.6 * 0.6 / 12.0;
  rod.com_body = {0.3, 0.0};
  rod.points["end"] = {0.6, 0.0};
  rod.point_masses.push_back({"tip", 0.5, {0.6, 0.02}});
  rod.pose = {0.0, 0.0, -0.4};
  m.bodies = {ground, rod};
  m.joints.push_back(make_revolute("pivot", "ground", "origin", "rod", "origin"));
  m.springs.push_back({"spring", "ground", "anchor", "rod", "end", 400.0, 6.0, 0.3});
  m.point_forces.push_back({"push", "rod", "end", {5.0, -2.0}});
  m.characteristic_length_m = 0.6;
  return m;
}

TEST(SpatialPlanarEquivalence, SpringDamperPendulumAtTheSameStates) {
  const MultibodySystem planar(spring_pendulum());
  const spatial::System spatial(spatial::from_planar(planar.model()));
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(0.05 * k);
  const Results p = simulate_ggl(planar, times);
  double force_scale = 0.0;
  for (const Frame& f : p.frames) force_scale = std::max(force_scale, f.joints[0].on_j.force_world.norm());
  double state_error = 0.0, accel_error = 0.0;
  for (const Frame& f : p.frames) {
    VectorXd q(7), v(6);
    q << f.q(0), f.q(1), 0.0, spatial::axis_angle(Vector3d::UnitZ(), f.q(2));
    v << f.q_dot(0), f.q_dot(1), 0.0, 0.0, 0.0, f.q_dot(2);
    const spatial::Frame s = spatial::make_frame(spatial, f.t, q, v);
    state_error = std::max({state_error,
                            (f.joints[0].on_j.force_world - s.joints[0].on_j.force_world.head<2>()).norm() / force_scale,
                            std::abs(s.joints[0].on_j.force_world.z()) / force_scale});
    accel_error = std::max(accel_error, std::abs(f.q_ddot(2) - s.v_dot(5)) / std::max(1.0, std::abs(f.q_ddot(2))));
  }
  const spatial::Results s = spatial::simulate_ggl(spatial, times);
  double run_error = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const Eigen::Matrix3d& a = s.frames[k].bodies[1].rotation;
    run_error = std::max(run_error, std::abs(std::remainder(p.frames[k].bodies[1].q.z() - std::atan2(a(1, 0), a(0, 0)),
                                                            2.0 * std::numbers::pi)));
  }
  std::printf("spring-damper pendulum: at the planar states, reaction %.2e of %.4g N, angular acceleration %.2e; "
              "IDAS runs, angle %.2e rad\n",
              state_error, force_scale, accel_error, run_error);
  // Reference: the planar core at the same state; round-off (1e-12 relative).
  EXPECT_LT(state_error, 1e-12);
  EXPECT_LT(accel_error, 1e-12);
  // Reference: the planar IDAS run; both integrate to rtol 1e-10, atol 1e-12:
  // 1e-7 rad leaves room for the two integrators' different steps.
  EXPECT_LT(run_error, 1e-7);
  // The spring and damper do work: without them the motion differs.
  MultibodyModel bare = spring_pendulum();
  bare.springs.clear();
  const spatial::System no_spring(spatial::from_planar(bare));
  const spatial::Results sb = spatial::simulate_ggl(no_spring, times);
  const Eigen::Matrix3d& a = sb.frames.back().bodies[1].rotation;
  EXPECT_GT(std::abs(p.frames.back().bodies[1].q.z() - std::atan2(a(1, 0), a(0, 0))), 1e-3);
}

// The same pendulum driven by a DC motor and a PD servo on its pivot (force
// drives): the efforts and accelerations at the planar run's states, and the
// two IDAS runs.
TEST(SpatialPlanarEquivalence, ForceDrivesAtTheSameStates) {
  MultibodyModel m = spring_pendulum();
  ForceDrive motor;
  motor.name = "motor";
  motor.coordinate = {CoordinateType::Angle, "ground", "origin", "rod", "origin", {1, 0}};
  motor.law_type = ForceLaw::DcMotor;
  motor.stall = 30.0;
  motor.no_load_speed = 6.0;
  ForceDrive servo = motor;
  servo.name = "servo";
  servo.law_type = ForceLaw::PdServo;
  servo.kp = 80.0;
  servo.kd = 4.0;
  servo.law = std::make_shared<CycloidalLaw>(0.8, 1.0);
  m.force_drives = {motor, servo};
  const MultibodySystem planar(m);
  const spatial::System spatial(spatial::from_planar(planar.model()));
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(0.05 * k);
  const Results p = simulate_ggl(planar, times);
  double effort_scale = 0.0, effort_error = 0.0, accel_error = 0.0;
  for (const Frame& f : p.frames) {
    VectorXd q(7), v(6);
    q << f.q(0), f.q(1), 0.0, spatial::axis_angle(Vector3d::UnitZ(), f.q(2));
    v << f.q_dot(0), f.q_dot(1), 0.0, 0.0, 0.0, f.q_dot(2);
    const spatial::Frame s = spatial::make_frame(spatial, f.t, q, v);
    for (int d = 0; d < 2; ++d) {
      effort_scale = std::max(effort_scale, std::abs(f.drives.at(d).effort));
      effort_error = std::max(effort_error, std::abs(f.drives.at(d).effort - spatial.force_drive_effort(d, q, v, f.t)));
    }
    accel_error = std::max(accel_error, std::abs(f.q_ddot(2) - s.v_dot(5)) / std::max(1.0, std::abs(f.q_ddot(2))));
  }
  const spatial::Results s = spatial::simulate_ggl(spatial, times);
  double run_error = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const Eigen::Matrix3d& a = s.frames[k].bodies[1].rotation;
    run_error = std::max(run_error, std::abs(std::remainder(p.frames[k].bodies[1].q.z() - std::atan2(a(1, 0), a(0, 0)),
                                                            2.0 * std::numbers::pi)));
  }
  std::printf("force drives: at the planar states, efforts %.2e of %.4g N m, angular acceleration %.2e; IDAS runs, "
              "angle %.2e rad\n",
              effort_error / effort_scale, effort_scale, accel_error, run_error);
  // Reference: the planar core at the same state (round-off), and its IDAS run (as above).
  EXPECT_LT(effort_error / effort_scale, 1e-12);
  EXPECT_LT(accel_error, 1e-12);
  EXPECT_LT(run_error, 1e-7);
  EXPECT_GT(effort_scale, 1.0);
}

TEST(SpatialPlanarEquivalence, UnsupportedPlanarFeaturesAreNamed) {
  MultibodyModel m = spring_pendulum();
  m.bodies.push_back(m.bodies[1]);
  m.bodies.back().name = "second";
  m.joints.push_back(make_revolute("hinge", "rod", "end", "second", "origin"));
  Transmission belt;
  belt.name = "belt";
  belt.input = {CoordinateType::Angle, "ground", "origin", "rod", "origin", {1, 0}};
  belt.output = {CoordinateType::Angle, "rod", "origin", "second", "origin", {1, 0}};
  belt.ratio = -0.5;
  belt.radius_m = 0.05;
  m.transmissions.push_back(belt);
  try {
    (void)spatial::from_planar(m);
    ADD_FAILURE() << "a transmission was lifted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("transmission"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("belt"), std::string::npos) << e.what();
  }
  m.transmissions.clear();
  MotionDrive drive;
  drive.name = "backwards";
  drive.coordinate = {CoordinateType::Angle, "rod", "origin", "ground", "origin", {1, 0}};
  drive.law = std::make_shared<Polynomial345Law>(0.1, 1.0);
  m.motion_drives.push_back(drive);
  EXPECT_THROW((void)spatial::from_planar(m), Error);
}

}  // namespace
}  // namespace kinetofem::mech
