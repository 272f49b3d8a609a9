// Load transfer from the multibody results onto link FE models: a driven
// double pendulum of two identical two-bore links (tests/data/meshes/
// link_two_bores.geo) with a tip mass. The multibody bodies take the FE
// meshes' mass properties, so every link's transferred loads must be in
// equilibrium (reference: d'Alembert, exact up to round-off).
#include <gtest/gtest.h>

#include <memory>
#include <numbers>

#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace kinetofem::loads {
namespace {


const fem::FeModel& link_model() { return testing::two_bore_link_model(); }
using testing::double_pendulum;

std::vector<double> times(int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(0.5 * k / n);
  return t;
}

TEST(LinkLoads, TransferredLoadsOfEveryLinkAreInEquilibriumOverTheMotion) {
  const mech::MultibodyModel model = double_pendulum();
  const mech::MultibodySystem system(model);
  const mech::Results results = mech::run_kinematics(system, times(20));
  for (BoreLoad distribution : {BoreLoad::DistributingCoupling, BoreLoad::BearingPressure}) {
    LinkDefinition link1{"link1", &link_model(),
                         {{"J1", "bore_1", distribution}, {"J2", "bore_2", distribution}},
                         {},
                         {{"D1", "bore_1"}, {"D2", "bore_2"}}};
    LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1", distribution}},
                         {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
    const LinkLoads loads1(link1, model), loads2(link2, model);
    double worst = 0.0;
    for (const auto& frame : results.frames) {
      worst = std::max(worst, loads1.loads_at(frame).equilibrium_residual);
      worst = std::max(worst, loads2.loads_at(frame).equilibrium_residual);
    }
    // Reference: d'Alembert equilibrium of each link; the multibody
    // reactions balance to ~1e-12 and the FE mass properties match the
    // bodies' to round-off. The coupling reproduces each reaction exactly:
    // 1e-9. The bearing pressure reproduces the force exactly but cannot
    // carry a moment: on the unsymmetric (unstructured) bore its pressure
    // centre lies slightly off the mid-plane, leaving an out-of-plane moment
    // (measured 6e-7 of the loads here): it is held to the pipeline's
    // threshold, 1e-6.
    const bool bearing = distribution == BoreLoad::BearingPressure;
    EXPECT_LT(worst, bearing ? 1e-6 : 1e-9) << (bearing ? "bearing" : "coupling");
  }
}

TEST(LinkLoads, LoadPatternsTimesCoefficientsAreTheLoadsOfEveryFrame) {
  // Reference: loads_at (the nodal forces built frame by frame). The
  // patterns' combination is the same sum in another order: 1e-12 of the
  // largest nodal force.
  const mech::MultibodyModel model = double_pendulum();
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times(10));
  LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  ASSERT_TRUE(loads.superposable());
  const Eigen::MatrixXd P = loads.pattern_forces();
  ASSERT_EQ(P.cols(), loads.pattern_count());
  EXPECT_EQ(loads.pattern_count(), 12 + 6 * 2);  // bore_1 (joint and drive share it), bore_2 (the tip mass)
  EXPECT_EQ(loads.pattern_names().size(), size_t(loads.pattern_count()));
  EXPECT_EQ(loads.pattern_names()[12], "bore_1.F_x");
  double worst = 0.0;
  for (const auto& frame : results.frames) {
    const Eigen::VectorXd f = loads.loads_at(frame).forces;
    const LinkLoadCoefficients c = loads.coefficients_at(frame);
    worst = std::max(worst, (P * c.coefficients - f).cwiseAbs().maxCoeff() / f.cwiseAbs().maxCoeff());
    EXPECT_EQ(c.equilibrium_residual, loads.loads_at(frame).equilibrium_residual);
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(LinkLoads, BearingPressureIsNotAPatternCombination) {
  const mech::MultibodyModel model = double_pendulum();
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times(2));
  LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1", BoreLoad::BearingPressure}}, {{"tip", "bore_2"}},
                       {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  EXPECT_FALSE(loads.superposable());
  try {
    loads.coefficients_at(results.frames.front());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("bearing pressure"), std::string::npos) << e.what();
  }
}

TEST(LinkLoads, MismatchedMassPropertiesAreReportedWithLinkAndTime) {
  mech::MultibodyModel model = double_pendulum();
  model.bodies[2].mass_kg *= 1.05;  // the multibody arm 5 % heavier than its mesh
  const mech::MultibodySystem system(model);
  const mech::Results results = mech::run_kinematics(system, times(4));
  LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  try {
    loads.loads_at(results.frames.back());
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("link 'link2' at t = 0.5 s"), std::string::npos) << what;
  }
}

TEST(LinkLoads, BlockSolveOverAllTimesEqualsSingleSolves) {
  const mech::MultibodyModel model = double_pendulum();
  const mech::MultibodySystem system(model);
  const mech::Results results = mech::run_kinematics(system, times(10));
  LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads(link2, model);
  fem::FeModel fe = link_model();
  std::vector<fem::Index> all(size_t(fe.mesh.node_count()));
  for (size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
  fe.supports = fem::three_two_one_support(fe.mesh, all);
  Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  Eigen::MatrixXd F(3 * fe.mesh.node_count(), Eigen::Index(results.frames.size()));
  for (size_t k = 0; k < results.frames.size(); ++k) F.col(Eigen::Index(k)) = loads.loads_at(results.frames[k]).forces;
  const auto block = analysis.solve_forces(F);
  double worst = 0.0, scale = 0.0, worst_reaction = 0.0;
  for (Eigen::Index k = 0; k < F.cols(); ++k) {
    const auto single = analysis.solve_forces(F.col(k));
    worst = std::max(worst, (block[size_t(k)] - single[0]).cwiseAbs().maxCoeff());
    scale = std::max(scale, single[0].cwiseAbs().maxCoeff());
    const Eigen::VectorXd r = analysis.reactions(single[0], F.col(k));
    worst_reaction = std::max(worst_reaction, r.cwiseAbs().maxCoeff() / F.col(k).cwiseAbs().maxCoeff());
  }
  // Same factor, same right-hand sides: identical to round-off (1e-12 relative).
  EXPECT_LT(worst, 1e-12 * scale);
  // The 3-2-1 support of a self-equilibrated load carries nothing (1e-8 of the largest nodal load).
  EXPECT_LT(worst_reaction, 1e-8);
}

// A frame (a part of the ground) held on its foundation carries the ground
// sides of its joint and drive plus its weight; nothing balances them but
// the foundation, so loads_at neither checks their equilibrium nor hands
// out-of-plane components to the pins. Reference: the resultant force is
// the ground side of J1 plus the frame's weight (exact: the coupling and the
// body-force basis are statically exact), 1e-9.
TEST(LinkLoads, AFrameHeldOnItsFoundationCarriesTheGroundSidesUnbalanced) {
  const mech::MultibodyModel model = double_pendulum();
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times(4));
  LinkDefinition frame{"ground", &link_model(), {{"J1", "bore_1"}}, {}, {{"D1", "bore_1"}}};
  EXPECT_THROW(LinkLoads(frame, model).loads_at(results.frames[2]), Error);  // as a free link: out of equilibrium
  frame.held_on_foundation = true;
  const LinkLoads loads(frame, model);
  const double mass = fem::mass_properties(link_model().mesh, link_model().material).mass_kg;
  for (const auto& f : results.frames) {
    const LinkLoadResult r = loads.loads_at(f);
    Eigen::Vector3d force, moment;
    fem::resultant(link_model().mesh, r.forces, Eigen::Vector3d::Zero(), force, moment);
    const Eigen::Vector2d expected = f.joints[0].on_i.force_world + mass * model.gravity;
    EXPECT_LT((force.head<2>() - expected).norm(), 1e-9 * expected.norm()) << "t = " << f.t;
    EXPECT_LT(std::abs(force.z()), 1e-9 * expected.norm());
    EXPECT_EQ(r.out_of_plane_force_n, 0.0);
    EXPECT_EQ(r.out_of_plane_moment_nm, 0.0);
  }
}

TEST(LinkLoads, APartBuiltOutOfThePlaneTakesItsLoadsInItsOwnPlane) {
  // link2 built 50 mm out of the mechanism's plane (its mesh shifted along
  // the pins), its joint in bore_1 and the tip mass mounted on its bore_2
  // face: the reaction acts in the bore and the mass sits at that face's z,
  // so the link is loaded as the same link in the plane, and the out-of-plane
  // moment its pins are given is the same (at z = 0 the joint alone would
  // add e |R|, several N m here, and the mass about 0.05 x 29 N = 1.5 N m).
  const double e = 0.05;
  fem::FeModel shifted = link_model();
  shifted.mesh.nodes.col(2).array() += e;
  const mech::MultibodyModel model = double_pendulum();
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times(4));
  const LinkDefinition out_of_plane{"link2", &shifted, {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkDefinition in_plane{"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}};
  const LinkLoads loads_out(out_of_plane, model), loads_in(in_plane, model);
  for (const auto& frame : results.frames) {
    const LinkLoadResult a = loads_out.loads_at(frame), b = loads_in.loads_at(frame);
    // Reference: the same loads translated along z; 1e-6 N m: the centroids
    // of the unstructured bores' faces lie off their mid-plane by a few 1e-9
    // m (the effect tested is several N m).
    EXPECT_NEAR(a.out_of_plane_moment_nm, b.out_of_plane_moment_nm, 1e-6) << "t = " << frame.t;
    EXPECT_LT(a.equilibrium_residual, 1e-9) << "t = " << frame.t;
  }
}

// The double pendulum with its second drive replaced by a belt from the
// ground's pulley at J1 to link2's at J2, carried by link1 (ratio -2: link2
// turns back relative to link1 twice as far as link1 turns).
mech::MultibodyModel belt_pendulum() {
  mech::MultibodyModel m = double_pendulum();
  m.motion_drives.pop_back();
  mech::Transmission belt;
  belt.name = "T";
  belt.input = {mech::CoordinateType::Angle, "ground", "origin", "link1", "origin", {1, 0}};
  belt.output = {mech::CoordinateType::Angle, "link1", "origin", "link2", "origin", {1, 0}};
  belt.ratio = -2.0;
  belt.radius_m = 0.03;
  m.transmissions.push_back(belt);
  return m;
}

// A transmission's moments enter the parts of the bodies it joins like a
// drive's effort: link1 takes the input side's moment (as the input's body_j)
// at bore_1 and the output side's reaction (as the output's body_i) at
// bore_2, link2 the output side's moment at bore_1. Reference: d'Alembert
// equilibrium of each link, 1e-9 as for the joints and drives above; the
// patterns' combination equals loads_at to 1e-12; without link2's share the
// link is out of equilibrium (the check sees the missing moment).
TEST(LinkLoads, TransmissionMomentsKeepEveryLinkInEquilibriumAndSuperpose) {
  const mech::MultibodyModel model = belt_pendulum();
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times(10));
  ASSERT_EQ(results.frames.front().transmissions.size(), 1u);
  LinkDefinition link1{"link1", &link_model(), {{"J1", "bore_1"}, {"J2", "bore_2"}}, {}, {{"D1", "bore_1"}}};
  link1.transmissions = {{"T", TransmissionSide::Input, "bore_1"}, {"T", TransmissionSide::Output, "bore_2"}};
  LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}};
  link2.transmissions = {{"T", TransmissionSide::Output, "bore_1"}};
  const LinkLoads loads1(link1, model), loads2(link2, model);
  double worst = 0.0, worst_pattern = 0.0, peak_moment = 0.0;
  for (const auto& frame : results.frames) {
    peak_moment = std::max(peak_moment, std::abs(frame.transmissions[0].moment_output_Nm));
    for (const LinkLoads* loads : {&loads1, &loads2}) {
      const LinkLoadResult r = loads->loads_at(frame);
      worst = std::max(worst, r.equilibrium_residual);
      const Eigen::VectorXd combined = loads->pattern_forces() * loads->coefficients_at(frame).coefficients;
      worst_pattern = std::max(worst_pattern, (combined - r.forces).cwiseAbs().maxCoeff() / r.forces.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(peak_moment, 1.0);  // the belt carries link2 (N m): the check is not vacuous
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_pattern, 1e-12);
  LinkDefinition without = link2;
  without.transmissions.clear();
  EXPECT_THROW(LinkLoads(without, model).loads_at(results.frames[5]), Error);
  LinkDefinition wrong_side = link2;
  wrong_side.transmissions = {{"T", TransmissionSide::Input, "bore_1"}};  // link2 is not on the input
  EXPECT_THROW(LinkLoads(wrong_side, model), Error);
}

// The double pendulum with its second drive a linear actuator between the
// links: s = t . (r_B2(link2) - r_origin(link1)), t = link1's y axis, the
// offset across link1 of link2's far bore (s from 0 to -0.1 m: link2 turns
// back by asin(0.1 / 0.24)). Its force enters link2 at bore_2 along t and
// link1 at bore_1 against it, with the couple of t turning with link1.
// Reference: d'Alembert equilibrium of each link, 1e-9 as for the torque
// drives above (without the couple link1 would be out of balance by
// effort x (t x span)); the patterns' combination equals loads_at to 1e-12.
TEST(LinkLoads, ALinearActuatorsForceAndCoupleKeepEveryLinkInEquilibrium) {
  mech::MultibodyModel model = double_pendulum();
  mech::MotionDrive actuator;
  actuator.name = "A2";
  actuator.coordinate = {mech::CoordinateType::Displacement, "link1", "origin", "link2", "B2", {0.0, 1.0}};
  actuator.law = std::make_shared<mech::Polynomial345Law>(-0.1, 0.5);
  model.motion_drives.back() = actuator;
  const mech::Results results = mech::run_kinematics(mech::MultibodySystem(model), times(10));
  LinkDefinition link1{"link1", &link_model(), {{"J1", "bore_1"}, {"J2", "bore_2"}}, {}, {{"D1", "bore_1"}, {"A2", "bore_1"}}};
  LinkDefinition link2{"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"A2", "bore_2"}}};
  const LinkLoads loads1(link1, model), loads2(link2, model);
  double worst = 0.0, worst_pattern = 0.0, peak = 0.0;
  for (const auto& frame : results.frames) {
    peak = std::max(peak, std::abs(frame.drives[1].effort));
    for (const LinkLoads* loads : {&loads1, &loads2}) {
      const LinkLoadResult r = loads->loads_at(frame);
      worst = std::max(worst, r.equilibrium_residual);
      const Eigen::VectorXd combined = loads->pattern_forces() * loads->coefficients_at(frame).coefficients;
      worst_pattern = std::max(worst_pattern, (combined - r.forces).cwiseAbs().maxCoeff() / r.forces.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_GT(peak, 10.0);  // the actuator carries link2 and its 3 kg tip (N): not vacuous
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(worst_pattern, 1e-12);
  LinkDefinition without = link1;
  without.drives.pop_back();
  EXPECT_THROW(LinkLoads(without, model).loads_at(results.frames[5]), Error);
}

}  // namespace
}  // namespace kinetofem::loads
