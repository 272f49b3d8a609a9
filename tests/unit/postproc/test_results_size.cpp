// results_size.hpp: the results file's size is estimated before the work and
// refused, with the numbers, when it does not fit the output folder's free space.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_size.hpp"
#include "post_test_calls.hpp"

namespace kinetofem::post {
namespace {

TEST(ResultsSize, SeriesBytesCountEveryValueOfEveryWrittenStep) {
  EXPECT_EQ(series_bytes(1000, 4, 101), 1000.0 * 4 * 101 * 8);
}

TEST(ResultsSize, MoreThanTheFreeSpaceIsRefusedWithTheNumbers) {
  testing::TemporaryDirectory dir;
  const double free = free_bytes(dir.path());
  ASSERT_GT(free, 0.0);
  EXPECT_NO_THROW(require_free_space(dir.path(), 1e3, "the results file", "tiny"));
  // 1e5 field output times of a 1e6-node part: 3.2 TB.
  const double bytes = series_bytes(1000000, 4, 100000);
  if (bytes <= free) GTEST_SKIP() << "this file system has more than " << free * 1e-9 << " GB free";
  const std::string m = testing::error_text(
      [&] { require_free_space(dir.path(), bytes, "the results file 'r.h5'", "100000 field output times"); });
  EXPECT_NE(m.find("the results file 'r.h5' would take about 3.2e+03 GB (100000 field output times)"),
            std::string::npos) << m;
  EXPECT_NE(m.find("GB free in '" + dir.path().string() + "'"), std::string::npos) << m;
  EXPECT_NE(m.find("output.field_every"), std::string::npos) << m;
}

}  // namespace
}  // namespace kinetofem::post
