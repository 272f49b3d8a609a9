// Stages of the rigid-body motion (pipeline/motion_stages.hpp): the check of
// the motion before meshing, the dynamics methods, the static pose at rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/four_bar.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/pipeline/motion_stages.hpp"
#include "kinetofem/verification/spec2_four_bar.hpp"
#include "pipeline_fixtures.hpp"

namespace kinetofem::pipeline {
namespace {

using test::error_of;
using test::kDeg;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The first "t = <number>" of a message (s); NaN if none.
double first_time_in(const std::string& message) {
  const std::size_t at = message.find("t = ");
  return at == std::string::npos ? std::nan("") : std::stod(message.substr(at + 4));
}

// The SPEC §2 four-bar (lever manipulator) and the lever rotation from the
// design position to its upper limit of assembly, in closed form
// (verification/spec2_four_bar.hpp: |A B0| = coupler + rocker or |coupler - rocker|).
double upper_assembly_limit_dphi(const mech::LeverChainGeometry& g) {
  const mech::FourBar four_bar = mech::make_equivalent_four_bar(g);
  return verification::spec2::closed_form_assembly_limits(g, four_bar).hi_rad - four_bar.design_input_rad();
}

// A pendulum "rod": mass m with its centre of mass at (l, 0) of its body frame,
// pinned at its origin to the frame; driven by "hold" (frame -> rod angle)
// when `driven`.
mech::MultibodyModel pendulum(double m, double l, std::shared_ptr<const mech::MotionLaw> law) {
  mech::MultibodyModel model;
  model.name = "pendulum";
  model.characteristic_length_m = l;
  mech::Body frame;
  frame.name = "frame";
  frame.fixed = true;
  mech::Body rod;
  rod.name = "rod";
  rod.mass_kg = m;
  rod.inertia_kgm2 = 0.01;
  rod.com_body = {l, 0.0};
  model.bodies = {frame, rod};
  model.joints.push_back(mech::make_revolute("pivot", "frame", "origin", "rod", "origin"));
  if (law) {
    mech::MotionDrive hold;
    hold.name = "hold";
    hold.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "rod", "origin", {1, 0}};
    hold.law = std::move(law);
    model.motion_drives.push_back(hold);
  }
  return model;
}

// ---- check_motion_before_meshing ------------------------------------------------

TEST(CheckMotionBeforeMeshing, FourBarDrivenPastItsLimitOfAssemblyNamesTheTime) {
  // The lever turns at a constant rate that reaches the closed-form upper
  // limit of assembly at t* = 0.63 s; output times every 0.05 s. The time
  // named must bracket the limit: the last assembled time (0.60 s, when the
  // position turns singular just before it) or the first one past it (0.65 s).
  mech::ManipulatorDefinition def = test::lever_chain_definition(mech::ManipulatorType::Lever);
  const double limit = upper_assembly_limit_dphi(def.geometry), t_limit = 0.63;
  ASSERT_TRUE(std::isfinite(limit) && limit > 0) << limit;
  def.lever_motion = std::make_shared<mech::ConstantVelocityLaw>(limit / t_limit);
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  for (auto& body : model.bodies)
    if (!body.fixed) body.mass_kg = body.inertia_kgm2 = 0.0;  // from the meshes, not known yet
  const std::string message = error_of(
      [&] { check_motion_before_meshing(model, mech::equally_spaced_times(1.0, 21), {"lever", "arm", "rocker"}); });
  EXPECT_TRUE(contains(message, "mechanism 'lever manipulator'")) << message;
  const double t = first_time_in(message);
  EXPECT_GE(t, 0.60 - 1e-12) << message;
  EXPECT_LE(t, 0.65 + 1e-12) << message;
}

TEST(CheckMotionBeforeMeshing, ValidMotionPassesWithMasslessBodiesFromMeshes) {
  // The same four-bar turned to 90 % of its limit: possible, although every
  // moving body has zero mass until its part is meshed.
  mech::ManipulatorDefinition def = test::lever_chain_definition(mech::ManipulatorType::Lever);
  def.lever_motion = std::make_shared<mech::Polynomial345Law>(0.9 * upper_assembly_limit_dphi(def.geometry), 1.0);
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  for (auto& body : model.bodies)
    if (!body.fixed) body.mass_kg = body.inertia_kgm2 = 0.0;
  EXPECT_NO_THROW(check_motion_before_meshing(model, mech::equally_spaced_times(1.0, 21), {"lever", "arm", "rocker"}));
}

TEST(CheckMotionBeforeMeshing, SlackChainIsLeftToTheRunWithRealMasses) {
  // Lever-chain manipulator with gravity reversed: its chain is slack
  // (tests/data/robustness/39). The check uses nominal masses, so the chain
  // tension is not its business: it passes.
  mech::ManipulatorDefinition def = test::lever_chain_definition();
  def.gravity_m_s2 = {0.0, 9.80665};
  const mech::MultibodyModel model = mech::make_manipulator_model(def);
  EXPECT_NO_THROW(check_motion_before_meshing(model, mech::equally_spaced_times(2.0, 11), {"lever", "arm"}));
  // ... while the kinematic run with the real masses stops on it.
  DynamicsSettings kinematic;
  kinematic.method = DynamicsMethod::Kinematic;
  const std::string message =
      error_of([&] { run_dynamics(mech::MultibodySystem(model), mech::equally_spaced_times(2.0, 11), kinematic); });
  EXPECT_TRUE(contains(message, "chain 'chain'")) << message;
}

TEST(CheckMotionBeforeMeshing, LinkageWithFreeDofIsOnlyAssembledAtTheStart) {
  // A free pendulum of zero mass: its motion needs the masses, so only the
  // assembly at t = 0 is checked (integrating it would fail).
  const mech::MultibodyModel model = pendulum(0.0, 0.3, nullptr);
  EXPECT_NO_THROW(check_motion_before_meshing(model, {0.0, 1.0, 2.0}, {"rod"}));
}

// ---- run_dynamics ------------------------------------------------------------------

TEST(RunDynamics, KinematicMethodOnAOneDofLinkageIsAnErrorNamingTheDof) {
  const mech::MultibodySystem system(pendulum(2.0, 0.3, nullptr));
  DynamicsSettings settings;
  settings.method = DynamicsMethod::Kinematic;
  const std::string message = error_of([&] { run_dynamics(system, {0.0, 0.1}, settings); });
  EXPECT_TRUE(contains(message, "the kinematic method needs a fully driven linkage (0 DoF); this one has 1 DoF"))
      << message;
}

TEST(RunDynamics, CvodesMethodOnAFullyDrivenLinkageIsAnErrorNamingTheDof) {
  const mech::MultibodySystem system(pendulum(2.0, 0.3, std::make_shared<mech::Polynomial345Law>(0.5, 1.0)));
  DynamicsSettings settings;
  settings.method = DynamicsMethod::Cvodes;
  const std::string message = error_of([&] { run_dynamics(system, {0.0, 0.1}, settings); });
  EXPECT_TRUE(contains(message, "the CVODES method needs a linkage with 1 DoF; this one has 0 DoF")) << message;
}

TEST(RunDynamics, CvodesWithoutCoordinateOrForceDriveIsAnError) {
  const mech::MultibodySystem system(pendulum(2.0, 0.3, nullptr));
  DynamicsSettings settings;
  settings.method = DynamicsMethod::Cvodes;
  const std::string message = error_of([&] { run_dynamics(system, {0.0, 0.1}, settings); });
  EXPECT_TRUE(contains(message, "needs an independent coordinate")) << message;
}

TEST(RunDynamics, IdasAndKinematicAgreeOnAFullyDrivenLinkage) {
  // SPEC §1 lever-chain manipulator, 80 deg in 2 s (DoF 0). Reference: the
  // kinematic run (exact positions to the Newton tolerance). Both recompute
  // the multipliers from (q, q') (results.hpp), so reactions, drive torque and
  // chain tension differ only by IDAS's position and velocity error (rtol
  // 1e-10): 1e-6 of the largest load.
  const mech::MultibodySystem system(mech::make_manipulator_model(test::lever_chain_definition()));
  const std::vector<double> times = mech::equally_spaced_times(2.0, 21);
  DynamicsSettings idas, kinematic;
  kinematic.method = DynamicsMethod::Kinematic;
  const mech::Results a = run_dynamics(system, times, idas);
  const mech::Results b = run_dynamics(system, times, kinematic);
  ASSERT_EQ(a.frames.size(), times.size());
  ASSERT_EQ(b.frames.size(), times.size());
  double scale = 0.0;
  for (const auto& f : b.frames) {
    for (const auto& j : f.joints) scale = std::max(scale, j.on_j.force_world.norm());
    scale = std::max(scale, std::abs(f.chains[0].tension_N));
  }
  ASSERT_GT(scale, 100.0);  // a loaded mechanism (35 kg payload)
  for (std::size_t k = 0; k < times.size(); ++k) {
    for (std::size_t j = 0; j < b.frames[k].joints.size(); ++j) {
      EXPECT_NEAR((a.frames[k].joints[j].on_j.force_world - b.frames[k].joints[j].on_j.force_world).norm(), 0.0,
                  1e-6 * scale)
          << "joint " << b.frames[k].joints[j].name << " at t = " << times[k];
    }
    EXPECT_NEAR(a.frames[k].chains[0].tension_N, b.frames[k].chains[0].tension_N, 1e-6 * scale) << times[k];
    // Torque: the largest load times a lever arm of at most a = 0.5 m.
    EXPECT_NEAR(a.frames[k].drives[0].effort, b.frames[k].drives[0].effort, 1e-6 * scale * 0.5) << times[k];
  }
}

// ---- solve_static_pose ---------------------------------------------------------------

TEST(SolveStaticPose, PendulumDriveTorqueIsTheWeightsMoment) {
  // The drive law starts at 0.2 rad (law(0) = 0.2, so s_0 = -0.2 from the
  // initial pose 0): a target law value theta + 0.2 holds the rod at theta.
  // Reference (analytic statics): the drive's torque on the rod balances the
  // weight's moment about the pivot, effort = m g l cos(theta); 1e-9 relative
  // (the kinematic solve is exact to the Newton tolerance 1e-13 of l).
  const double m = 2.0, l = 0.4, g = units::kStandardGravity;
  const mech::MultibodyModel model = pendulum(m, l, std::make_shared<mech::ConstantVelocityLaw>(1.0, 0.2));
  for (const double theta : {0.5, 2.0, -1.2}) {
    const mech::Frame f = solve_static_pose(model, {theta + 0.2});
    EXPECT_NEAR(f.bodies[1].q.z(), theta, 1e-12) << theta;
    const double expected = m * g * l * std::cos(theta);
    EXPECT_NEAR(f.drives[0].effort, expected, 1e-9 * m * g * l) << theta;
    // At rest: the 3-4-5 ramp ends with zero speed and acceleration, so the
    // velocities and accelerations solved from it are zero to round-off
    // (measured 7e-18; 1e-12 rad/s, m/s).
    EXPECT_LT(std::abs(f.drives[0].s_dot), 1e-12) << theta;
    EXPECT_LT(f.bodies[1].q_dot.norm(), 1e-12) << theta;
    EXPECT_LT(f.bodies[1].q_ddot.norm(), 1e-12) << theta;
  }
}

TEST(SolveStaticPose, LeverChainTorqueAtRestIsTheVirtualWorkOfGravity) {
  // SPEC §1 lever-chain manipulator held at dphi = 20 deg. Reference: virtual
  // work with the closed-form position function (mechanisms/lever_chain.hpp,
  // independent of the multibody model): effort = dV/d(dphi),
  //   V = g (m_lever y_lever_com + m_arm y_arm_com + m_payload y_H).
  // 1e-9 relative: both sides exact to round-off and Newton tolerance.
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  const mech::MultibodyModel model = mech::make_manipulator_model(def);
  const double dphi = 20 * kDeg, g = -def.gravity_m_s2.y();
  const mech::Frame f = solve_static_pose(model, {dphi});
  const mech::LeverChainPose pose = mech::LeverChain(def.geometry).pose(dphi);
  const auto turned = [](double angle, const Eigen::Vector2d& v) {
    return Eigen::Rotation2Dd(angle + std::numbers::pi / 2) * v;  // d/dangle of R(angle) v
  };
  const double dy_lever = turned(dphi, def.lever.com_body).y();
  const double dy_arm = pose.a.d1.y() + pose.theta_d1 * turned(pose.theta_rad, def.arm.com_body).y();
  const double payload = def.gripper_mass_kg + def.casting_mass_kg;
  const double expected = g * (def.lever.mass_kg * dy_lever + def.arm.mass_kg * dy_arm + payload * pose.h.d1.y());
  EXPECT_NEAR(f.bodies[2].q.z(), pose.theta_rad, 1e-12);
  ASSERT_GT(std::abs(expected), 10.0);
  EXPECT_NEAR(f.drives[0].effort, expected, 1e-9 * std::abs(expected));
  EXPECT_GT(f.chains[0].tension_N, 0.0);
}

TEST(SolveStaticPose, SlackChainAtRestIsAnError) {
  // Gravity reversed: the payload lifts the arm and the chain would have to
  // push (tests/data/robustness/39).
  mech::ManipulatorDefinition def = test::lever_chain_definition();
  def.gravity_m_s2 = {0.0, 9.80665};
  const std::string message = error_of([&] { solve_static_pose(mech::make_manipulator_model(def), {0.0}); });
  EXPECT_TRUE(contains(message, "chain 'chain' is slack at rest in this pose (tension -")) << message;
}

TEST(SolveStaticPose, NeedsOneTargetPerMotionDrive) {
  const mech::MultibodyModel model = pendulum(2.0, 0.4, std::make_shared<mech::Polynomial345Law>(0.5, 1.0));
  const std::string message = error_of([&] { solve_static_pose(model, {0.1, 0.2}); });
  EXPECT_TRUE(contains(message, "static pose: 2 target values for 1 motion drives")) << message;
}

TEST(SolveStaticPose, NeedsAFullyDrivenLinkage) {
  const std::string message = error_of([&] { solve_static_pose(pendulum(2.0, 0.4, nullptr), {}); });
  EXPECT_TRUE(contains(message, "the static pose study needs a fully driven linkage")) << message;
}

// A motion whose own checks fail is not used: the limits of motion_stages.hpp
// on the drift and the energy balance, a NaN as a failure, values at the
// limit accepted.
TEST(RequireAccurateMotion, DriftOrEnergyBalanceAboveTheirLimitsOrNotFiniteAreErrors) {
  mech::Results results;
  results.summary.method = "IDAS GGL index-2";
  mech::DynamicsOptions options;
  options.relative_tolerance = 1e-3;
  options.absolute_tolerance = 1e-4;
  results.summary.max_drift_relative = kMaxRelativeConstraintDrift;
  results.summary.energy_balance_error = kMaxEnergyBalanceError;
  EXPECT_EQ(error_of([&] { require_accurate_motion(results, options); }), "(no error)");

  results.summary.energy_balance_error = 0.5;
  const std::string energy = error_of([&] { require_accurate_motion(results, options); });
  EXPECT_NE(energy.find("energy balance |dT + dV - W| is off by 0.5 of the energy scale, more than the 0.01 "
                        "accepted, at relative tolerance 0.001 and absolute tolerance 0.0001"),
            std::string::npos)
      << energy;

  results.summary.energy_balance_error = std::nan("");
  EXPECT_NE(error_of([&] { require_accurate_motion(results, options); }).find("energy balance"), std::string::npos);

  results.summary.energy_balance_error = 0.0;
  results.summary.max_drift_relative = 2e-4;
  const std::string drift = error_of([&] { require_accurate_motion(results, options); });
  EXPECT_NE(drift.find("joints drift apart by 0.0002 of the characteristic length"), std::string::npos) << drift;
}

}  // namespace
}  // namespace kinetofem::pipeline
