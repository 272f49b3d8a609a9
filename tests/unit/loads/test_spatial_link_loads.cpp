// SpatialLinkLoads: the loads of a spatial mechanism's frames on a part's FE
// model, as coefficients of the part's fixed load patterns.
#include <gtest/gtest.h>

#include <memory>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace kinetofem::loads {
namespace {

namespace spatial = mech::spatial;
constexpr double kDeg = std::numbers::pi / 180.0;

const fem::FeModel& link_model() { return testing::two_bore_link_model(); }

std::vector<double> times(int n) {
  std::vector<double> t;
  for (int k = 0; k <= n; ++k) t.push_back(0.5 * k / n);
  return t;
}

// A two-bore link as a spatial body (the mesh's mass properties, its far bore
// "B2").
spatial::Body spatial_link(const std::string& name) {
  spatial::Body b;
  b.name = name;
  assign_mass_properties(b, link_model());
  b.points["B2"] = {0.24, 0.0, 0.0};
  return b;
}

spatial::MotionDrive rotation_drive(const std::string& name, const std::string& joint,
                                    std::shared_ptr<const mech::MotionLaw> law) {
  spatial::MotionDrive d;
  d.name = name;
  d.joint = joint;
  d.coordinate = spatial::DriveCoordinate::Rotation;
  d.law = std::move(law);
  return d;
}

// testing::double_pendulum() (planar, gravity -y) written for the spatial core.
spatial::Model spatial_double_pendulum() {
  spatial::Model m;
  m.name = "double pendulum";
  m.characteristic_length_m = 0.3;
  m.gravity = {0.0, -9.81, 0.0};
  spatial::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  spatial::Body link1 = spatial_link("link1"), link2 = spatial_link("link2");
  link2.position = {0.24, 0.0, 0.0};
  link2.point_masses.push_back({"tip", 3.0, {0.24, 0.0, 0.0}, Eigen::Matrix3d::Zero()});
  m.bodies = {ground, link1, link2};
  m.joints = {spatial::make_joint("J1", spatial::JointType::Revolute, "ground", "origin", "link1", "origin"),
              spatial::make_joint("J2", spatial::JointType::Revolute, "link1", "B2", "link2", "origin")};
  m.motion_drives = {rotation_drive("D1", "J1", std::make_shared<mech::CycloidalLaw>(60 * kDeg, 0.5)),
                     rotation_drive("D2", "J2", std::make_shared<mech::Polynomial345Law>(-90 * kDeg, 0.5))};
  return m;
}

TEST(SpatialLinkLoads, PlanarMotionGivesThePlanarLoads) {
  // Reference: the planar LinkLoads of the same mechanism through the planar
  // core (tests/unit/loads/test_link_loads.cpp). Both build the same pattern
  // coefficients from reactions that agree to ~1e-12 (the spatial core's
  // planar tests; measured 1.1e-12 here); the planar loads also hand the
  // out-of-plane residue of the unstructured mesh (its centroid ~1e-9 m off
  // z = 0) to the pins: 1e-10 of the largest coefficient.
  const mech::MultibodyModel planar_model = testing::double_pendulum();
  const mech::Results planar = mech::run_kinematics(mech::MultibodySystem(planar_model), times(10));
  const spatial::Model model = spatial_double_pendulum();
  const spatial::Results results = spatial::run_kinematics(spatial::System(model), times(10));
  ASSERT_EQ(planar.frames.size(), results.frames.size());
  const LinkLoads planar1(
      {"link1", &link_model(), {{"J1", "bore_1"}, {"J2", "bore_2"}}, {}, {{"D1", "bore_1"}, {"D2", "bore_2"}}},
      planar_model);
  const LinkLoads planar2({"link2", &link_model(), {{"J2", "bore_1"}}, {{"tip", "bore_2"}}, {{"D2", "bore_1"}}},
                          planar_model);
  const SpatialLinkLoads loads1(
      {"link1", &link_model(), {{"J1", "bore_1"}, {"J2", "bore_2"}, {"D1", "bore_1"}, {"D2", "bore_2"}}}, model);
  const SpatialLinkLoads loads2({"link2", &link_model(), {{"J2", "bore_1"}, {"D2", "bore_1"}}, {{"tip", "bore_2"}}},
                                model);
  EXPECT_EQ(loads1.pattern_names(), planar1.pattern_names());
  EXPECT_EQ(loads2.pattern_names(), planar2.pattern_names());
  double worst = 0.0, worst_equilibrium = 0.0;
  for (std::size_t k = 0; k < results.frames.size(); ++k)
    for (const auto& [spatial_loads, planar_loads] : {std::pair{&loads1, &planar1}, std::pair{&loads2, &planar2}}) {
      const LinkLoadCoefficients s = spatial_loads->coefficients_at(results.frames[k]);
      const LinkLoadCoefficients p = planar_loads->coefficients_at(planar.frames[k]);
      worst = std::max(worst,
                       (s.coefficients - p.coefficients).cwiseAbs().maxCoeff() / p.coefficients.cwiseAbs().maxCoeff());
      worst_equilibrium = std::max(worst_equilibrium, s.equilibrium_residual);
    }
  EXPECT_LT(worst, 1e-10);
  // d'Alembert equilibrium of each link with the FE mass properties on its
  // body: round-off (measured 4e-16).
  EXPECT_LT(worst_equilibrium, 1e-12);
}

// A link on a revolute whose axis is tilted 30 degrees from the vertical,
// driven through 120 degrees, carrying at its far bore a gripper with rotary
// inertia: every load component in 3D.
spatial::Model tilted_link(double gripper_inertia_scale = 1.0) {
  spatial::Model m;
  m.name = "tilted link";
  m.characteristic_length_m = 0.3;
  spatial::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  const Eigen::Vector3d axis(0.0, std::sin(30 * kDeg), std::cos(30 * kDeg));
  spatial::Body link = spatial_link("link");
  spatial::set_rotation(link, Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis).toRotationMatrix());
  link.point_masses.push_back({"gripper",
                               4.0,
                               {0.24, 0.0, 0.0},
                               gripper_inertia_scale * Eigen::Vector3d(0.01, 0.02, 0.03).asDiagonal().toDenseMatrix()});
  m.bodies = {ground, link};
  m.joints = {spatial::make_joint("J", spatial::JointType::Revolute, "ground", "origin", "link", "origin", axis,
                                  Eigen::Vector3d::UnitZ())};
  m.motion_drives = {rotation_drive("D", "J", std::make_shared<mech::CycloidalLaw>(120 * kDeg, 0.5))};
  return m;
}

TEST(SpatialLinkLoads, LoadsOfASpatialMotionAreInEquilibrium) {
  // Reference: d'Alembert equilibrium of the link (Newton-Euler of the body
  // with its gripper); the spatial reactions balance to round-off (measured
  // 3e-16): 1e-12.
  const spatial::Model model = tilted_link();
  const spatial::Results results = spatial::run_kinematics(spatial::System(model), times(20));
  const SpatialLinkLoads loads({"link", &link_model(), {{"J", "bore_1"}, {"D", "bore_1"}}, {{"gripper", "bore_2"}}},
                               model);
  double worst = 0.0, out_of_plane = 0.0;
  for (const spatial::Frame& f : results.frames) {
    const LinkLoadCoefficients c = loads.coefficients_at(f);
    worst = std::max(worst, c.equilibrium_residual);
    // The gravity has components in the link's plane and across it.
    out_of_plane = std::max(out_of_plane, std::abs(c.coefficients[2]));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_GT(out_of_plane, 1.0);

  // Without the gripper's rotary inertia on the part, the loads are out of
  // balance by the gyroscopic and angular-acceleration moments: an Error
  // naming the part and the time.
  const spatial::Model lighter = tilted_link(0.0);
  const SpatialLinkLoads unbalanced(
      {"link", &link_model(), {{"J", "bore_1"}, {"D", "bore_1"}}, {{"gripper", "bore_2"}}}, lighter);
  try {
    for (const spatial::Frame& f : results.frames) unbalanced.coefficients_at(f);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("part 'link' at t = "), std::string::npos) << e.what();
  }
}

TEST(SpatialLinkLoads, PatternHistoryStressEqualsFrameByFrameSolves) {
  // Reference: each frame's nodal forces P c(t) solved on their own; the
  // superposition is the same linear algebra in another order: round-off,
  // 1e-12 of the peak deformation (measured 7e-15).
  const spatial::Model model = tilted_link();
  const spatial::Results results = spatial::run_kinematics(spatial::System(model), times(8));
  const SpatialLinkLoads loads({"link", &link_model(), {{"J", "bore_1"}, {"D", "bore_1"}}, {{"gripper", "bore_2"}}},
                               model);
  fem::FeModel fe = testing::supported_two_bore_link();
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(fe, log);
  std::vector<fem::DisplacementField> fields(results.frames.size());
  const PatternLoadHistory history = loads.history(results.frames);
  EXPECT_EQ(history.times.size(), results.frames.size());
  const LinkEnvelope env = analyse_link_over_motion(
      analysis, history, log, {},
      [&](std::size_t step, const fem::DisplacementField& u, const fem::NodalStress&) { fields[step] = u; });
  double worst = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < results.frames.size(); ++k) {
    const fem::DisplacementField u = analysis.solve_forces(loads.loads_at(results.frames[k]))[0];
    const fem::DisplacementField elastic = fem::remove_rigid_body_motion(fe.mesh, u);
    worst = std::max(worst, (elastic - fields[k]).cwiseAbs().maxCoeff());
    scale = std::max(scale, elastic.cwiseAbs().maxCoeff());
  }
  EXPECT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-12 * scale);
  EXPECT_LT(env.worst_support_reaction, 1e-6);
  EXPECT_GT(env.peak_von_mises_pa, 0.0);
}

TEST(SpatialLinkLoads, UnknownNamesAreErrorsNamingThePart) {
  const spatial::Model model = tilted_link();
  for (const SpatialLinkDefinition& bad :
       {SpatialLinkDefinition{"arm", &link_model(), {{"J", "bore_1"}}},
        SpatialLinkDefinition{"link", &link_model(), {{"K", "bore_1"}}},
        SpatialLinkDefinition{"link", &link_model(), {{"J", "bore_9"}}},
        SpatialLinkDefinition{"link", &link_model(), {{"J", "bore_1"}}, {{"casting", "bore_2"}}}}) {
    try {
      SpatialLinkLoads loads(bad, model);
      FAIL() << "expected an Error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("'"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace kinetofem::loads
