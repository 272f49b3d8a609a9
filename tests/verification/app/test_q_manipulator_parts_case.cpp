// The bundled SPEC §4 Q-manipulator with FE parts (cases/q_manipulator_parts)
// through the whole chain: the case file, the parametric .geo parts, the
// dynamics with the belt, the transmission's loads on both links and their
// stress over the motion, the elastic assembly with the belt as a torsional
// member, the results file.
// References: H against SPEC §4's closed form (mech::QManipulator, the
// source's i = 4) at every output time, 1e-9 of l1; the belt's moments
// in the results file equal the frames' (the write is exact); every part's
// loads close (the stress stage refuses them otherwise, 1e-6 of their size);
// in the assembly the belt's largest moment is the dynamics' (1e-6, the
// assembly's own check) and its twist that moment over the hand stiffness of
// the case's chain, k = EA r^2 / b (one span, no preload; EA the ISO 606
// 08B-1 default 5.0e6 N, r = 20 mm, b = 200 mm): 1e-9 relative.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <Eigen/Geometry>
#include <fmt/format.h>

#include "kinetofem/mechanisms/q_manipulator.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/testing/linkage_run.hpp"

namespace kinetofem::app {
namespace {

TEST(QManipulatorPartsCase, HTracesSpec4sRoseAndTheBeltLoadsBothParts) {
  const auto [output_dir, run] =
      testing::run_linkage_quietly("cases/q_manipulator_parts/case.toml", "kinetofem_q_manipulator_parts");
  const double l1 = 0.2, l2 = 0.2;  // m, the case's links (SPEC §4's rose)
  const mech::QManipulator rose = mech::make_two_link_q_manipulator(l1, l2, 4.0);
  ASSERT_EQ(run.model.transmissions.size(), 1u);
  EXPECT_EQ(run.model.transmissions[0].ratio, -4.0);  // ours is -i (docs/transmissions.md)
  int link2 = -1;
  for (std::size_t b = 0; b < run.model.bodies.size(); ++b)
    if (run.model.bodies[b].name == "link2") link2 = int(b);
  ASSERT_GE(link2, 0);
  double worst = 0.0, peak_moment = 0.0;
  for (const auto& f : run.results.frames) {
    const mech::BodyFrame& arm = f.bodies[std::size_t(link2)];
    const Eigen::Vector2d h = arm.q.head<2>() + Eigen::Rotation2Dd(arm.q.z()) * Eigen::Vector2d(l2, 0.0);
    worst = std::max(worst, (h - rose.point_h(f.drives.at(0).s).p).norm());
    peak_moment = std::max(peak_moment, std::abs(f.transmissions.at(0).moment_output_Nm));
  }
  fmt::print("q_manipulator_parts: |H - H_closed| {:.3e} m over {} frames; belt moment up to {:.4g} N m; "
             "drift {:.3e} of l1\n", worst, run.results.frames.size(), peak_moment,
             run.results.summary.max_drift_relative);
  EXPECT_LT(worst, 1e-9 * l1);
  EXPECT_LT(run.results.summary.max_drift_relative, 1e-8);
  EXPECT_GT(peak_moment, 0.5);  // the belt carries link 2 and the payload
  ASSERT_EQ(run.parts.size(), 2u);
  for (const auto& part : run.parts) {
    EXPECT_GT(part.peak_von_mises_pa, 0.0) << part.body;
    EXPECT_LT(part.worst_equilibrium_residual, 1e-6) << part.body;  // the transmission's moments included
  }

  ASSERT_TRUE(run.assembly.has_value());
  ASSERT_EQ(run.assembly->transmissions.size(), 1u);
  const auto& belt = run.assembly->transmissions[0];
  const double k_hand = 5.0e6 * 0.02 * 0.02 / 0.2;  // N m/rad
  EXPECT_NEAR(belt.max_moment_nm, peak_moment, 1e-6 * peak_moment);
  EXPECT_NEAR(belt.max_twist_rad, belt.max_moment_nm / k_hand, 1e-9 * belt.max_moment_nm / k_hand);
  ASSERT_EQ(run.assembly->points.size(), 1u);
  EXPECT_GT(run.assembly->points[0].max_displacement_m, 0.0);

  const auto file = post::ResultsFile::open(run.results_file);
  const auto force = file.read_history("transmission.belt.force");
  ASSERT_EQ(std::size_t(force.values.rows()), run.results.frames.size());
  for (std::size_t k = 0; k < run.results.frames.size(); ++k)
    EXPECT_EQ(force.values(Eigen::Index(k), 0), run.results.frames[k].transmissions[0].force_N);
  std::filesystem::remove_all(output_dir);
}

}  // namespace
}  // namespace kinetofem::app
