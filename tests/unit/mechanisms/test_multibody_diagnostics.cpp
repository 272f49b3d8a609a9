// Diagnoses of the multibody core when a run cannot go on: a SUNDIALS failure
// is named by its flag's name and plain meaning (never a bare number) with the
// time; a singular acceleration system names its real cause, and a body far
// heavier than the others (1e300 kg) is no cause at all; a prescribed motion
// too large to follow in substeps is an error.
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/sundials_check.hpp"

namespace kinetofem::mech {
namespace {

// A bar hinged at the ground origin, its centre of mass at (0.5, 0) in its frame.
MultibodyModel pendulum(double mass_kg, double inertia_kgm2) {
  MultibodyModel m;
  m.name = "pendulum";
  m.characteristic_length_m = 1.0;
  m.gravity = {0.0, -9.81};
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  Body bar;
  bar.name = "bar";
  bar.mass_kg = mass_kg;
  bar.inertia_kgm2 = inertia_kgm2;
  bar.com_body = {0.5, 0.0};
  bar.pose = {0.0, 0.0, -0.25 * std::numbers::pi};
  m.bodies = {ground, bar};
  m.joints.push_back(make_revolute("hinge", "ground", "origin", "bar", "origin"));
  return m;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(MultibodyDiagnostics, SundialsFlagIsNamedAndExplained) {
  const std::string what = message_of([] { sundials_check(-4, "IDASolve", "t = 0.25 s"); });
  EXPECT_NE(what.find("IDA_CONV_FAIL"), std::string::npos) << what;
  EXPECT_NE(what.find("did not converge"), std::string::npos) << what;
  EXPECT_NE(what.find("t = 0.25 s"), std::string::npos) << what;
  EXPECT_EQ(what.find("flag -4"), std::string::npos) << what;
  const std::string cv = message_of([] { sundials_check(-1, "CVode", "t = 2 s"); });
  EXPECT_NE(cv.find("CV_TOO_MUCH_WORK"), std::string::npos) << cv;
  EXPECT_NE(cv.find("t = 2 s"), std::string::npos) << cv;
  // A flag the table does not explain still has its name.
  const std::string other = message_of([] { sundials_check(-22, "IDASetMaxStep"); });
  EXPECT_NE(other.find("IDA_ILL_INPUT"), std::string::npos) << other;
}

TEST(MultibodyDiagnostics, IntegratorOutOfStepsSaysWhatToChange) {
  const MultibodySystem sys(pendulum(2.0, 2.0 / 12.0));
  DynamicsOptions options;
  options.max_steps = 3;
  const std::string what = message_of([&] { simulate_ggl(sys, {0.0, 1.0}, options); });
  std::printf("%s\n", what.c_str());
  EXPECT_NE(what.find("IDA_TOO_MUCH_WORK"), std::string::npos) << what;
  EXPECT_NE(what.find("t = "), std::string::npos) << what;
  EXPECT_NE(what.find("tolerance"), std::string::npos) << what;
  EXPECT_EQ(what.find("flag -1"), std::string::npos) << what;
}

TEST(MultibodyDiagnostics, HeavyBodyIsNotMassless) {
  // Accelerations do not depend on a common scale of the masses: 1e300 kg and
  // 1 kg give the same pendulum motion.
  const MultibodySystem light(pendulum(1.0, 1.0 / 12.0));
  const MultibodySystem heavy(pendulum(1e300, 1e300 / 12.0));
  const Eigen::VectorXd q = assemble(light, light.initial_coordinates(), 0.0);
  const Eigen::VectorXd qd = Eigen::VectorXd::Zero(q.size());
  const Accelerations a_light = solve_accelerations(light, q, qd, 0.0);
  Accelerations a_heavy;
  ASSERT_NO_THROW(a_heavy = solve_accelerations(heavy, q, qd, 0.0));
  ASSERT_TRUE(a_heavy.q_ddot.allFinite());
  EXPECT_LT((a_heavy.q_ddot - a_light.q_ddot).norm(), 1e-12 * a_light.q_ddot.norm());
}

TEST(MultibodyDiagnostics, MasslessBodyIsNamed) {
  // A bar with no mass and no inertia on a hinge: its acceleration is undetermined.
  const MultibodySystem sys(pendulum(0.0, 0.0));
  const Eigen::VectorXd q = assemble(sys, sys.initial_coordinates(), 0.0);
  const std::string what =
      message_of([&] { solve_accelerations(sys, q, Eigen::VectorXd::Zero(q.size()), 0.5); });
  EXPECT_NE(what.find("t = 0.5 s"), std::string::npos) << what;
  EXPECT_NE(what.find("'bar'"), std::string::npos) << what;
  EXPECT_NE(what.find("no mass"), std::string::npos) << what;
}

TEST(MultibodyDiagnostics, RedundantConstraintIsNotCalledMassless) {
  // The same hinge twice: the constraint Jacobian loses rank, every body has mass.
  MultibodyModel m = pendulum(2.0, 2.0 / 12.0);
  m.joints.push_back(make_revolute("hinge twice", "ground", "origin", "bar", "origin"));
  const MultibodySystem sys(m);
  const Eigen::VectorXd q = assemble(sys, sys.initial_coordinates(), 0.0);
  const std::string what = message_of([&] { solve_accelerations(sys, q, Eigen::VectorXd::Zero(q.size()), 0.0); });
  EXPECT_NE(what.find("redundant"), std::string::npos) << what;
  EXPECT_EQ(what.find("massless"), std::string::npos) << what;
  EXPECT_EQ(what.find("no mass"), std::string::npos) << what;
}

TEST(MultibodyDiagnostics, MotionTooLargeToFollowIsAnErrorNotAnEndlessRun) {
  // The pendulum turned 100 times in 1 s with two output times: followed in
  // substeps of at most 0.1 rad, some 12 600 of them.
  MultibodyModel m = pendulum(2.0, 2.0 / 12.0);
  MotionDrive spin;
  spin.name = "spin";
  spin.coordinate = {CoordinateType::Angle, "ground", "origin", "bar", "origin", {1, 0}};
  spin.law = std::make_shared<ConstantVelocityLaw>(200.0 * std::numbers::pi);
  m.motion_drives.push_back(spin);
  const MultibodySystem sys(m);
  const Results res = run_kinematics(sys, {0.0, 1.0});
  EXPECT_NEAR(res.frames.back().bodies[1].q.z(), -0.25 * std::numbers::pi + 200.0 * std::numbers::pi, 1e-9);
  KinematicOptions budget;
  budget.max_substeps = 1000;
  const std::string what = message_of([&] { run_kinematics(sys, {0.0, 1.0}, budget); });
  EXPECT_NE(what.find("the motion is too large to follow: more than 1002 substeps"), std::string::npos) << what;
}

}  // namespace
}  // namespace kinetofem::mech
