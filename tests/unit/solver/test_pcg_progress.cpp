// The progress of a long PCG solve (pcg_progress.hpp): the estimate of the
// iterations left, and when the reporter prints, driven by a fake clock.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "kinetofem/solver/pcg_progress.hpp"
#include "kinetofem/testing/captured_log.hpp"

namespace kinetofem::fem {
namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  for (size_t start = 0, end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  return lines;
}

TEST(PcgProgress, GeometricResidualsGiveTheExactRemainingIterations) {
  // rho_k = q^k: the target q^N is reached at iteration N, whatever iteration
  // the estimate is made at (reference: N - i, exactly).
  for (const double q : {0.9, 0.8, 0.5, 0.1}) {
    const int N = int(std::floor(std::log(1e-8) / std::log(q)));
    const double target = std::pow(q, N);
    for (int i = 1; i < N; ++i)
      EXPECT_EQ(estimated_remaining_iterations(i, 1.0, std::pow(q, i), target), long(N - i))
          << "q = " << q << ", iteration " << i;
  }
  // From another start: rho_0 = 4, rho_k = 4 q^k.
  EXPECT_EQ(
      estimated_remaining_iterations(10, 4.0, 4.0 * std::pow(0.7, 10), 4.0 * std::pow(0.7, 60)),
      50);
  // A target between two iterates is reached at the later one.
  EXPECT_EQ(estimated_remaining_iterations(5, 1.0, std::pow(0.5, 5), 0.9 * std::pow(0.5, 20)), 16);
}

TEST(PcgProgress, NoEstimateBeforeTheResidualDecreases) {
  EXPECT_FALSE(estimated_remaining_iterations(0, 1.0, 1.0, 1e-8));   // no iteration yet
  EXPECT_FALSE(estimated_remaining_iterations(3, 1.0, 1.0, 1e-8));   // no decrease
  EXPECT_FALSE(estimated_remaining_iterations(3, 1.0, 2.0, 1e-8));   // growth
  EXPECT_FALSE(estimated_remaining_iterations(3, 1.0, NAN, 1e-8));
  EXPECT_FALSE(estimated_remaining_iterations(3, 1.0, 0.5, 0.0));
  EXPECT_EQ(estimated_remaining_iterations(3, 1.0, 1e-9, 1e-8), 0);  // already there
}

TEST(PcgProgress, PrintsAtMostEveryIntervalOnceTheSolveHasRunThatLong) {
  testing::CapturedLog captured;
  double now_s = 100.0;
  PcgProgress progress(captured.log(), 10.0, [&] { return now_s; });
  progress.start("AMG-PCG column 2/5", 1e-8);
  // 3 s per iteration, residual 0.5^i: lines at 12 s (i = 4), 24 s (i = 8),
  // 36 s (i = 12), each at least 10 s after the one before.
  for (int i = 1; i <= 13; ++i) {
    now_s += 3.0;
    progress.iteration(i, std::pow(0.5, i));
  }
  const auto lines = lines_of(captured.text());
  ASSERT_EQ(lines.size(), 3u) << captured.text();
  EXPECT_EQ(progress.lines(), 3);
  // Iteration 4: 0.5^4 = 6.25e-2, ~23 more iterations to 1e-8 (2^-27 = 7.5e-9)
  // at 3 s each.
  EXPECT_EQ(lines[0],
            "  AMG-PCG column 2/5: iteration 4, relative residual 6.2e-02 (target 1e-08), "
            "~69 s left");
  EXPECT_NE(lines[1].find("iteration 8,"), std::string::npos) << lines[1];
  EXPECT_NE(lines[2].find("iteration 12,"), std::string::npos) << lines[2];
  EXPECT_NE(lines[2].find("~45 s left"), std::string::npos) << lines[2];

  // A new solve waits its own interval again.
  progress.start("AMG-PCG column 3/5", 1e-8);
  now_s += 9.0;
  progress.iteration(1, 0.5);
  EXPECT_EQ(progress.lines(), 3);
  now_s += 1.0;
  progress.iteration(2, 0.25);
  EXPECT_EQ(progress.lines(), 4);
}

TEST(PcgProgress, ARiseThenFasterConvergenceIsEstimatedFromTheLaterHalf) {
  // rho_k = 5 for k <= 20 (the preconditioned residual rises first), then
  // 5 * 0.7^(k - 20): the target 1e-8 is reached at k = 77 (5 * 0.7^57 < 1e-8
  // < 5 * 0.7^56), so at k = 40 there are 37 iterations left. The later
  // half's rate (iterations 20 to 40) gives exactly that; the mean rate
  // from iteration 0 would say 94 (2.5x).
  testing::CapturedLog captured;
  double now_s = 0.0;
  PcgProgress progress(captured.log(), 0.0, [&] { return now_s; });
  progress.start("AMG-PCG column 1/1", 1e-8);
  for (int k = 1; k <= 40; ++k) {
    now_s += 1.0;
    progress.iteration(k, k <= 20 ? 5.0 : 5.0 * std::pow(0.7, k - 20));
  }
  const auto lines = lines_of(captured.text());
  ASSERT_EQ(lines.size(), 40u);
  EXPECT_NE(lines.back().find("~37 s left"), std::string::npos) << lines.back();  // 1 s per iteration
  EXPECT_EQ(estimated_remaining_iterations(40, 1.0, 5.0 * std::pow(0.7, 20), 1e-8), 94);
}

TEST(PcgProgress, ZeroIntervalPrintsEveryIterationNegativeNever) {
  testing::CapturedLog captured;
  double now_s = 0.0;
  PcgProgress every(captured.log(), 0.0, [&] { return now_s; });
  every.start("AMG-PCG column 1/1", 1e-8);
  every.iteration(1, 1.0);  // no decrease yet
  now_s += 0.5;
  every.iteration(2, 0.1);
  const auto lines = lines_of(captured.text());
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_NE(lines[0].find("time left unknown"), std::string::npos) << lines[0];
  // The rate of the later half (iteration 1 to 2: 1.0 -> 0.1): 7 more at 0.25 s.
  EXPECT_NE(lines[1].find("~1.8 s left"), std::string::npos) << lines[1];

  PcgProgress never(captured.log(), -1.0, [&] { return now_s; });
  never.start("AMG-PCG column 1/1", 1e-8);
  for (int i = 1; i <= 5; ++i) {
    now_s += 100.0;
    never.iteration(i, std::pow(0.1, i));
  }
  EXPECT_EQ(never.lines(), 0);
  EXPECT_EQ(lines_of(captured.text()).size(), 2u);
}

}  // namespace
}  // namespace kinetofem::fem
