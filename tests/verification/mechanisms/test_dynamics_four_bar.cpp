// Lever manipulator (SPEC §2: the hinged four-bar A0-A-B-B0 equivalent to the
// lever-chain example) built from revolute joints of the multibody core.
// References: coupler point B from the intersection of the circles about A
// (radius r) and B0 (radius b0), an independent closed form; the assembly limit
// of the non-Grashof linkage reported with its time; IDAS and CVODES paths of a
// free motion under gravity agree to 1e-6.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/multibody/dynamics.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/verification/spec1_lever_chain.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// SPEC §1 example (kinetofem/verification/spec1_lever_chain.hpp): a = 0.5,
// c = 0.35, r = 0.075 m, b0 = a c / (c + r).
const LeverChainGeometry kExample = verification::spec1::example_geometry();
const double kA = kExample.a_m, kR = kExample.r_m, kC = kExample.c_m, kB0 = kExample.b0_m;

MultibodyModel four_bar(std::shared_ptr<const MotionLaw> law, Eigen::Vector2d gravity, double lever_speed = 0.0) {
  MultibodyModel m;
  m.name = "lever manipulator";
  m.characteristic_length_m = kA;
  m.gravity = gravity;
  Body frame;
  frame.name = "frame";
  frame.fixed = true;
  frame.points["B0"] = {kR, kA - kB0};
  Body lever;
  lever.name = "lever";
  lever.mass_kg = 8.0;
  lever.inertia_kgm2 = 8.0 * kA * kA / 12.0;
  lever.com_body = {0.0, 0.5 * kA};
  lever.points["A"] = {0.0, kA};
  lever.velocity = {0.0, 0.0, lever_speed};
  Body coupler;  // origin at A, x along A->B; carries C and H
  coupler.name = "coupler";
  coupler.mass_kg = 5.0;
  coupler.inertia_kgm2 = 5.0 * kC * kC / 12.0;
  coupler.com_body = {-0.5 * kC, 0.0};
  coupler.points["B"] = {kR, 0.0};
  coupler.points["H"] = {-kC, 0.1};
  coupler.pose = {0.0, kA, 0.0};
  Body rocker;  // origin at B0, x along B0->B (pointing +Y in the design position)
  rocker.name = "rocker";
  rocker.mass_kg = 2.0;
  rocker.inertia_kgm2 = 2.0 * kB0 * kB0 / 12.0;
  rocker.com_body = {0.5 * kB0, 0.0};
  rocker.points["B"] = {kB0, 0.0};
  rocker.pose = {kR, kA - kB0, 0.5 * std::numbers::pi};
  m.bodies = {frame, lever, coupler, rocker};
  m.joints.push_back(make_revolute("A0", "frame", "origin", "lever", "origin"));
  m.joints.push_back(make_revolute("A", "lever", "A", "coupler", "origin"));
  m.joints.push_back(make_revolute("B", "coupler", "B", "rocker", "B"));
  m.joints.push_back(make_revolute("B0", "frame", "B0", "rocker", "origin"));
  if (law) {
    MotionDrive drive;
    drive.name = "lever drive";
    drive.coordinate = {CoordinateType::Angle, "frame", "origin", "lever", "origin", {1, 0}};
    drive.law = std::move(law);
    m.motion_drives.push_back(drive);
  }
  return m;
}

// Independent closed form: B on the circles |B - A| = r and |B - B0| = b0, on
// the branch through the design position B = (r, a).
Eigen::Vector2d point_b(double dphi) {
  const Eigen::Vector2d a(-kA * std::sin(dphi), kA * std::cos(dphi)), b0(kR, kA - kB0);
  const Eigen::Vector2d d = b0 - a;
  const double dist = d.norm();
  const double along = (kR * kR - kB0 * kB0 + dist * dist) / (2.0 * dist);
  const double height = std::sqrt(kR * kR - along * along);
  return a + along * d / dist + height * Eigen::Vector2d(-d.y(), d.x()) / dist;
}

std::vector<double> sample_times(double duration, int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(duration * k / n);
  return t;
}

TEST(DynamicsFourBar, CouplerMatchesCircleIntersection) {
  double worst = 0.0;
  for (double stroke_deg : {25.0, -25.0}) {
    const MultibodySystem sys(four_bar(std::make_shared<CycloidalLaw>(stroke_deg * kDeg, 1.0), {0, -9.81}));
    const Results res = run_kinematics(sys, sample_times(1.0, 40));
    for (const Frame& f : res.frames) {
      const Eigen::Vector3d c = f.bodies[2].q;
      const Eigen::Vector2d b = c.head<2>() + kR * Eigen::Vector2d(std::cos(c.z()), std::sin(c.z()));
      worst = std::max(worst, (b - point_b(f.bodies[1].q.z())).norm());
    }
    EXPECT_LT(res.summary.max_equilibrium_residual, 1e-9);
  }
  std::printf("four-bar B vs circle intersection: %.2e m\n", worst);
  // Reference: closed form above; assembly tolerance 1e-13 L -> 1e-9 m is generous.
  EXPECT_LT(worst, 1e-9);
}

TEST(DynamicsFourBar, NonGrashofLimitStopsTheRunWithTime) {
  // SPEC §2: 500 + 75 > 411.8 + 115.8, no link turns fully; a lever stroke of
  // 170 deg passes the limit of assembly.
  const MultibodySystem sys(four_bar(std::make_shared<CycloidalLaw>(170.0 * kDeg, 1.0), {0, -9.81}));
  try {
    run_kinematics(sys, sample_times(1.0, 200));
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("four-bar limit: %s\n", what.c_str());
    EXPECT_TRUE(what.find("singular position at t = ") != std::string::npos ||
                what.find("cannot be assembled at t = ") != std::string::npos)
        << what;
  }
}

TEST(DynamicsFourBar, LimitPassedBetweenTwoOutputTimesIsFound) {
  // The lever goes out 40 deg (past the limit of assembly at 36.4 deg) and back
  // between the only two output times, both at 0 deg: the poses at the output
  // times assemble, the motion between them does not exist.
  const auto out_and_back =
      std::make_shared<TabulatedLaw>(std::vector<double>{0.0, 1.0, 2.0}, std::vector<double>{0.0, 40.0 * kDeg, 0.0});
  const MultibodySystem sys(four_bar(out_and_back, {0, -9.81}));
  try {
    run_kinematics(sys, {0.0, 2.0});
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    std::printf("four-bar limit between two output times: %s\n", what.c_str());
    EXPECT_TRUE(what.find("singular position at t = 0.") != std::string::npos ||
                what.find("cannot be followed from t = 0 s to t = 2 s") != std::string::npos)
        << what;
  }
}

TEST(DynamicsFourBar, FreeMotionIdasAndCvodesAgree) {
  // Gravity along +Y: the linkage hangs from A0 and B0 and swings from the design
  // position with an initial lever speed.
  const MultibodySystem sys(four_bar(nullptr, {0.0, 9.81}, 1.5));
  const std::vector<double> times = sample_times(0.6, 30);
  const Results ggl = simulate_ggl(sys, times);
  const Results minimal =
      simulate_minimal(sys, {CoordinateType::Angle, "frame", "origin", "lever", "origin", {1, 0}}, times);
  double err = 0.0, scale = 0.0, err_force = 0.0, force_scale = 0.0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    for (int b = 1; b < 4; ++b) {
      scale = std::max(scale, std::abs(ggl.frames[k].bodies[b].q.z() - ggl.frames[0].bodies[b].q.z()));
      err = std::max(err, std::abs(ggl.frames[k].bodies[b].q.z() - minimal.frames[k].bodies[b].q.z()));
    }
    for (std::size_t j = 0; j < 4; ++j) {
      force_scale = std::max(force_scale, ggl.frames[k].joints[j].on_i.force_world.norm());
      err_force = std::max(err_force, (ggl.frames[k].joints[j].on_i.force_world -
                                       minimal.frames[k].joints[j].on_i.force_world).norm());
    }
  }
  std::printf("four-bar free motion IDAS vs CVODES: angles %.2e rel (swing %.3f rad), reactions %.2e rel\n%s%s",
              err / scale, scale, err_force / force_scale, ggl.format_checks().c_str(), minimal.format_checks().c_str());
  EXPECT_GT(scale, 0.1);
  EXPECT_LT(err / scale, 1e-6);          // paths agree to 1e-6 of the length scale
  EXPECT_LT(err_force / force_scale, 1e-6);
  EXPECT_LT(ggl.summary.max_drift_relative, 1e-8);
  EXPECT_LT(ggl.summary.energy_balance_error, 1e-8);  // conservative run
  EXPECT_LT(minimal.summary.energy_balance_error, 1e-8);
}

TEST(DynamicsFourBar, CrankRockerKeepsItsBranchWithFewOutputTimes) {
  // A Grashof crank-rocker (ground d = 0.4, crank r = 0.1, coupler c = 0.35,
  // rocker b = 0.3 m; r + d < c + b) whose crank turns once in 1 s, from rest
  // by a 3-4-5 law and at constant speed, with 3, 5, 11 and 21 output times. Reference: B on the circles |B - A| = c and |B - O4| = b on the
  // open branch (left of A -> O4) the run starts on; the crossed branch is the
  // mirror image of B in the line A O4.
  const double d = 0.4, r = 0.1, c = 0.35, b = 0.3, phi0 = 30.0 * kDeg;
  const Eigen::Vector2d o4(d, 0.0);
  const auto point_b_open = [&](double phi) {
    const Eigen::Vector2d a(r * std::cos(phi), r * std::sin(phi));
    const Eigen::Vector2d u = (o4 - a).normalized();
    const double dist = (o4 - a).norm(), along = (c * c - b * b + dist * dist) / (2.0 * dist);
    return Eigen::Vector2d(a + along * u + std::sqrt(c * c - along * along) * Eigen::Vector2d(-u.y(), u.x()));
  };
  MultibodyModel m;
  m.name = "crank-rocker";
  m.characteristic_length_m = d;
  m.gravity = {0.0, -9.81};
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["O4"] = o4;
  Body crank;
  crank.name = "crank";
  crank.mass_kg = 1.0;
  crank.inertia_kgm2 = 1e-3;
  crank.com_body = {0.5 * r, 0.0};
  crank.points["A"] = {r, 0.0};
  crank.pose = {0.0, 0.0, phi0};
  const Eigen::Vector2d a0(r * std::cos(phi0), r * std::sin(phi0)), b0 = point_b_open(phi0);
  Body coupler;  // origin at A, x along A -> B
  coupler.name = "coupler";
  coupler.mass_kg = 2.0;
  coupler.inertia_kgm2 = 2e-2;
  coupler.com_body = {0.5 * c, 0.0};
  coupler.points["B"] = {c, 0.0};
  coupler.pose = {a0.x(), a0.y(), std::atan2(b0.y() - a0.y(), b0.x() - a0.x())};
  Body rocker;  // origin at O4, x along O4 -> B
  rocker.name = "rocker";
  rocker.mass_kg = 1.5;
  rocker.inertia_kgm2 = 1e-2;
  rocker.com_body = {0.5 * b, 0.0};
  rocker.points["B"] = {b, 0.0};
  rocker.pose = {d, 0.0, std::atan2(b0.y(), b0.x() - d)};
  m.bodies = {ground, crank, coupler, rocker};
  m.joints.push_back(make_revolute("O2", "ground", "origin", "crank", "origin"));
  m.joints.push_back(make_revolute("A", "crank", "A", "coupler", "origin"));
  m.joints.push_back(make_revolute("B", "coupler", "B", "rocker", "B"));
  m.joints.push_back(make_revolute("O4", "ground", "O4", "rocker", "origin"));
  MotionDrive drive;
  drive.name = "crank drive";
  drive.coordinate = {CoordinateType::Angle, "ground", "origin", "crank", "origin", {1, 0}};
  m.motion_drives.push_back(drive);
  const double turn = 2.0 * std::numbers::pi;
  for (const std::shared_ptr<const MotionLaw>& law :
       {std::shared_ptr<const MotionLaw>(std::make_shared<Polynomial345Law>(turn, 1.0)),
        std::shared_ptr<const MotionLaw>(std::make_shared<ConstantVelocityLaw>(turn))}) {
    m.motion_drives.front().law = law;
    const MultibodySystem sys(m);
    for (int n : {3, 5, 11, 21}) {
      const Results res = run_kinematics(sys, sample_times(1.0, n - 1));
      double worst = 0.0;
      for (const Frame& f : res.frames) {
        const Eigen::Vector3d rocker_pose = f.bodies[3].q;
        const Eigen::Vector2d bp = o4 + b * Eigen::Vector2d(std::cos(rocker_pose.z()), std::sin(rocker_pose.z()));
        worst = std::max(worst, (bp - point_b_open(f.bodies[1].q.z())).norm());
      }
      std::printf("crank-rocker, %s, %d output times: B vs open-branch closed form %.2e m\n",
                  law->describe().c_str(), n, worst);
      EXPECT_LT(worst, 1e-9) << law->describe() << ", " << n << " output times";
    }
  }
}

}  // namespace
}  // namespace kinetofem::mech
