// Pins in contact in the elastic assembly (ElasticAssembly with joint
// attachments of loads::BoreLoad::Contact; docs/contact.md, "In the elastic
// assembly").
//
// The double pendulum of two-bore links (testing/pendulum_links.hpp) is
// statically determinate (two pins, two rigid drives): its joint loads are
// the multibody reactions whatever the stiffness, so each link in the
// assembly carries exactly the loads of the per-link analysis, and the
// contact pressure on each bore must equal loads::solve_contact_over_motion's
// (the same QP on the same factorization; reference: the per-link contact,
// itself verified in tests/verification/loads/test_pin_contact.cpp).
// Tolerances: pressures 1e-6 of the peak (two QPs solved to 1e-10 of their
// scales, through a dense system of ~100 unknowns); reciprocity of the
// contact responses (Maxwell-Betti) 1e-9.
#include <gtest/gtest.h>

#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/loads/link_contact.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/testing/pendulum_links.hpp"

namespace kinetofem::structure {
namespace {

using loads::BoreLoad;
using testing::double_pendulum;
using testing::even_times;
using testing::two_bore_link_model;

// The two links of the double pendulum, every pin in contact: J1 with
// `clearance_1`, J2 with `clearance_2` (radial, m).
std::vector<Part> pendulum_parts(double clearance_1, double clearance_2, BoreLoad pins = BoreLoad::Contact) {
  std::vector<Part> parts(2);
  parts[0].label = "link1";
  parts[0].attachments = {"link1", nullptr, {{"J1", "bore_1", pins, clearance_1}, {"J2", "bore_2", pins, clearance_2}},
                          {}, {{"D1", "bore_1"}, {"D2", "bore_2"}}};
  parts[1].label = "link2";
  parts[1].attachments = {"link2", nullptr, {{"J2", "bore_1", pins, clearance_2}}, {}, {{"D2", "bore_1"}}};
  parts[1].attachments.point_masses = {{"tip", "bore_2"}};
  for (Part& part : parts) {
    part.model = two_bore_link_model();
    part.mass = fem::mass_properties(part.model.mesh, part.model.material);
  }
  return parts;
}

std::vector<mech::Frame> frames_of(const mech::MultibodyModel& model, const std::vector<double>& times) {
  return mech::run_kinematics(mech::MultibodySystem(model), times).frames;
}

TEST(AssemblyContact, OnADeterminateLinkageEachBoreCarriesThePerLinkContact) {
  const mech::MultibodyModel model = double_pendulum();
  const auto frames = frames_of(model, even_times(0.5, 10));
  const std::vector<Part> parts = pendulum_parts(0.0, 30e-6);
  ElasticAssembly assembly(parts, model);
  const std::vector<PoseSolution> poses = assembly.solve(frames);
  ASSERT_EQ(poses.size(), frames.size());
  ASSERT_EQ(poses.front().contacts.size(), 3u);  // link1: J1, J2; link2: J2

  const Log log = Log::quiet();
  double worst = 0.0, peak = 0.0, reciprocity = 0.0;
  for (const Part& part : parts) {
    fem::FeModel supported = supported_model(part);
    loads::LinkDefinition link = part.attachments;
    link.model = &supported;
    const loads::LinkLoads link_loads(link, model);
    fem::LinearStaticAnalysis analysis(supported, log);
    const loads::LinkContactHistory reference = loads::solve_contact_over_motion(analysis, link_loads, frames, log);
    for (const loads::BoreContactHistory& bore : reference.bores)
      for (size_t t = 0; t < frames.size(); ++t) {
        const BoreContactResult* found = nullptr;
        for (const BoreContactResult& c : poses[t].contacts)
          if (c.body == part.body() && c.joint == bore.joint) found = &c;
        ASSERT_NE(found, nullptr) << part.body() << " " << bore.joint;
        ASSERT_EQ(found->pressure_pa.size(), bore.pressure_pa.rows());
        worst = std::max(worst, (found->pressure_pa - bore.pressure_pa.col(Eigen::Index(t))).cwiseAbs().maxCoeff());
        peak = std::max(peak, bore.pressure_pa.col(Eigen::Index(t)).maxCoeff());
      }
  }
  for (const PoseSolution& pose : poses) reciprocity = std::max(reciprocity, pose.contact.reciprocity_error);
  std::printf("assembly vs per-link contact: worst %.2e of the peak %.4g MPa; reciprocity %.1e; %d corners, "
              "%.2f ms per pose for the contact\n",
              worst / peak, peak / 1e6, reciprocity, assembly.statistics().contact_corners,
              1e3 * assembly.statistics().contact_seconds / double(frames.size()));
  ASSERT_GT(peak, 1e5);
  EXPECT_LE(worst, 1e-6 * peak);
  EXPECT_LE(reciprocity, 1e-9);
}

TEST(AssemblyContact, TheContactCarriesTheJointLoadsAndThePointSplitAddsUp) {
  // Equilibrium: each bore's contact force equals the joint load on its side
  // (the multibody reaction, a determinate linkage; 1e-8 of the force), no
  // penetration beyond 1e-12 m. The unit-load split of the tip's
  // displacement (parts, then each pin's play) adds up to it (Maxwell-Betti:
  // 1e-9 of its size), and the play is the difference to the couplings'
  // model up to the parts' own share of it.
  const mech::MultibodyModel model = double_pendulum();
  const auto frames = frames_of(model, even_times(0.5, 4));
  AssemblyOptions options;
  options.points = {{"tip", "link2", "B2", "bore_2"}};
  mech::MultibodyModel with_point = model;
  with_point.bodies[2].points["B2"] = {0.24, 0.0};
  ElasticAssembly assembly(pendulum_parts(20e-6, 50e-6), with_point, options);
  const std::vector<PoseSolution> poses = assembly.solve(frames);
  double worst = 0.0, split = 0.0, play = 0.0;
  for (size_t t = 0; t < frames.size(); ++t) {
    const PoseSolution& pose = poses[t];
    for (const BoreContactResult& c : pose.contacts) {
      const JointLoad& jl = pose.joint(c.joint);
      const mech::JointFrame* jf = nullptr;
      for (const auto& j : frames[t].joints)
        if (j.name == c.joint) jf = &j;
      ASSERT_NE(jf, nullptr);
      const bool on_i = jl.body_i == c.body;
      const Eigen::Vector2d reaction = on_i ? jf->on_i.force_world : jf->on_j.force_world;
      // The contact force in world axes (the part's body axes rotated).
      const double theta = frames[t].bodies[c.body == "link1" ? 1 : 2].q.z();
      const Eigen::Vector3d force = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ()) * c.state.force_n;
      worst = std::max(worst, (force.head<2>() - reaction).norm() / reaction.norm());
    }
    EXPECT_LE(pose.contact.worst_penetration_m, 1e-12);
    const PointResult& tip = pose.point("tip");
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), plays = Eigen::Vector3d::Zero();
    for (const PointContribution& c : tip.contributions) {
      sum += c.displacement_m;
      if (c.name.rfind("play.", 0) == 0) plays += c.displacement_m;
    }
    split = std::max(split, (sum - tip.displacement_m).norm() / tip.displacement_m.norm());
    play = std::max(play, plays.norm());
    // With 20 and 50 um of clearance the tip moves by more than the couplings'
    // model says: the pins' play (a lever of 0.48 m over bores 0.24 m apart).
    EXPECT_GT((tip.displacement_m - tip.coupling_displacement_m).norm(), 10e-6);
  }
  std::printf("contact force vs joint load: worst %.2e; split vs displacement %.2e; largest play %.3g um\n", worst,
              split, 1e6 * play);
  EXPECT_LE(worst, 1e-8);
  EXPECT_LE(split, 1e-9);
  EXPECT_GT(play, 20e-6);
}

}  // namespace
}  // namespace kinetofem::structure

namespace kinetofem::structure {
namespace {

std::vector<Part> parallelogram_parts(double clearance) {
  const BoreLoad contact = BoreLoad::Contact;
  std::vector<Part> parts(3);
  parts[0].attachments = {"link1", nullptr, {{"J1", "bore_1", contact, clearance}, {"J2", "bore_2", contact, clearance}},
                          {}, {{"D1", "bore_1"}}};
  parts[1].attachments = {"link2", nullptr, {{"J2", "bore_1", contact, clearance}, {"J3", "bore_2", contact, clearance}}};
  parts[1].attachments.point_masses = {{"mass", "bore_2"}};
  parts[2].attachments = {"link3", nullptr, {{"J4", "bore_1", contact, clearance}, {"J3", "bore_2", contact, clearance}}};
  for (Part& part : parts) {
    part.label = part.attachments.body;
    part.model = two_bore_link_model();
    part.mass = fem::mass_properties(part.model.mesh, part.model.material);
  }
  return parts;
}

TEST(AssemblyContact, AnIndeterminateLoopKeepsEquilibriumAndItsSplit) {
  // References: the in-plane joint loads of a linkage determinate in the
  // plane are the multibody reactions whatever the contact (1e-8 of the
  // largest); each bore's contact force is its side's joint load (the
  // contact carries the released tie exactly; 1e-8); no tension, no
  // penetration beyond 1e-12 m; the unit-load split of the mass point's
  // displacement adds up to it (Maxwell-Betti, 1e-9); the two contact
  // responses are reciprocal (1e-9).
  const mech::MultibodyModel model = testing::parallelogram();
  const auto frames = frames_of(model, even_times(0.5, 4));
  AssemblyOptions options;
  options.points = {{"mass", "link2", "B2", "bore_2"}};
  ElasticAssembly assembly(parallelogram_parts(20e-6), model, options);
  const std::vector<PoseSolution> poses = assembly.solve(frames);
  ASSERT_GT(poses.front().indeterminacy.out_of_plane, 0);
  ASSERT_EQ(poses.front().indeterminacy.in_plane, 0);
  double reaction = 0.0, carried = 0.0, scale = 0.0, split = 0.0, reciprocity = 0.0;
  for (size_t t = 0; t < frames.size(); ++t) {
    const PoseSolution& pose = poses[t];
    for (const auto& jf : frames[t].joints) {
      const JointLoad& jl = pose.joint(jf.name);
      scale = std::max({scale, jf.on_i.force_world.norm(), jf.on_j.force_world.norm()});
      reaction = std::max({reaction, (jl.force_on_i_n.head<2>() - jf.on_i.force_world).norm(),
                           (jl.force_on_j_n.head<2>() - jf.on_j.force_world).norm()});
    }
    for (const BoreContactResult& c : pose.contacts) {
      const JointLoad& jl = pose.joint(c.joint);
      const Eigen::Vector3d on_side = jl.body_i == c.body ? jl.force_on_i_n : jl.force_on_j_n;
      int body = 0;
      for (size_t b = 0; b < model.bodies.size(); ++b)
        if (model.bodies[b].name == c.body) body = int(b);
      const Eigen::Vector3d force =
          Eigen::AngleAxisd(frames[t].bodies[size_t(body)].q.z(), Eigen::Vector3d::UnitZ()) * c.state.force_n;
      carried = std::max(carried, (force.head<2>() - on_side.head<2>()).norm());
      EXPECT_GE(c.pressure_pa.minCoeff(), 0.0);
    }
    EXPECT_LE(pose.contact.worst_penetration_m, 1e-12);
    reciprocity = std::max(reciprocity, pose.contact.reciprocity_error);
    const PointResult& point = pose.point("mass");
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const PointContribution& c : point.contributions) sum += c.displacement_m;
    split = std::max(split, (sum - point.displacement_m).norm() / point.displacement_m.norm());
  }
  std::printf("indeterminate loop: in-plane loads vs reactions %.2e, contact vs joint load %.2e (of %.4g N), split "
              "%.2e, reciprocity %.1e, %d poses by the fallback\n",
              reaction / scale, carried / scale, scale, split, reciprocity,
              assembly.statistics().contact_interior_point_poses);
  EXPECT_LE(reaction, 1e-8 * scale);
  EXPECT_LE(carried, 1e-8 * scale);
  EXPECT_LE(split, 1e-9);
  EXPECT_LE(reciprocity, 1e-9);
}

}  // namespace
}  // namespace kinetofem::structure
