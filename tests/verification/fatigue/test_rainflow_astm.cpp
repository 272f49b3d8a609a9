// Rainflow counting against the worked example of ASTM E1049-85 (reapproved
// 2011), section 5.4.4 "Rainflow Counting", fig. 6: the history
//   A..I = -2, 1, -3, 5, -1, 3, -4, 4, -2   (units of stress)
// whose rainflow count in the standard is
//   range 3: 0.5   4: 1.5   6: 0.5   8: 1.0   9: 0.5    (10, 7, 5: none)
// The same table is encoded in the tests of the Python package `rainflow`
// (iamlikeme/rainflow, tests/test_rainflow.py, "Load series and corresponding
// cycle counts from ASTM E1049-85"). Counts and ranges are exact (small
// integers times 1 MPa are exact in binary floating point).
#include <gtest/gtest.h>

#include <vector>

#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/rainflow.hpp"

namespace kinetofem::fatigue {
namespace {

std::vector<double> astm_history_pa() {
  std::vector<double> h = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
  for (double& v : h) v *= units::kMpa;
  return h;
}

TEST(RainflowAstmE1049, Fig6HistoryCountsTheStandardsTable) {
  const std::vector<Cycle> cycles = rainflow_count(astm_history_pa());
  const std::vector<RangeCount> merged = merge_ranges(cycles);
  const std::vector<RangeCount> expected = {
      {3e6, 0.5}, {4e6, 1.5}, {6e6, 0.5}, {8e6, 1.0}, {9e6, 0.5}};
  ASSERT_EQ(merged.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(merged[i].range_pa, expected[i].range_pa) << i;
    EXPECT_EQ(merged[i].count, expected[i].count) << i;
  }
  EXPECT_EQ(total_count(cycles), 4.0);
}

// The order of 5.4.4's steps on fig. 6 (the standard's fig. 6 (b)-(f)): half
// A-B, half B-C, full E-F, half C-D, then the residue D-G, G-H, H-I as halves.
TEST(RainflowAstmE1049, Fig6CyclesInTheOrderOfTheSteps) {
  const std::vector<Cycle> cycles = rainflow_count(astm_history_pa());
  struct Expected {
    double range, mean, count;
  };
  const std::vector<Expected> expected = {{3, -0.5, 0.5}, {4, -1.0, 0.5}, {4, 1.0, 1.0},
                                          {8, 1.0, 0.5},  {9, 0.5, 0.5},  {8, 0.0, 0.5},
                                          {6, 1.0, 0.5}};
  ASSERT_EQ(cycles.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(cycles[i].range_pa, expected[i].range * units::kMpa) << i;
    EXPECT_EQ(cycles[i].mean_pa, expected[i].mean * units::kMpa) << i;
    EXPECT_EQ(cycles[i].count, expected[i].count) << i;
  }
}

// Plateaus and points between the turning points change nothing.
TEST(RainflowAstmE1049, Fig6WithPlateausAndIntermediatePointsCountsTheSame) {
  std::vector<double> h;
  const std::vector<double> tp = astm_history_pa();
  for (std::size_t i = 0; i + 1 < tp.size(); ++i) {
    h.push_back(tp[i]);
    h.push_back(tp[i]);
    h.push_back(0.5 * (tp[i] + tp[i + 1]));
  }
  h.push_back(tp.back());
  const std::vector<RangeCount> a = merge_ranges(rainflow_count(h));
  const std::vector<RangeCount> b = merge_ranges(rainflow_count(tp));
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].range_pa, b[i].range_pa);
    EXPECT_EQ(a[i].count, b[i].count);
  }
}

// Fig. 6 as one period of a repeated history (Residue::Periodic): rotated to
// start at its peak D = 5: 5, -1, 3, -4, 4, -2, 1, -3, 5, counted by hand
// with 5.4.4: E-F (4), B-C' (-2..1: 3), H-C (4..-3: 7) full, then D-G (9)
// as two halves: 3, 4, 7 and 9 one cycle each, 4 cycles per period.
TEST(RainflowAstmE1049, Fig6AsOnePeriodClosesEveryCycle) {
  const std::vector<RangeCount> merged =
      merge_ranges(rainflow_count(astm_history_pa(), Residue::Periodic));
  const std::vector<RangeCount> expected = {{3e6, 1.0}, {4e6, 1.0}, {7e6, 1.0}, {9e6, 1.0}};
  ASSERT_EQ(merged.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(merged[i].range_pa, expected[i].range_pa) << i;
    EXPECT_EQ(merged[i].count, expected[i].count) << i;
  }
}

}  // namespace
}  // namespace kinetofem::fatigue
