// SPEC §5 spherical 3-DoF manipulator: trapezoidal motion timing, static drive
// loads by hand, the energy balance of the kinetostatic drive efforts, the
// CVODES forward-dynamics cross-check, and a vertical-plane motion compared
// with the planar multibody core (an independent formulation: absolute
// coordinates, Lagrange multipliers).
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <string>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/spherical_manipulator.hpp"
#include "kinetofem/verification/spec5_spherical.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

TEST(Spec5Spherical, TrapezoidalTimingOfTheStraightLine) {
  const SphericalVariant& v = spherical_variant('B');
  const Eigen::Vector3d a(1.6, -0.9, 0.5), b(1.3, 1.2, 0.9);
  const StraightLineMotion motion(a, b, v.speed_mps, v.k_accel, v.k_decel);
  // SPEC §5: T_c = l_ab / (V (1 - 0.5 kP - 0.5 kT)), tP = kP T_c, tT = kT T_c.
  const double l_ab = (b - a).norm(), tc = l_ab / (v.speed_mps * (1 - 0.5 * v.k_accel - 0.5 * v.k_decel));
  EXPECT_NEAR(motion.duration(), tc, 1e-14);
  EXPECT_NEAR(motion.breakpoints()[1], v.k_accel * tc, 1e-13);
  EXPECT_NEAR(motion.breakpoints()[2], tc - v.k_decel * tc, 1e-13);
  EXPECT_LT((motion.at(tc).m - b).norm(), 1e-14);
  EXPECT_NEAR(motion.at(0.5 * tc).m_dot.norm(), v.speed_mps, 1e-14);
  // M stays on the segment.
  const Eigen::Vector3d mid = motion.at(0.37 * tc).m;
  EXPECT_LT(((mid - a).cross(b - a)).norm() / l_ab, 1e-15);
}

TEST(Spec5Spherical, StaticDriveLoadsByHand) {
  const double payload = 15.0, g = 9.80665;
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), payload);
  SphericalJointMotion rest;
  rest.q = Eigen::Vector3d(20 * kDeg, 12 * kDeg, 1.8);
  const SphericalDynamics s = spherical_inverse_dynamics(d, rest);
  const double m3 = d.variant.m3_kg, d3 = 1.8 - 0.5 * d.arm_length_m;
  // Hand statics: the slide holds the arm + payload weight along the arm,
  // F32d = (m3 + mp) g sin(phi21); the tilt drive holds their moment about B,
  // M21d = g cos(phi21) (m3 d3 + mp l); the base drive carries no torque; the
  // base pair carries the whole weight.
  EXPECT_NEAR(s.pair32.drive, (m3 + payload) * g * std::sin(12 * kDeg), 1e-10);
  EXPECT_NEAR(s.pair21.drive, g * std::cos(12 * kDeg) * (m3 * d3 + payload * 1.8), 1e-10);
  EXPECT_NEAR(s.pair10.drive, 0.0, 1e-10);
  const double weight = (d.variant.m1_kg + d.variant.m2_kg + m3 + payload) * g;
  EXPECT_NEAR(s.pair10.force_world.z(), weight, 1e-9);
  EXPECT_NEAR(s.total_power_W, 0.0, 0.0);
}

TEST(Spec5Spherical, DriveWorkEqualsPotentialEnergyChange) {
  // Rest to rest, 20 kg, (1.4, -0.7, 0.5) -> (1.2, 0.8, 0.9) m (inside the
  // zones of A, C and E): the drives' work (Simpson) is the potential energy
  // gained by the arm and the payload. The computation is that of `kinetofem
  // verify` spec5.drive_work (kinetofem/verification/spec5_spherical.hpp).
  for (char name : {'A', 'C', 'E'}) {
    const verification::spec5::WorkEnergyBalance b = verification::spec5::work_energy_balance(name);
    const SphericalRun& run = b.run;
    std::printf("SPEC5 %c: T = %.4f s, drive work %.6f J, dV %.6f J, peaks M10d %.2f N m, M21d %.2f N m, F32d %.2f N, "
                "power %.1f / %.1f / %.1f W\n",
                name, b.duration_s, b.work_J, b.potential_gain_J, run.peak_drive(0), run.peak_drive(1),
                run.peak_drive(2), run.peak_power_W(0), run.peak_power_W(1), run.peak_power_W(2));
    // Reference: work-energy theorem; Simpson error ~1e-10 of the scale -> 1e-8.
    EXPECT_NEAR(b.work_J, b.potential_gain_J, verification::spec5::kWorkEnergyTolerance * b.scale_J);
  }
}

TEST(Spec5Spherical, ForwardDynamicsReproducesThePlannedPath) {
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('D'), 12.0);
  const Eigen::Vector3d a(1.7, -0.8, 0.4), b(1.2, 0.9, 0.85);
  const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
  std::vector<double> times;
  for (int k = 0; k <= 20; ++k) times.push_back(motion.duration() * k / 20.0);
  const SphericalForwardResult fwd = spherical_forward_dynamics(d, motion, times);
  std::printf("SPEC5 D forward dynamics (CVODES): max |M - M_planned| = %.3e m over l_ab = %.3f m, %ld steps\n",
              fwd.max_path_deviation_m, motion.length(), fwd.steps);
  // The inverse dynamics' efforts, fed back, must reproduce the motion:
  // integrator tolerance 1e-10 -> deviation 1e-6 of the segment length allowed.
  EXPECT_LT(fwd.max_path_deviation_m, 1e-6 * motion.length());
  EXPECT_LT((spherical_forward_kinematics(d, fwd.joints.back().q) - b).norm(), 1e-6 * motion.length());
}

// Joint coordinate k of the spherical manipulator along a straight-line motion
// as a MotionLaw (relative to its initial value), for the planar multibody model.
class JointLaw final : public MotionLaw {
 public:
  JointLaw(const SphericalDesign& d, const StraightLineMotion& m, int k) : d_(d), m_(m), k_(k) {}
  MotionState at(double t) const override {
    const StraightLineMotion::Point p = m_.at(t), p0 = m_.at(0.0);
    const SphericalJointMotion j = spherical_joint_motion(d_, p.m, p.m_dot, p.m_ddot);
    const double q0 = spherical_inverse_kinematics(d_, p0.m)(k_);
    return {j.q(k_) - q0, j.qd(k_), j.qdd(k_)};
  }
  double stroke() const override { return at(duration()).s; }
  double duration() const override { return m_.duration(); }
  std::string describe() const override { return "spherical joint law"; }

 private:
  const SphericalDesign& d_;
  const StraightLineMotion& m_;
  int k_;
};

TEST(Spec5Spherical, VerticalPlaneMotionMatchesPlanarMultibodyCore) {
  const double payload = 10.0;
  const SphericalDesign d = size_spherical_manipulator(spherical_variant('A'), payload);
  const Eigen::Vector3d a(1.3, 0.0, 0.5), b(2.0, 0.0, 0.95);  // phi10 = 0 throughout
  const StraightLineMotion motion(a, b, d.variant.speed_mps, d.variant.k_accel, d.variant.k_decel);
  const Eigen::Vector3d q0 = spherical_inverse_kinematics(d, a);
  const double zb = d.variant.height_b_m, half = 0.5 * d.arm_length_m;
  // Planar model in the vertical plane (X radial, Y up): sleeve pinned at B,
  // arm sliding in it, payload at M; both joint coordinates prescribed.
  MultibodyModel m;
  m.name = "spherical manipulator, vertical plane";
  m.gravity = {0.0, -d.gravity_mps2};
  m.characteristic_length_m = d.arm_length_m;
  Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["B"] = {0.0, zb};
  Body sleeve;
  sleeve.name = "sleeve";
  sleeve.mass_kg = d.variant.m2_kg;
  sleeve.inertia_kgm2 = d.sleeve_inertia_transverse;
  sleeve.pose = {0.0, zb, q0(1)};
  Body arm;  // frame origin at its centre of mass, x towards M
  arm.name = "arm";
  arm.mass_kg = d.variant.m3_kg;
  arm.inertia_kgm2 = d.arm_inertia_transverse;
  arm.points["M"] = {half, 0.0};
  arm.point_masses.push_back({"payload", payload, {half, 0.0}});
  const double d3 = q0(2) - half;
  arm.pose = {d3 * std::cos(q0(1)), zb + d3 * std::sin(q0(1)), q0(1)};
  m.bodies = {ground, sleeve, arm};
  m.joints.push_back(make_revolute("B", "ground", "B", "sleeve", "origin"));
  m.joints.push_back(make_prismatic("slide", "sleeve", "origin", "arm", "origin", {1, 0}));
  MotionDrive tilt;
  tilt.name = "M21";
  tilt.coordinate = {CoordinateType::Angle, "ground", "origin", "sleeve", "origin", {1, 0}};
  tilt.law = std::make_shared<JointLaw>(d, motion, 1);
  MotionDrive slide;
  slide.name = "F32";
  slide.coordinate = {CoordinateType::Displacement, "sleeve", "origin", "arm", "M", {1, 0}};
  slide.law = std::make_shared<JointLaw>(d, motion, 2);
  m.motion_drives = {tilt, slide};
  const MultibodySystem sys(m);
  std::vector<double> times;
  for (int k = 0; k <= 40; ++k) times.push_back(motion.duration() * k / 40.0);
  const Results planar = run_kinematics(sys, times);
  double err_torque = 0, err_force = 0, scale_torque = 0, scale_force = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const StraightLineMotion::Point p = motion.at(times[k]);
    const SphericalDynamics s = spherical_inverse_dynamics(d, spherical_joint_motion(d, p.m, p.m_dot, p.m_ddot));
    scale_torque = std::max(scale_torque, std::abs(s.pair21.drive));
    scale_force = std::max(scale_force, std::abs(s.pair32.drive));
    err_torque = std::max(err_torque, std::abs(planar.frames[k].drives[0].effort - s.pair21.drive));
    err_force = std::max(err_force, std::abs(planar.frames[k].drives[1].effort - s.pair32.drive));
    EXPECT_NEAR(s.pair10.drive, 0.0, 1e-9 * scale_torque);
  }
  std::printf("SPEC5 vertical plane: kinetostatics vs planar multibody: M21d %.2e rel, F32d %.2e rel\n",
              err_torque / scale_torque, err_force / scale_force);
  // Both are exact kinetostatics of the same motion: agreement to round-off (1e-9).
  EXPECT_LT(err_torque / scale_torque, 1e-9);
  EXPECT_LT(err_force / scale_force, 1e-9);
}

}  // namespace
}  // namespace kinetofem::mech
