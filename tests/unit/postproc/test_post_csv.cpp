// CSV export: header rows with units, and values (converted to mm / MPa) that
// match the synthetic results file cell by cell.
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/csv_export.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "post_test_results.hpp"
#include "postproc_test_meshes.hpp"

namespace kinetofem::post {
namespace {

using testing::SyntheticMotion;
using Table = std::vector<std::vector<std::string>>;

Table read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in) << path;
  Table rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    rows.push_back(cells);
  }
  return rows;
}

size_t column(const Table& t, const std::string& name) {
  const auto& h = t.front();
  const auto it = std::find(h.begin(), h.end(), name);
  EXPECT_NE(it, h.end()) << "no column " << name;
  return size_t(it - h.begin());
}

TEST(PostCsv, HotSpotsHeaderAndRowsInMillimetresAndMegapascals) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  write_hot_spots_csv(dir / "hot.csv", find_hot_spots(max_envelopes(r), {.count = 3}));
  const Table t = read_csv(dir / "hot.csv");
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t[0], (std::vector<std::string>{"rank", "body", "node", "x [mm]", "y [mm]", "z [mm]", "step",
                                            "time [s]", "von_mises [MPa]", "solid", "seam"}));
  EXPECT_EQ(t[1][0], "1");
  EXPECT_EQ(t[1][1], "beam");
  EXPECT_EQ(std::stoll(t[1][2]), SyntheticMotion::kBeamPeak);
  EXPECT_NEAR(std::stod(t[1][3]), 50.0, 1e-9);
  EXPECT_NEAR(std::stod(t[1][4]), 0.0, 1e-9);
  EXPECT_EQ(t[1][6], "2");
  EXPECT_NEAR(std::stod(t[1][7]), 0.2, 1e-12);
  EXPECT_NEAR(std::stod(t[1][8]), 300.0, 1e-6);
  EXPECT_EQ(t[2][1], "plate");
  EXPECT_NEAR(std::stod(t[2][8]), 250.0, 1e-6);
  EXPECT_NEAR(std::stod(t[3][3]), 150.0, 1e-9);
  EXPECT_NEAR(std::stod(t[3][5]), 10.0, 1e-9);
}

TEST(PostCsv, StaticHotSpotHasAnEmptyTime) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_static(dir.path()));
  write_hot_spots_csv(dir / "hot.csv", find_hot_spots(max_envelopes(r), {.count = 1}));
  const Table t = read_csv(dir / "hot.csv");
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[1][6], "");
  EXPECT_EQ(t[1][7], "");
  EXPECT_NEAR(std::stod(t[1][8]), 27.5, 1e-6);  // 25 MPa (1 + 0.1)
}

TEST(PostCsv, NodeHistoryAndMechanismHistories) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  write_history_csv(dir / "h.csv", node_history(r, "beam", "displacement", 20));
  const Table h = read_csv(dir / "h.csv");
  ASSERT_EQ(h.size(), 6u);  // header + 5 steps
  EXPECT_EQ(h[0], (std::vector<std::string>{"time [s]", "displacement_x [mm]", "displacement_y [mm]",
                                            "displacement_z [mm]"}));
  EXPECT_NEAR(std::stod(h[5][0]), 0.4, 1e-12);
  EXPECT_NEAR(std::stod(h[5][2]), -0.05, 1e-12);  // -1e-5 m * 5 at x = 200 mm

  write_mechanism_csv(dir / "m.csv", r);
  const Table m = read_csv(dir / "m.csv");
  ASSERT_EQ(m.size(), 22u);  // header + 21 times
  EXPECT_EQ(m[0], (std::vector<std::string>{"time [s]", "chain_tension [N]", "drive_torque [N*m]",
                                            "gripper_point_H_x [mm]", "gripper_point_H_y [mm]",
                                            "reaction_A0_on_lever_x [N]", "reaction_A0_on_lever_y [N]"}));
  EXPECT_NEAR(std::stod(m[11][0]), 0.2, 1e-12);
  EXPECT_NEAR(std::stod(m[11][1]), 800.0, 1e-6);  // 500 + 300 sin(pi/2)
  EXPECT_NEAR(std::stod(m[11][2]), 100.0, 1e-6);
  EXPECT_NEAR(std::stod(m[1][3]), 500.0, 1e-6);   // H starts at (0.5, 0) m
  EXPECT_NEAR(std::stod(m[11][6]), 400.0, 1e-6);
}

TEST(PostCsv, BodyFieldsWithStoredAndRecomputedEnvelopes) {
  testing::TemporaryDirectory dir;
  const auto r = ResultsFile::open(testing::write_synthetic_motion(dir.path()));
  write_body_fields_csv(dir / "beam.csv", r, "beam");
  const Table beam = read_csv(dir / "beam.csv");
  ASSERT_EQ(beam.size(), 1u + 21 * 3 * 2);
  const size_t row = 1 + size_t(SyntheticMotion::kBeamPeak);
  EXPECT_EQ(beam[row][0], std::to_string(SyntheticMotion::kBeamPeak));
  EXPECT_NEAR(std::stod(beam[row][column(beam, "x [mm]")]), 50.0, 1e-9);
  EXPECT_NEAR(std::stod(beam[row][column(beam, "static_von_mises [MPa]")]), 1.0, 1e-9);
  EXPECT_NEAR(std::stod(beam[row][column(beam, "von_mises_max [MPa]")]), 300.0, 1e-6);
  EXPECT_NEAR(std::stod(beam[row][column(beam, "von_mises_max_time [s]")]), 0.2, 1e-12);

  write_body_fields_csv(dir / "plate.csv", r, "plate");  // envelope recomputed from the series
  const Table plate = read_csv(dir / "plate.csv");
  const size_t prow = 1 + size_t(SyntheticMotion::plate_peak());
  EXPECT_NEAR(std::stod(plate[prow][column(plate, "von_mises_max [MPa]")]), 250.0, 1e-6);
  EXPECT_NEAR(std::stod(plate[prow][column(plate, "von_mises_max_time [s]")]), 0.1, 1e-12);
}

TEST(PostCsv, UnwritableFileIsAnErrorNamingIt) {
  testing::TemporaryDirectory dir;
  try {
    write_hot_spots_csv(dir / "missing_dir" / "hot.csv", {});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing_dir/hot.csv"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kinetofem::post
