// equally_spaced_times: the last output time is the end time exactly, which the
// formula end * k / (n - 1) used before does not guarantee.
#include <cmath>
#include <iomanip>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"

namespace kinetofem::mech {
namespace {

// The formula the callers used: duration * k / (n - 1), evaluated left to right.
double old_formula(double duration, long k, long n) { return duration * double(k) / double(n - 1); }

TEST(TimeGrid, LastTimeIsTheEndTimeWhereTheOldFormulaMissesIt) {
  // 0.1 s in 4 times: 0.1 * 3 = 0.30000000000000004, / 3 = 0.10000000000000002.
  ASSERT_NE(old_formula(0.1, 3, 4), 0.1);
  const std::vector<double> t = equally_spaced_times(0.1, 4);
  ASSERT_EQ(t.size(), 4u);
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_EQ(t.back(), 0.1) << std::setprecision(17) << t.back();  // exact, not within a tolerance
}

TEST(TimeGrid, EndIsExactForEveryCountWhereTheOldFormulaMisses) {
  // Search: durations a case file would hold, counts 2..2000. The old formula
  // misses the end for some of them (0.1 s alone: counts 4, 7, 13, 25, ...).
  long misses = 0;
  for (double duration : {0.1, 0.3, 0.7, 1.1, 2.5, 0.015, 0.035, 0.005}) {
    for (long n = 2; n <= 2000; ++n) {
      if (old_formula(duration, n - 1, n) == duration) continue;
      ++misses;
      const std::vector<double> t = equally_spaced_times(duration, n);
      ASSERT_EQ(t.size(), static_cast<std::size_t>(n));
      ASSERT_EQ(t.front(), 0.0);
      ASSERT_EQ(t.back(), duration) << std::setprecision(17) << "duration " << duration << " s, count " << n
                                    << ": last " << t.back();
    }
  }
  EXPECT_GT(misses, 100);  // the search did find the old formula's misses
}

TEST(TimeGrid, InteriorTimesAreTheFormulaAndIncrease) {
  for (long n : {2L, 3L, 4L, 7L, 101L, 1001L}) {
    const double end = 0.7;
    const std::vector<double> t = equally_spaced_times(end, n);
    ASSERT_EQ(t.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(t.front(), 0.0);
    EXPECT_EQ(t.back(), end);
    for (long k = 1; k + 1 < n; ++k) EXPECT_EQ(t[k], old_formula(end, k, n));  // interior unchanged
    for (long k = 1; k < n; ++k) {
      EXPECT_GT(t[k], t[k - 1]);
      // Equal spacing to round-off: |dt - end/(n-1)| <= 4 ulp of the end time.
      EXPECT_NEAR(t[k] - t[k - 1], end / double(n - 1), 4 * std::numeric_limits<double>::epsilon() * end);
    }
  }
}

TEST(TimeGrid, BadArgumentsAreErrors) {
  EXPECT_THROW(equally_spaced_times(1.0, 1), Error);
  EXPECT_THROW(equally_spaced_times(1.0, 0), Error);
  EXPECT_THROW(equally_spaced_times(1.0, -5), Error);
  EXPECT_THROW(equally_spaced_times(0.0, 10), Error);
  EXPECT_THROW(equally_spaced_times(-1.0, 10), Error);
  EXPECT_THROW(equally_spaced_times(std::numeric_limits<double>::infinity(), 10), Error);
  EXPECT_THROW(equally_spaced_times(std::numeric_limits<double>::quiet_NaN(), 10), Error);
  try {
    equally_spaced_times(1.0, 1);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("got 1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kinetofem::mech
