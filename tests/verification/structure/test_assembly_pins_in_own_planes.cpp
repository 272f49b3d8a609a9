// Parts in their own planes: the two-link arm of structure_fixtures.hpp with
// link2 moved out of link1's plane by e = 40 mm along the pin axes (its bar
// meshed at z in [e - T/2, e + T/2]), so joint J2's bores sit at z = 0 and
// z = e and its pin is an elastic member (a Timoshenko beam of d = 20 mm).
//
// Plates in parallel planes: both links along x (theta = 0) at rest (t = 0 of
// the 3-4-5 laws: no velocity, no acceleration), gravity along -x, no
// payload. Link2's weight pushes along -x through the pin into link1's tip:
// the pin carries the in-plane force F = m2 g and the out-of-plane moment
// M = e F (link2's loads all act in its own plane, so no moment reaches it
// across the pin), and link1 (held at J1 against the out-of-plane rotations,
// its angle held by d1) is a cantilever under the constant bending moment
// M about y plus an axial load.
//
// Joint forces in the motion: the same arm with gravity -y, at three poses of
// its motion. In the plane it is statically determinate, so the joint forces'
// in-plane components must equal the multibody reactions; out of the plane
// every body must be in equilibrium under its joint loads and its own loads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

using Eigen::Vector3d;
constexpr double kOffset = 0.040;  // e: link2's plane above link1's, m
constexpr double kPinDiameter = 0.020;
constexpr double kG = 9.80665;

struct OffsetArm {
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
};

OffsetArm offset_arm(const test::TwoLinkArm& arm, const Eigen::Vector2d& gravity) {
  OffsetArm r;
  r.parts = test::two_link_parts(arm);
  fem::Mesh& mesh = r.parts[1].model.mesh;
  mesh.nodes.col(2).array() += kOffset;
  r.parts[1].mass = fem::mass_properties(mesh, r.parts[1].model.material);
  r.model = test::two_link_arm(arm);
  r.model.gravity = gravity;
  pipeline::apply_mass_properties(r.model, r.parts, Log::quiet());
  return r;
}

AssemblyOptions with_pin() {
  AssemblyOptions o;
  o.pins.push_back({"J2", kPinDiameter, std::nullopt, std::nullopt});
  return o;
}

TEST(AssemblyPinsInOwnPlanes, PlatesInParallelPlanesCarryTheOutOfPlaneMoment) {
  test::TwoLinkArm arm;
  arm.theta1_rad = 0.0;
  arm.theta2_rad = 0.0;
  // No payload: a point mass acts at its body point in the mechanism's plane
  // (z = 0, loads::LinkLoads), which would load link2 out of its own plane.
  arm.payload_kg = 0.0;
  const OffsetArm r = offset_arm(arm, {-kG, 0.0});
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(r.model), {0.0}).frames;
  AssemblyOptions options = with_pin();
  options.keep_part_stress = true;  // the stress the fatigue check of parts in several planes uses
  ElasticAssembly assembly(r.parts, r.model, options);
  const PoseSolution pose = assembly.solve(frames.front());
  ASSERT_EQ(pose.pins.size(), 1u);
  const PinResult& pin = pose.pin("J2");
  EXPECT_NEAR(pin.length_m, kOffset, 1e-12);

  // Independent of the assembly: the weight of link2's mesh.
  const double F = r.parts[1].mass.mass_kg * kG;
  const double M = kOffset * F;
  const JointLoad& j2 = pose.joint("J2");
  std::printf("  F = %.6g N, e F = %.6g N m; the pin on link1: force (%.6g, %.6g, %.6g) N, moment (%.6g, %.6g, %.6g) N m\n",
              F, M, j2.force_on_i_n.x(), j2.force_on_i_n.y(), j2.force_on_i_n.z(), j2.moment_on_i_nm.x(),
              j2.moment_on_i_nm.y(), j2.moment_on_i_nm.z());
  // Statics of the pin and of link2 (every load of link2 in its plane): the
  // in-plane force F and the moment e F about y on link1; round-off of the
  // dense pose system: 1e-9 relative.
  EXPECT_NEAR(j2.force_on_i_n.x() / -F, 1.0, 1e-9);
  EXPECT_NEAR(j2.moment_on_i_nm.y() / -M, 1.0, 1e-9);  // (e z) x (-F x) = -e F y on link1
  EXPECT_LT(j2.moment_on_j_nm.head<2>().norm(), 1e-9 * M);
  // The pin's section (pin_member.hpp): bending e F at link1's bore, none at
  // link2's; shear F. Same statics: 1e-9.
  EXPECT_NEAR(pin.loads.bending_moment_i_nm / M, 1.0, 1e-9);
  EXPECT_LT(pin.loads.bending_moment_j_nm, 1e-9 * M);
  EXPECT_NEAR(pin.loads.bending_stress_pa / (32 * M / (std::numbers::pi * std::pow(kPinDiameter, 3))), 1.0, 1e-9);
  EXPECT_NEAR(pin.loads.shear_stress_pa / (16 * F / (3 * std::numbers::pi * kPinDiameter * kPinDiameter)), 1.0, 1e-9);
  EXPECT_GT(pin.loads.deflection_m, 0.0);

  // Link1's bending stress at mid-span vs beam theory: sigma = 6 M/(H T^2)
  // at the faces z = +-T/2 (M about y constant along the cantilever; its
  // axial load cancels in (sigma_top - sigma_bottom)/2). 2 %: the Hex20 bar
  // (10 x 2 x 1 cells) and the plate's anticlastic (Poisson) bending.
  const test::BarSize bar;
  const PartField& field = pose.part("link1");
  const fem::Mesh& mesh = r.parts[0].model.mesh;
  const fem::NodalStress recovered = fem::recover_nodal_stress(mesh, r.parts[0].model.material, field.displacement_m);
  // The kept stress tensor (patterns x coefficients: what the fatigue check
  // reads) is the stress of the assembly's displacement field (round-off).
  ASSERT_GT(field.stress_coefficients.size(), 0);
  const Eigen::VectorXd kept = assembly.stress_patterns("link1") * field.stress_coefficients;
  const Eigen::Map<const Eigen::VectorXd> from_field(recovered.stress_pa.data(), recovered.stress_pa.size());
  EXPECT_LT((kept - from_field).cwiseAbs().maxCoeff(), 1e-9 * from_field.cwiseAbs().maxCoeff());
  const Eigen::Map<const fem::StressField> stress_pa(kept.data(), mesh.node_count(), 6);
  double top = 0, bottom = 0;
  int n_top = 0, n_bottom = 0;
  for (fem::Index i = 0; i < mesh.node_count(); ++i) {
    if (std::abs(mesh.nodes(i, 0) - 0.5 * bar.length_m) > 1e-9) continue;
    if (std::abs(mesh.nodes(i, 2) - 0.5 * bar.thickness_m) < 1e-9) top += stress_pa(i, 0), ++n_top;
    if (std::abs(mesh.nodes(i, 2) + 0.5 * bar.thickness_m) < 1e-9) bottom += stress_pa(i, 0), ++n_bottom;
  }
  ASSERT_GT(n_top, 0);
  ASSERT_GT(n_bottom, 0);
  const double bending = 0.5 * (top / n_top - bottom / n_bottom);
  const double beam = 6 * M / (bar.height_m * bar.thickness_m * bar.thickness_m);
  std::printf("  link1 at mid-span: bending stress %.6g MPa, beam theory %.6g MPa (%.3f %%)\n", bending * 1e-6,
              beam * 1e-6, 100 * (std::abs(bending) / beam - 1));
  EXPECT_NEAR(std::abs(bending) / beam, 1.0, 0.02);
}

// Joint forces over the motion. References: the multibody reactions
// (mech::Frame) for the in-plane components, 1e-8 of the largest reaction
// (a dense solve of ~100 unknowns, as for the arm in one plane); each body's
// equilibrium out of the plane (z force, moments about x and y: joint loads
// plus the part's own loads, loads::LinkLoads), 1e-9 of the largest load
// times the arm length.
TEST(AssemblyPinsInOwnPlanes, JointForcesEqualTheReactionsInPlaneAndBalanceOutOfIt) {
  const test::TwoLinkArm arm;
  const OffsetArm r = offset_arm(arm, {0.0, -kG});
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(r.model), {0.1, 0.25, 0.4}).frames;
  ElasticAssembly assembly(r.parts, r.model, with_pin());
  const std::vector<PoseSolution> poses = assembly.solve(frames);
  const double L = arm.l1_m;
  for (size_t f = 0; f < frames.size(); ++f) {
    const mech::Frame& frame = frames[f];
    const PoseSolution& pose = poses[f];
    ASSERT_EQ(pose.pins.size(), 1u);
    EXPECT_EQ(pose.indeterminacy.in_plane, 0) << "the arm is determinate in its plane";
    double scale = 0.0, in_plane = 0.0;
    for (const auto& jf : frame.joints) scale = std::max({scale, jf.on_i.force_world.norm(), jf.on_j.force_world.norm()});
    for (const auto& jf : frame.joints) {
      const JointLoad& jl = pose.joint(jf.name);
      in_plane = std::max(in_plane, (jl.force_on_i_n.head<2>() - jf.on_i.force_world).norm());
      in_plane = std::max(in_plane, (jl.force_on_j_n.head<2>() - jf.on_j.force_world).norm());
    }
    for (const auto& df : frame.drives)
      in_plane = std::max(in_plane, std::abs(pose.drive(df.name).moment_on_j_nm - df.effort) / L);

    // Out of the plane: each moving body's joint loads and own loads.
    double out_of_plane = 0.0, moment_scale = scale * L;
    for (const pipeline::Part& part : r.parts) {
      const mech::BodyFrame& bf = frame.bodies[size_t(&part == &r.parts[0] ? 1 : 2)];
      const Eigen::Matrix3d R = Eigen::AngleAxisd(bf.q.z(), Vector3d::UnitZ()).toRotationMatrix();
      const Vector3d origin(bf.q.x(), bf.q.y(), 0.0);
      Vector3d force, moment;
      fem::resultant(part.model.mesh, assembly.part_loads(part.body()).loads_at(frame).forces, Vector3d::Zero(), force,
                     moment);
      Vector3d sum_force = R * force, sum_moment = R * moment;
      for (const JointLoad& jl : pose.joints) {
        if (jl.body_i == part.body()) {
          sum_force += jl.force_on_i_n;
          sum_moment += jl.moment_on_i_nm + (jl.point_i_m - origin).cross(jl.force_on_i_n);
        }
        if (jl.body_j == part.body()) {
          sum_force += jl.force_on_j_n;
          sum_moment += jl.moment_on_j_nm + (jl.point_j_m - origin).cross(jl.force_on_j_n);
        }
      }
      // The motion drives act about z only: out of the plane they add nothing.
      out_of_plane = std::max({out_of_plane, std::abs(sum_force.z()) * L, sum_moment.head<2>().norm()});
      moment_scale = std::max(moment_scale, moment.norm());
    }
    const double moment_j2 = pose.joint("J2").moment_on_i_nm.head<2>().norm();
    std::printf("  t = %.2f s: in-plane joint forces vs reactions %.2e, out-of-plane equilibrium %.2e (J2's "
                "out-of-plane moment on link1 %.4g N m)\n",
                frame.t, in_plane / scale, out_of_plane / moment_scale, moment_j2);
    EXPECT_LT(in_plane / scale, 1e-8) << "t = " << frame.t;
    EXPECT_LT(out_of_plane / moment_scale, 1e-9) << "t = " << frame.t;
    EXPECT_GT(moment_j2, 1e-3 * scale * kOffset) << "the offset must load link1 out of its plane";
  }
}

// A pin to the rigid ground: link1 too out of the mechanism's plane (z =
// 20 mm), so J1's pin runs from the ground's joint point at z = 0 to
// link1's bore. Reference: the multibody reactions in the plane (the arm
// stays determinate in it), 1e-8 of the largest, as above.
TEST(AssemblyPinsInOwnPlanes, APinToTheGroundStartsInTheMechanismsPlane) {
  const test::TwoLinkArm arm;
  OffsetArm r = offset_arm(arm, {0.0, -kG});
  r.parts[0].model.mesh.nodes.col(2).array() += 0.020;
  r.parts[0].mass = fem::mass_properties(r.parts[0].model.mesh, r.parts[0].model.material);
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(r.model), {0.25}).frames;
  ElasticAssembly assembly(r.parts, r.model, with_pin());
  const PoseSolution pose = assembly.solve(frames.front());
  ASSERT_EQ(pose.pins.size(), 2u);
  EXPECT_NEAR(pose.pin("J1").length_m, 0.020, 1e-12);
  EXPECT_NEAR(pose.pin("J1").end_i_m.z(), 0.0, 1e-15);
  EXPECT_NEAR(pose.pin("J2").length_m, kOffset - 0.020, 1e-12);
  double scale = 0.0, worst = 0.0;
  for (const auto& jf : frames.front().joints) scale = std::max(scale, jf.on_i.force_world.norm());
  for (const auto& jf : frames.front().joints) {
    const JointLoad& jl = pose.joint(jf.name);
    worst = std::max({worst, (jl.force_on_i_n.head<2>() - jf.on_i.force_world).norm(),
                      (jl.force_on_j_n.head<2>() - jf.on_j.force_world).norm()});
  }
  std::printf("  pins J1 (to the ground) and J2: in-plane joint forces vs reactions %.2e\n", worst / scale);
  EXPECT_LT(worst / scale, 1e-8);
  EXPECT_GT(pose.pin("J1").loads.bending_stress_pa, 0.0);
}

// The split of a tracked point's displacement still adds up with the pin in it.
TEST(AssemblyPinsInOwnPlanes, UnitLoadSplitAddsUpWithThePin) {
  const test::TwoLinkArm arm;
  const OffsetArm r = offset_arm(arm, {0.0, -kG});
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(r.model), {0.25}).frames;
  AssemblyOptions o = with_pin();
  o.points.push_back({"tip", "link2", "tip", "x1"});
  ElasticAssembly assembly(r.parts, r.model, o);
  const PoseSolution pose = assembly.solve(frames.front());
  const PointResult& tip = pose.point("tip");
  Vector3d sum = Vector3d::Zero(), pin_share = Vector3d::Zero();
  for (const auto& c : tip.contributions) {
    sum += c.displacement_m;
    if (c.name == "pin.J2") pin_share = c.displacement_m;
  }
  std::printf("  tip displacement %.6g mm, pin's share %.6g mm, sum of the split - displacement %.2e mm\n",
              tip.displacement_m.norm() * 1e3, pin_share.norm() * 1e3, (sum - tip.displacement_m).norm() * 1e3);
  // Maxwell-Betti: exact up to round-off of the dense solve (1e-9 relative).
  EXPECT_LT((sum - tip.displacement_m).norm(), 1e-9 * tip.displacement_m.norm());
  EXPECT_GT(pin_share.norm(), 0.0);
}

TEST(AssemblyPinsInOwnPlanes, PinOptionsAreChecked) {
  const test::TwoLinkArm arm;
  const OffsetArm r = offset_arm(arm, {0.0, -kG});
  AssemblyOptions no_joint;
  no_joint.pins.push_back({"J9", kPinDiameter, std::nullopt, std::nullopt});
  EXPECT_NE(test::error_of([&] { ElasticAssembly(r.parts, r.model, no_joint); }).find("not a revolute joint"),
            std::string::npos);
  // A pin through bores in one plane: the rigid tie stays (no pin member).
  AssemblyOptions same_plane = with_pin();
  same_plane.pins.push_back({"J1", kPinDiameter, std::nullopt, std::nullopt});
  ElasticAssembly assembly(r.parts, r.model, same_plane);
  const std::vector<mech::Frame> frames = mech::run_kinematics(mech::MultibodySystem(r.model), {0.25}).frames;
  const PoseSolution pose = assembly.solve(frames.front());
  ASSERT_EQ(pose.pins.size(), 1u);
  EXPECT_EQ(pose.pins.front().joint, "J2");
  AssemblyOptions too_wide;
  too_wide.pins.push_back({"J2", 0.2, std::nullopt, std::nullopt});
  EXPECT_NE(test::error_of([&] { ElasticAssembly(r.parts, r.model, too_wide); }).find("larger than the bore"),
            std::string::npos);
}

}  // namespace
}  // namespace kinetofem::structure
