#include "kinetofem/verification/spec4_belt_arm.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "kinetofem/mechanisms/motion_law_factory.hpp"
#include "kinetofem/mechanisms/q_manipulator.hpp"

namespace kinetofem::verification::spec4 {

namespace {

constexpr double kM1 = 2.0, kM2 = 1.5, kPayload = 3.0;  // kg
const Eigen::Vector2d kCom2{0.1, 0.012};                 // link 2's bare centre of mass, m (off its axis on purpose)
const double kJ1 = kM1 * kBeltArmL1 * kBeltArmL1 / 12.0, kJ2 = kM2 * kBeltArmL2 * kBeltArmL2 / 12.0;  // kg m^2
const Eigen::Vector2d kGravity{0.0, -9.80665};

Eigen::Vector2d e(double angle) { return {std::cos(angle), std::sin(angle)}; }
Eigen::Vector2d perp(const Eigen::Vector2d& v) { return {-v.y(), v.x()}; }
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

}  // namespace

std::shared_ptr<const mech::MotionLaw> belt_arm_lever_law() {
  mech::MotionLawSpec spec;
  spec.law = "polynomial345";
  spec.stroke = 2.0 * std::numbers::pi;
  spec.duration_s = kBeltArmDuration;
  return mech::make_motion_law(spec);
}

mech::MultibodyModel belt_arm_model() {
  mech::MultibodyModel m;
  m.name = "belt Q-manipulator";
  m.characteristic_length_m = kBeltArmL1;
  m.gravity = kGravity;
  mech::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  mech::Body link1;
  link1.name = "link1";
  link1.mass_kg = kM1;
  link1.inertia_kgm2 = kJ1;
  link1.com_body = {0.5 * kBeltArmL1, 0.0};
  link1.points["A"] = {kBeltArmL1, 0.0};
  mech::Body link2;
  link2.name = "link2";
  link2.mass_kg = kM2;
  link2.inertia_kgm2 = kJ2;
  link2.com_body = kCom2;
  link2.points["H"] = {kBeltArmL2, 0.0};
  link2.point_masses.push_back({"payload", kPayload, {kBeltArmL2, 0.0}});
  link2.pose = {kBeltArmL1, 0.0, 0.0};
  m.bodies = {ground, link1, link2};
  m.joints.push_back(mech::make_revolute("O", "ground", "origin", "link1", "origin"));
  m.joints.push_back(mech::make_revolute("A", "link1", "A", "link2", "origin"));
  mech::MotionDrive lever;
  lever.name = "lever";
  lever.coordinate = {mech::CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  lever.law = belt_arm_lever_law();
  m.motion_drives.push_back(lever);
  mech::Transmission belt;
  belt.name = "belt";
  belt.input = {mech::CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  belt.output = {mech::CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  belt.ratio = kBeltArmRatio;
  belt.radius_m = kBeltArmPulleyRadius;
  m.transmissions.push_back(belt);
  return m;
}

double belt_arm_moment_on_link2(const mech::MotionState& lever) {
  const double k2 = 1.0 + kBeltArmRatio;  // theta_2 = (1 + ratio) P = (1 - i) P
  const double th1 = lever.s, w1 = lever.s_dot, a1 = lever.s_ddot;
  const double th2 = k2 * th1, w2 = k2 * w1, a2 = k2 * a1;
  const Eigen::Vector2d acc_a = kBeltArmL1 * (a1 * perp(e(th1)) - w1 * w1 * e(th1));
  const Eigen::Matrix2d rot = Eigen::Rotation2Dd(th2).toRotationMatrix();
  double moment = kJ2 * a2;
  for (const auto& [mass, at_body] :
       {std::pair{kM2, kCom2}, std::pair{kPayload, Eigen::Vector2d(kBeltArmL2, 0.0)}}) {
    const Eigen::Vector2d rho = rot * at_body;
    const Eigen::Vector2d acc = acc_a + a2 * perp(rho) - w2 * w2 * rho;
    moment += cross(rho, mass * (acc - kGravity));
  }
  return moment;
}

BeltArmAgreement belt_arm_against_references(const mech::Results& results) {
  const mech::QManipulator closed_form =
      mech::make_two_link_q_manipulator(kBeltArmL1, kBeltArmL2, kBeltArmSourceRatio);
  const auto law = belt_arm_lever_law();
  BeltArmAgreement out;
  for (const mech::Frame& f : results.frames) {
    const double p = f.drives.at(0).s;
    const mech::BodyFrame& link2 = f.bodies.at(2);
    const Eigen::Vector2d h = link2.q.head<2>() + Eigen::Rotation2Dd(link2.q.z()) * Eigen::Vector2d(kBeltArmL2, 0.0);
    out.path_m = std::max(out.path_m, (h - closed_form.point_h(p).p).norm());
    const mech::TransmissionFrame& belt = f.transmissions.at(0);
    const double reference = belt_arm_moment_on_link2(law->at(f.t));
    out.moment_scale_Nm = std::max(out.moment_scale_Nm, std::abs(reference));
    out.moment_Nm = std::max(out.moment_Nm, std::abs(belt.moment_output_Nm - reference));
    out.force_N = std::max(out.force_N, std::abs(belt.force_N - reference / kBeltArmPulleyRadius));
    out.input_moment_Nm = std::max(out.input_moment_Nm, std::abs(belt.moment_input_Nm + kBeltArmRatio * reference));
    out.row_rad = std::max(out.row_rad, std::abs(belt.s_out - kBeltArmRatio * belt.s_in));
  }
  return out;
}

}  // namespace kinetofem::verification::spec4
