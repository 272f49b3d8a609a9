// A `linkage` case whose ground carries a frame part (tests/data/
// linkage_frame_part: the SPEC §1 lever-chain as a linkage with the preset's
// parametric lever and arm, standing on a base plate held at its foot, whose
// bores carry the pivot A0, the lever drive and the chain's hinge B0) runs
// through the whole chain: the frame's mass is printed, not put into the
// dynamics; its stress over the motion comes from the ground sides of the
// joints and drive plus its weight, held on its foundation; the elastic
// assembly adds its deformation to H's and names it in the split.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/linkage_job.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/testing/linkage_run.hpp"

namespace kinetofem::app {
namespace {

namespace fs = std::filesystem;

TEST(LinkageFramePart, LeverChainOnABasePlateRunsAndTheFrameIsInTheSplit) {
  const auto [output_dir, run] =
      testing::run_linkage_quietly("tests/data/linkage_frame_part/case.toml", "kinetofem_linkage_frame_part");

  // The ground carries no mass in the dynamics.
  const auto ground = std::find_if(run.model.bodies.begin(), run.model.bodies.end(),
                                   [](const mech::Body& b) { return b.name == "frame"; });
  ASSERT_NE(ground, run.model.bodies.end());
  EXPECT_EQ(ground->mass_kg, 0.0);

  // The frame's own stress over the motion, and the assembly's.
  const auto frame = std::find_if(run.parts.begin(), run.parts.end(), [](const auto& p) { return p.body == "frame"; });
  ASSERT_NE(frame, run.parts.end());
  EXPECT_GT(frame->peak_von_mises_pa, 0.0);
  ASSERT_TRUE(run.assembly.has_value());
  const pipeline::AssemblySummary& a = *run.assembly;
  const auto peak = std::find_if(a.parts.begin(), a.parts.end(), [](const auto& p) { return p.body == "frame"; });
  ASSERT_NE(peak, a.parts.end());
  // The lever-chain is statically determinate: the joint loads on the frame
  // are the multibody reactions in both analyses, so its von Mises peaks
  // agree to round-off (both hold it on the same foundation).
  std::printf("  frame: peak von Mises %.6f MPa per part, %.6f MPa in the assembly\n", frame->peak_von_mises_pa * 1e-6,
              peak->max_von_mises_pa * 1e-6);
  EXPECT_NEAR(peak->max_von_mises_pa, frame->peak_von_mises_pa, 1e-6 * frame->peak_von_mises_pa);

  // H's split names the frame and adds up to H's displacement.
  ASSERT_EQ(a.points.size(), 1u);
  const pipeline::PointSummary& h = a.points.front();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero(), from_frame = Eigen::Vector3d::Zero();
  for (const auto& contribution : h.contributions_at_max) {
    sum += contribution.displacement_m;
    if (contribution.name == "part.frame") from_frame = contribution.displacement_m;
  }
  std::printf("  H: %.6e m; the frame's share %.6e m along it; split sum error %.1e\n", h.max_displacement_m,
              from_frame.dot(h.displacement_at_max_m.normalized()), (sum - h.displacement_at_max_m).norm());
  EXPECT_LT((sum - h.displacement_at_max_m).norm(), 1e-10 * h.max_displacement_m);
  EXPECT_GT(from_frame.norm(), 1e-3 * h.max_displacement_m);

  // The results file holds the frame like any part, and its assembly field.
  const auto file = post::ResultsFile::open(run.results_file);
  const auto bodies = file.bodies();
  for (const std::string body : {"frame", "assembly.frame"})
    EXPECT_NE(std::find(bodies.begin(), bodies.end(), body), bodies.end()) << body;
  fs::remove_all(output_dir);
}

}  // namespace
}  // namespace kinetofem::app
