// The bundled STEP slider-crank with the elastic assembly on
// (cases/slider_crank_parts/assembly.toml) through the whole chain: the
// crank and rod meshed from their STEP files, the motion, their stress, the
// assembly (the rigid slider on its guide, the servo's drive train), the
// vibration and the fatigue.
//
// References: the linkage is statically determinate in the plane, so each
// part's peak von Mises stress in the assembly equals the per-part stage's
// (1e-3: the out-of-plane loads, split equally between the pins by the
// per-part analysis, are the only difference; measured 5e-6 on the crank at
// 6 mm); the guide holds the slider on its line, so
// C moves along x only (1e-9 of its motion); its deflection splits into the
// crank's, the rod's and the drive train's shares, which add up to it
// (1e-9: the unit-load method's sum).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "kinetofem/testing/linkage_run.hpp"

namespace kinetofem::app {
namespace {

TEST(SliderCrankPartsAssembly, RunsThroughTheWholeChain) {
  const auto [output_dir, run] = testing::run_linkage_quietly("cases/slider_crank_parts/assembly.toml",
                                                              "kinetofem_slider_crank_assembly", {"mesh.element_size_mm=6"});
  ASSERT_EQ(run.parts.size(), 2u);
  ASSERT_TRUE(run.assembly.has_value());
  EXPECT_EQ(run.assembly->indeterminacy.in_plane, 0);
  for (const auto& peak : run.assembly->parts) {
    const auto own = std::find_if(run.parts.begin(), run.parts.end(), [&](const auto& p) { return p.body == peak.body; });
    ASSERT_NE(own, run.parts.end()) << peak.body;
    std::printf("  %s: peak von Mises %.6f MPa in the assembly, %.6f MPa per part\n", peak.body.c_str(),
                peak.max_von_mises_pa * 1e-6, own->peak_von_mises_pa * 1e-6);
    EXPECT_NEAR(peak.max_von_mises_pa, own->peak_von_mises_pa, 1e-3 * own->peak_von_mises_pa) << peak.body;
  }
  ASSERT_EQ(run.assembly->points.size(), 1u);
  const pipeline::PointSummary& c = run.assembly->points[0];
  const Eigen::Vector3d u = c.displacement_at_max_m;
  EXPECT_GT(std::abs(u.x()), 0.0);
  EXPECT_LT(std::abs(u.y()), 1e-9 * std::abs(u.x()));
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  bool drive = false;
  for (const auto& share : c.contributions_at_max) {
    sum += share.displacement_m;
    drive = drive || share.name == "drive.motor";
  }
  EXPECT_TRUE(drive);
  EXPECT_LT((sum - u).norm(), 1e-9 * u.norm());
  ASSERT_TRUE(run.vibration.has_value());
  EXPECT_GT(run.vibration->lowest_first_hz, 0.0);
  ASSERT_EQ(run.fatigue.size(), 2u);
  for (const auto& f : run.fatigue) EXPECT_GT(f.utilization.maxCoeff(), 0.0) << f.body;
  std::printf("  C: %.4e m along the guide; first frequency %.1f .. %.1f Hz\n", u.x(), run.vibration->lowest_first_hz,
              run.vibration->highest_first_hz);
  std::filesystem::remove_all(output_dir);
}

}  // namespace
}  // namespace kinetofem::app
