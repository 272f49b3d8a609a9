// Verification 3: a pinned two-bar frame of slender bars with a torsional
// spring, loaded at its tip, against Euler-Bernoulli beam theory.
//
//          D  <- P (tip load, +x)
//          |
//   bar 2  |  L2 (along world +y; its body frame turned 90 deg)
//          |
//   O======B        bar 1: L1 along +x
//   ^ J1: pin to the ground at O, drive d1 rigid (holds bar 1's angle)
//          ^ J2: pin at B, drive d2 a torsional spring k_d (bar 2 against bar 1)
//
// Bars h x t = 20 x 20 mm (HEX20, 2 x 2 cells across, 25 / 20 along), steel,
// no gravity, static. Bar 2 is a cantilever from B under P; bar 1 carries
// the axial force P and the constant moment M = P L2 (pure bending). Tip
// displacement along x (EB theory, I = t h^3 / 12, A = h t):
//   bar 2 bending           P L2^3 / (3 E I)
//   bar 1 rotation at B     theta_B = M L1 / (E I), times the arm L2: P L2^2 L1 / (E I)
//   bar 1 elongation        P L1 / (E A)
//   spring at B             P L2 / k_d, times L2: P L2^2 / k_d
// along y: bar 1's deflection at B under M: -P L2 L1^2 / (2 E I) (the rotations
// at B move D only along x; bar 2 carries no axial force).
// Tolerance 1 % (discretisation, the couplings' Saint-Venant end zones and the
// shear deflection of bar 2, 3 E I / (kappa G A L2^2) = 0.2 % of its part).
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

TEST(ElasticAssemblyBeamFrame, TipDeflectionIsBeamTheoryPlusTheSpring) {
  const double L1 = 0.5, L2 = 0.4, h = 0.02, t = 0.02, P = 100.0, kd = 5000.0;
  mech::MultibodyModel m;
  m.name = "two-bar frame";
  m.characteristic_length_m = L1;
  m.gravity = {0.0, 0.0};
  mech::Body ground;
  ground.name = "frame";
  ground.fixed = true;
  mech::Body bar1;
  bar1.name = "bar1";
  bar1.mass_kg = 1.0;
  bar1.inertia_kgm2 = 0.01;
  bar1.points["tip"] = {L1, 0.0};
  mech::Body bar2 = bar1;
  bar2.name = "bar2";
  bar2.points["tip"] = {L2, 0.0};
  bar2.pose = {L1, 0.0, 90 * test::kDeg};
  m.bodies = {ground, bar1, bar2};
  m.joints.push_back(mech::make_revolute("J1", "frame", "origin", "bar1", "origin"));
  m.joints.push_back(mech::make_revolute("J2", "bar1", "tip", "bar2", "origin"));
  mech::MotionDrive d1;
  d1.name = "d1";
  d1.coordinate = {mech::CoordinateType::Angle, "frame", "origin", "bar1", "origin", {1, 0}};
  d1.law = std::make_shared<mech::Polynomial345Law>(0.0, 1.0);  // held at its initial angle
  mech::MotionDrive d2 = d1;
  d2.name = "d2";
  d2.coordinate = {mech::CoordinateType::Angle, "bar1", "origin", "bar2", "origin", {1, 0}};
  m.motion_drives = {d1, d2};
  m.point_forces.push_back({"push", "bar2", "tip", {P, 0.0}});

  test::BarSize s1, s2;
  s1.length_m = L1;
  s2.length_m = L2;
  s1.height_m = s2.height_m = h;
  s1.thickness_m = s2.thickness_m = t;
  s1.cells = {25, 2, 2};
  s2.cells = {20, 2, 2};
  std::vector<pipeline::Part> parts = {
      test::bar_part("bar1", {"bar1", nullptr, {{"J1", "x0"}, {"J2", "x1"}}, {}, {{"d1", "x0"}, {"d2", "x1"}}}, s1),
      test::bar_part("bar2", {"bar2", nullptr, {{"J2", "x0"}}, {}, {{"d2", "x0"}}, {}, {{"push", "x1"}}}, s2)};
  pipeline::apply_mass_properties(m, parts, Log::quiet());
  const mech::Frame frame = mech::run_kinematics(mech::MultibodySystem(m), {0.0}).frames.front();

  AssemblyOptions options;
  options.drives = {{"d2", kd}};
  options.points = {{"D", "bar2", "tip", "x1"}};
  ElasticAssembly assembly(parts, m, options);
  const PoseSolution pose = assembly.solve(frame);
  const Eigen::Vector3d u = pose.point("D").displacement_m;

  const double E = parts[0].model.material.youngs_modulus_pa, I = t * h * h * h / 12.0, A = h * t;
  const double bar2_bending = P * L2 * L2 * L2 / (3 * E * I);
  const double bar1_rotation = P * L2 * L2 * L1 / (E * I);
  const double bar1_axial = P * L1 / (E * A);
  const double spring = P * L2 * L2 / kd;
  const double expected_x = bar2_bending + bar1_rotation + bar1_axial + spring;
  const double expected_y = -P * L2 * L1 * L1 / (2 * E * I);
  std::printf(
      "  tip D: u_x %.5e m (beam theory %.5e: bar 2 %.3e, bar 1 rotation %.3e, axial %.1e, spring %.3e), "
      "error %.3f %%\n",
      u.x(), expected_x, bar2_bending, bar1_rotation, bar1_axial, spring, 100 * (u.x() / expected_x - 1));
  std::printf("  tip D: u_y %.5e m (beam theory %.5e), error %.3f %%; u_z %.1e m\n", u.y(), expected_y,
              100 * (u.y() / expected_y - 1), u.z());
  EXPECT_NEAR(u.x(), expected_x, 0.01 * std::abs(expected_x));
  EXPECT_NEAR(u.y(), expected_y, 0.01 * std::abs(expected_y));
  EXPECT_LT(std::abs(u.z()), 1e-9 * std::abs(expected_x));  // symmetric about the plane
  // The spring's twist: the moment it carries (P L2) over k_d, exactly (statically determinate).
  const DriveResult& spring_drive = pose.drive("d2");
  EXPECT_NEAR(spring_drive.moment_on_j_nm, P * L2, 1e-9 * P * L2);
  EXPECT_NEAR(spring_drive.twist_rad, -P * L2 / kd, 1e-9 * P * L2 / kd);
  // The largest nodal displacement is at the tip end of bar 2.
  EXPECT_EQ(pose.max_displacement_body, "bar2");
}

}  // namespace
}  // namespace kinetofem::structure
