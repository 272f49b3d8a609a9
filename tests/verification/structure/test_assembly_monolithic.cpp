// Verification 1: the condensed elastic assembly (structure/elastic_assembly.hpp)
// against the monolithic reference (monolithic_reference.hpp: all parts' full
// stiffness in one sparse system, the joints as Lagrange constraints on the
// coupling definitions, SparseLU), on the two-link arm of structure_fixtures.hpp
// (two HEX20 bars 300 x 40 x 20 mm, 10 x 2 x 1 cells) at three poses of its
// motion (t = 0.1, 0.25, 0.4 s: gravity, d'Alembert inertia, a 3 kg payload).
//
// Reference and tolerance: both solve the same discrete model exactly (same
// meshes, couplings and loads), so they agree to the round-off of two direct
// solves of systems with condition ~1e10: 1e-8 of the largest displacement.
#include <gtest/gtest.h>

#include "../../unit/structure/structure_fixtures.hpp"
#include "kinetofem/mechanisms/multibody/kinematics.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "monolithic_reference.hpp"

namespace kinetofem::structure {
namespace {

struct ArmSetup {
  mech::MultibodyModel model;
  std::vector<pipeline::Part> parts;
  std::vector<mech::Frame> frames;
};

ArmSetup two_link_motion() {
  ArmSetup s;
  s.parts = test::two_link_parts();
  s.model = test::two_link_arm();
  pipeline::apply_mass_properties(s.model, s.parts, Log::quiet());
  s.frames = mech::run_kinematics(mech::MultibodySystem(s.model), {0.1, 0.25, 0.4}).frames;
  return s;
}

double max_abs(const fem::DisplacementField& u) { return u.cwiseAbs().maxCoeff(); }

void expect_matches_monolithic(const std::vector<pipeline::Part>& parts, const mech::MultibodyModel& model,
                               const std::vector<mech::Frame>& frames, const AssemblyOptions& options,
                               const std::map<std::string, double>& drive_stiffness, const char* what) {
  ElasticAssembly assembly(parts, model, options);
  const std::vector<PoseSolution> poses = assembly.solve(frames);
  ASSERT_EQ(poses.size(), frames.size());
  for (size_t f = 0; f < frames.size(); ++f) {
    const test::MonolithicResult ref = test::solve_monolithic(parts, model, frames[f], drive_stiffness);
    EXPECT_LT(ref.relative_residual, 1e-8) << what;  // the reference itself (SparseLU, 3 refinement steps)
    EXPECT_EQ(poses[f].rank, poses[f].unknowns);
    double scale = 0.0, worst = 0.0;
    for (size_t p = 0; p < parts.size(); ++p) scale = std::max(scale, max_abs(ref.displacement[p]));
    ASSERT_GT(scale, 0.0);
    for (size_t p = 0; p < parts.size(); ++p) {
      const fem::DisplacementField& u = poses[f].part(parts[p].body()).displacement_m;
      worst = std::max(worst, max_abs(u - ref.displacement[p]));
    }
    ::testing::Test::RecordProperty(std::string(what) + "_pose" + std::to_string(f) + "_relative_error",
                                    std::to_string(worst / scale));
    std::printf("  %s, t = %.2f s: max |u| %.4e m, condensed vs monolithic %.2e relative\n", what, frames[f].t, scale,
                worst / scale);
    EXPECT_LT(worst / scale, 1e-8) << what << " at t = " << frames[f].t;
  }
}

TEST(ElasticAssemblyMonolithic, DeterminateTwoLinkArmMatchesAtThreePoses) {
  const ArmSetup s = two_link_motion();
  expect_matches_monolithic(s.parts, s.model, s.frames, {}, {}, "determinate");
}

TEST(ElasticAssemblyMonolithic, IndeterminateArmWithCompliantDriveMatchesAtThreePoses) {
  // The same arm with link2's tip also pinned to the ground (joint "J3": a
  // closed loop frame-link1-link2-frame, statically indeterminate) and drive
  // d2 a torsional spring of 2000 N m/rad instead of a constraint. The frames
  // come from the determinate model (same bodies); J3's ground point plays no
  // part (the ground does not move).
  ArmSetup s = two_link_motion();
  mech::MultibodyModel model = s.model;
  model.bodies[0].points["anchor"] = {0.0, 0.0};
  model.joints.push_back(mech::make_revolute("J3", "frame", "anchor", "link2", "tip"));
  std::vector<pipeline::Part> parts = s.parts;
  parts[1].attachments.joints.push_back({"J3", "x1"});
  AssemblyOptions options;
  options.drives = {{"d2", 2000.0}};
  expect_matches_monolithic(parts, model, s.frames, options, {{"d2", 2000.0}}, "indeterminate");
}

}  // namespace
}  // namespace kinetofem::structure
