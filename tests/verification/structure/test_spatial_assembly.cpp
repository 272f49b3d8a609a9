// The spatial elastic assembly (structure/spatial_elastic_assembly.hpp).
//
// 1. A cantilevered sliding arm: a HEX20 bar on a prismatic joint to the
//    ground whose axis is oblique to every world axis, held along it by a
//    rigid displacement drive, loaded at its tip. The tip's compliance, turned
//    into the bar's axes, vs beam theory: across the bar in each direction,
//    Timoshenko's cantilever L^3 / (3 E I) + L / (kappa G A) (kappa = 10 (1 +
//    nu) / (12 + 11 nu), a rectangle); along it, L / (E A). 1 %: the root is
//    held through a distributing coupling of its end face (which lets the face
//    warp) and the tip load enters the same way (Saint-Venant zones); the
//    planar assembly's column measured -0.47 % with the same couplings.
// 2. A spatial two-link arm (a revolute about the vertical, then a revolute
//    about link1's own y axis, so link2 pitches out of any plane; both turned
//    by rigid motion drives; a payload with rotary inertia; gravity), at two
//    output times of its motion:
//    a. the assembly equals the monolithic sparse reference
//       (spatial_monolithic_reference.hpp: the full stiffnesses with the same
//       ties as Lagrange constraints), 1e-8 of the largest displacement;
//    b. a serial chain is statically determinate: every joint's load and each
//       drive's effort equal the multibody reactions (1e-8 of the largest: the
//       same statics, two formulations);
//    c. the tip's displacement is the sum of the parts' contributions and its
//       compliance is symmetric (Maxwell-Betti, round-off: 1e-9).
// 3. A planar linkage lifted into the spatial core (the SPEC §1 lever-chain
//    manipulator with box parts, its chain a tension member of EA = 2e6 N):
//    the spatial assembly equals the planar ElasticAssembly, displacement
//    fields 1e-8 of the largest, the chain's tension and the gripper point's
//    displacement and shares 1e-8 (the same structure: the planar revolute
//    holds the translations and the tilts about x and y, the spatial one the
//    translations and the tilts about f and g, the same span for h = z).
// 4. A slide (an arm on two lands of a sleeve fixed to the ground, pushed by
//    its drive, a payload at the tip, gravity; the sleeve's axis oblique):
//    a serial chain, so the loads the two lands put on the arm add up to the
//    multibody reaction of the slide and its drive (1e-8: the same statics);
//    pushed out until the front land passes the arm's last station: an Error
//    naming the time and the land (the slide beyond its stroke).
// 5. Bad models: a part without the face set of a joint; a joint nobody
//    drives (a mechanism): Errors naming them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Geometry>

#include "../../unit/structure/structure_fixtures.hpp"
#include "../../unit/structure/spatial_fixtures.hpp"
#include "spatial_monolithic_reference.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/loads/slide_stations.hpp"
#include "kinetofem/loads/spatial_link_loads.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/kinematics.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/mechanisms/spatial/from_planar.hpp"
#include "kinetofem/pipeline/part_model.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/spatial_elastic_assembly.hpp"

namespace kinetofem::structure {
namespace {

namespace sp = mech::spatial;
using test::BarSize;
using test::give_mass_of;
using test::kDeg;
using test::slide_model;
using test::spatial_arm;
using test::SlideModel;
using test::SpatialArm;
using test::spatial_bar;

// --- 1. The cantilevered sliding arm -------------------------------------

TEST(SpatialElasticAssembly, ACantileveredSlidingArmBendsAsBeamTheorySays) {
  const BarSize size{.length_m = 1.0, .height_m = 0.05, .thickness_m = 0.03, .cells = {40, 4, 2}};
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 0.7, 0.4).normalized();
  const Eigen::Matrix3d R = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), axis).toRotationMatrix() *
                            Eigen::AngleAxisd(25 * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Vector3d base(0.2, -0.1, 0.3);

  sp::Model model;
  model.name = "sliding arm";
  model.gravity.setZero();
  sp::Body ground;
  ground.name = "ground";
  ground.fixed = true;
  ground.points["base"] = base;
  sp::Body arm;
  arm.name = "arm";
  arm.position = base;
  sp::set_rotation(arm, R);
  arm.points["tip"] = Eigen::Vector3d(size.length_m, 0.0, 0.0);
  model.bodies = {ground, arm};
  model.joints = {sp::make_joint("slide", sp::JointType::Prismatic, "ground", "base", "arm", "origin", axis,
                                 Eigen::Vector3d::UnitX())};
  sp::MotionDrive push;
  push.name = "push";
  push.joint = "slide";
  push.coordinate = sp::DriveCoordinate::Translation;
  push.law = std::make_shared<mech::ConstantVelocityLaw>(0.0);
  model.motion_drives = {push};
  const std::vector<SpatialPart> parts = {spatial_bar("arm", size, {{"slide", "x0"}, {"push", "x0"}})};
  give_mass_of(model, parts);
  const sp::System system(model);
  const sp::Results run = sp::run_kinematics(system, {0.0});

  SpatialAssemblyOptions options;
  options.points = {{"tip", "arm", "tip", "x1"}};
  SpatialElasticAssembly assembly(parts, model, options);
  const SpatialPoseSolution pose = assembly.solve(run.frames.at(0));
  const Eigen::Matrix3d& Rf = run.frames[0].bodies[1].rotation;
  const Eigen::Matrix3d C = Rf.transpose() * pose.point("tip").compliance_m_per_n * Rf;  // bar axes

  const fem::IsotropicMaterial steel = test::steel();
  const double E = steel.youngs_modulus_pa, nu = steel.poisson_ratio, G = E / (2 * (1 + nu));
  const double L = size.length_m, h = size.height_m, t = size.thickness_m, A = h * t;
  const double kappa = 10 * (1 + nu) / (12 + 11 * nu);
  const double across_y = L * L * L / (3 * E * t * h * h * h / 12) + L / (kappa * G * A);
  const double across_z = L * L * L / (3 * E * h * t * t * t / 12) + L / (kappa * G * A);
  const double along = L / (E * A);
  std::printf(
      "tip compliance (bar axes) vs beam theory: y %.5g / %.5g (%+.3f %%), z %.5g / %.5g (%+.3f %%), "
      "x %.5g / %.5g (%+.3f %%)\n",
      C(1, 1), across_y, 100 * (C(1, 1) / across_y - 1), C(2, 2), across_z, 100 * (C(2, 2) / across_z - 1), C(0, 0),
      along, 100 * (C(0, 0) / along - 1));
  EXPECT_NEAR(C(1, 1) / across_y, 1.0, 0.01);  // Timoshenko cantilever, 1 %
  EXPECT_NEAR(C(2, 2) / across_z, 1.0, 0.01);
  EXPECT_NEAR(C(0, 0) / along, 1.0, 0.01);  // bar in tension, 1 %
  // Maxwell-Betti: symmetric to round-off.
  EXPECT_LT((C - C.transpose()).norm(), 1e-9 * C.norm());
  // No loads: the pose's own displacement is zero.
  EXPECT_LT(pose.point("tip").displacement_m.norm(), 1e-15);
}

// --- 2. A spatial two-link arm ---------------------------------------------


TEST(SpatialElasticAssembly, ASpatialArmEqualsTheMonolithicReferenceAndTheMultibodyReactions) {
  const SpatialArm arm = spatial_arm();
  const sp::System system(arm.model);
  const sp::Results run = sp::run_kinematics(system, {0.3, 0.6});
  SpatialAssemblyOptions options;
  options.points = {{"tip", "link2", "tip", "x1"}};
  SpatialElasticAssembly assembly(arm.parts, arm.model, options);
  for (const sp::Frame& frame : run.frames) {
    const SpatialPoseSolution pose = assembly.solve(frame);
    // a. the monolithic reference
    const test::SpatialMonolithicResult reference = test::solve_spatial_monolithic(arm.parts, arm.model, frame);
    EXPECT_LT(reference.relative_residual,
              1e-8);  // the reference itself (SparseLU, 3 refinement steps), as the planar one
    double scale = 0.0, worst = 0.0;
    for (size_t p = 0; p < arm.parts.size(); ++p) {
      scale = std::max(scale, reference.displacement[p].rowwise().norm().maxCoeff());
      worst = std::max(worst, (pose.parts[p].displacement_m - reference.displacement[p]).cwiseAbs().maxCoeff());
    }
    std::printf("t = %.2f s: max displacement %.4g mm, vs monolithic %.2e of it\n", frame.t, 1e3 * scale,
                worst / scale);
    EXPECT_GT(scale, 1e-6);
    EXPECT_LT(worst, 1e-8 * scale);  // the same structure, condensed vs monolithic

    // b. statically determinate: the multibody reactions
    double load = 0.0;
    for (const sp::JointState& j : frame.joints)
      load = std::max({load, j.on_j.force_world.norm(), j.on_j.moment_world.norm() / 0.7});
    for (const sp::JointState& j : frame.joints) {
      const SpatialJointLoad& jl = pose.joint(j.name);
      EXPECT_LT((jl.force_on_j_n - j.on_j.force_world).norm(), 1e-8 * load) << j.name;
      EXPECT_LT((jl.moment_on_j_nm - j.on_j.moment_world).norm(), 1e-8 * load * 0.7) << j.name;
      EXPECT_LT((jl.force_on_i_n - j.on_i.force_world).norm(), 1e-8 * load) << j.name;
    }
    for (size_t d = 0; d < frame.drives.size(); ++d)
      EXPECT_NEAR(pose.drives[d].effort, frame.drives[d].effort, 1e-8 * load * 0.7) << frame.drives[d].name;

    // c. the unit-load split and Maxwell-Betti
    const PointResult& tip = pose.point("tip");
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const PointContribution& c : tip.contributions) sum += c.displacement_m;
    EXPECT_LT((sum - tip.displacement_m).norm(), 1e-9 * tip.displacement_m.norm());
    EXPECT_LT((tip.compliance_m_per_n - tip.compliance_m_per_n.transpose()).norm(),
              1e-9 * tip.compliance_m_per_n.norm());
  }
}

// --- 3. A planar linkage lifted ---------------------------------------------

TEST(SpatialElasticAssembly, APlanarLinkageLiftedIntoTheSpatialCoreGivesThePlanarAssembly) {
  const mech::ManipulatorDefinition def = test::lever_chain_definition();
  mech::MultibodyModel model = mech::make_manipulator_model(def);
  const std::vector<pipeline::Part> parts = test::lever_chain_parts(def, test::steel());
  pipeline::apply_mass_properties(model, parts, Log::quiet());
  const std::vector<double> times = {0.6, 1.4};
  const mech::Results planar_run = mech::run_kinematics(mech::MultibodySystem(model), times);
  const sp::Model lifted = sp::from_planar(model);
  const sp::Results spatial_run = sp::run_kinematics(sp::System(lifted), times);

  AssemblyOptions planar_options;
  planar_options.chains = {{"chain", 2e6}};
  planar_options.points = {{"H", "arm", "H", "x0"}};
  ElasticAssembly planar(parts, model, planar_options);
  std::vector<SpatialPart> spatial_parts;
  for (const pipeline::Part& part : parts) spatial_parts.push_back(spatial_part_of(part));
  SpatialAssemblyOptions options;
  options.chains = planar_options.chains;
  options.points = {{"H", "arm", "H", "x0"}};
  SpatialElasticAssembly spatial(spatial_parts, lifted, options);
  for (size_t k = 0; k < times.size(); ++k) {
    const PoseSolution p = planar.solve(planar_run.frames[k]);
    const SpatialPoseSolution s = spatial.solve(spatial_run.frames[k]);
    double scale = 0.0, worst = 0.0;
    for (size_t q = 0; q < parts.size(); ++q) {
      scale = std::max(scale, p.parts[q].displacement_m.rowwise().norm().maxCoeff());
      worst = std::max(worst, (s.parts[q].displacement_m - p.parts[q].displacement_m).cwiseAbs().maxCoeff());
    }
    const PointResult &hp = p.point("H"), &hs = s.point("H");
    std::printf(
        "t = %.2f s: max displacement %.4g mm, spatial vs planar %.2e of it; chain %.3f / %.3f N; |u_H| %.5g "
        "/ %.5g mm\n",
        times[k], 1e3 * scale, worst / scale, s.chains.at(0).tension_n, p.chain("chain").tension_n,
        1e3 * hs.displacement_m.norm(), 1e3 * hp.displacement_m.norm());
    EXPECT_LT(worst, 1e-8 * scale);  // the same structure, two formulations
    EXPECT_NEAR(s.chains.at(0).tension_n, p.chain("chain").tension_n, 1e-8 * p.chain("chain").tension_n);
    EXPECT_LT((hs.displacement_m - hp.displacement_m).norm(), 1e-8 * hp.displacement_m.norm());
    EXPECT_LT((hs.compliance_m_per_n - hp.compliance_m_per_n).norm(), 1e-8 * hp.compliance_m_per_n.norm());
    ASSERT_EQ(hs.contributions.size(), 3u);  // part.lever, part.arm, chain.chain
    for (const PointContribution& share : hs.contributions) {
      const auto planar_share = std::find_if(hp.contributions.begin(), hp.contributions.end(),
                                             [&](const PointContribution& c) { return c.name == share.name; });
      ASSERT_NE(planar_share, hp.contributions.end()) << share.name;
      EXPECT_LT((share.displacement_m - planar_share->displacement_m).norm(), 1e-8 * hp.displacement_m.norm())
          << share.name;
    }
  }
}

// --- 4. A slide ----------------------------------------------------------------


TEST(SpatialElasticAssembly, TheLandsOfASlideCarryItsMultibodyLoadAndASlideBeyondItsStrokeIsNamed) {
  {
    const SlideModel slide = slide_model(0.1);
    const sp::System system(slide.model);
    const sp::Results run = sp::run_kinematics(system, {0.0, 0.5, 1.0});
    SpatialAssemblyOptions options;
    options.points = {{"tip", "arm", "tip", "x1"}};
    SpatialElasticAssembly assembly(slide.parts, slide.model, options);
    for (const sp::Frame& frame : run.frames) {
      const SpatialPoseSolution pose = assembly.solve(frame);
      const sp::JointState& joint = frame.joints[1];
      const sp::DriveState& drive = frame.drives[0];
      const Eigen::Vector3d force = joint.on_j.force_world + drive.on_j.force_world;
      const Eigen::Vector3d moment = joint.on_j.moment_world + drive.on_j.moment_world +
                                     (drive.on_j.point_world - joint.on_j.point_world).cross(drive.on_j.force_world);
      const SpatialJointLoad& lands = pose.joint("slide");
      std::printf("t = %.2f s: slide load on the arm %.4f N (multibody %.4f N), tip moves %.4g mm\n", frame.t,
                  lands.force_on_j_n.norm(), force.norm(), 1e3 * pose.point("tip").displacement_m.norm());
      EXPECT_LT((lands.force_on_j_n - force).norm(), 1e-8 * force.norm());  // the same statics
      EXPECT_LT((lands.moment_on_j_nm - moment).norm(), 1e-8 * force.norm() * 0.6);
      EXPECT_GT(pose.point("tip").displacement_m.norm(), 1e-6);
    }
  }
  {
    const SlideModel slide = slide_model(-0.2);  // the front land passes the arm's last station
    const sp::System system(slide.model);
    const sp::Results run = sp::run_kinematics(system, {1.0});
    SpatialElasticAssembly assembly(slide.parts, slide.model);
    const std::string message = test::error_of([&] { assembly.solve(run.frames[0]); });
    EXPECT_NE(message.find("t = 1 s"), std::string::npos) << message;
    EXPECT_NE(message.find("slide 'slide'"), std::string::npos) << message;
    EXPECT_NE(message.find("front land"), std::string::npos) << message;
  }
}

// --- 5. Bad models ---------------------------------------------------------

TEST(SpatialElasticAssembly, APartWithoutTheFaceSetOfAJointIsNamed) {
  SpatialArm arm = spatial_arm();
  arm.parts[1].attachments.joints = {{"J2", "x0"}};  // d2 missing
  const std::string message = test::error_of([&] { SpatialElasticAssembly(arm.parts, arm.model); });
  EXPECT_NE(message.find("link2"), std::string::npos) << message;
  EXPECT_NE(message.find("drive 'd2'"), std::string::npos) << message;
}

TEST(SpatialElasticAssembly, AMechanismIsRefusedNamingTheBodyNothingHolds) {
  SpatialArm arm = spatial_arm();
  const sp::System system(arm.model);
  const sp::Results run = sp::run_kinematics(system, {0.3});
  arm.model.motion_drives.pop_back();  // J2 free: link2 swings
  arm.parts[0].attachments.joints.pop_back();
  arm.parts[1].attachments.joints.pop_back();
  SpatialAssemblyOptions options;
  options.load_check_tolerance = std::numeric_limits<double>::infinity();  // the frame still has d2's loads
  SpatialElasticAssembly assembly(arm.parts, arm.model, options);
  sp::Frame frame = run.frames[0];
  frame.drives.pop_back();
  const std::string message = test::error_of([&] { assembly.solve(frame); });
  EXPECT_NE(message.find("mechanism"), std::string::npos) << message;
  EXPECT_NE(message.find("link2"), std::string::npos) << message;
}

}  // namespace
}  // namespace kinetofem::structure
