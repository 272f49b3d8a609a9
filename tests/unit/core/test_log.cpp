// Log levels: info lines at Normal and Verbose, detail lines at Verbose only,
// nothing at Quiet; Progress prints no line (and no time-left estimate) from its first item.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include "kinetofem/core/log.hpp"

namespace kinetofem {
namespace {

// Everything a Log at `level` writes for one info and one detail line.
std::string written_at(Log::Level level, void (*write)(const Log&)) {
  std::FILE* file = std::tmpfile();
  EXPECT_NE(file, nullptr);
  {
    const Log log(level, file);
    write(log);
  }
  std::fflush(file);
  std::rewind(file);
  std::string text;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, file)) > 0;) text.append(buffer, n);
  std::fclose(file);
  return text;
}

void one_of_each(const Log& log) {
  log.info("stage: {} parts", 2);
  log.detail("  CHOLMOD solve: {} right-hand side(s)", 1);
}

TEST(Log, DetailLinesOnlyWhenVerbose) {
  EXPECT_EQ(written_at(Log::Level::Normal, one_of_each), "stage: 2 parts\n");
  EXPECT_EQ(written_at(Log::Level::Verbose, one_of_each), "stage: 2 parts\n  CHOLMOD solve: 1 right-hand side(s)\n");
  EXPECT_EQ(written_at(Log::Level::Quiet, one_of_each), "");
}

TEST(Log, LevelQueries) {
  EXPECT_TRUE(Log::quiet().is_quiet());
  EXPECT_FALSE(Log::quiet().is_verbose());
  EXPECT_TRUE(Log(Log::Level::Verbose).is_verbose());
  EXPECT_FALSE(Log(Log::Level::Verbose).is_quiet());
  EXPECT_FALSE(Log().is_verbose());
}

TEST(Progress, NoEstimateFromTheFirstItem) {
  // interval 0: every advance may report. The first item took all the time so
  // far (it carries the setup): no line from it; from the second on, once a
  // second has passed, a line with an estimate.
  const std::string text = written_at(Log::Level::Normal, [](const Log& log) {
    Progress progress(log, "time steps", 100, 0.0);
    progress.advance(1);
    std::this_thread::sleep_for(std::chrono::milliseconds(1100));
    progress.advance(2);
    progress.finish();
  });
  EXPECT_EQ(text.find("time steps 1/100"), std::string::npos) << text;
  const auto first_end = text.find('\n');
  ASSERT_NE(first_end, std::string::npos) << text;
  const std::string first = text.substr(0, first_end);
  EXPECT_NE(first.find("time steps 2/100"), std::string::npos) << text;
  EXPECT_NE(first.find("s left"), std::string::npos) << text;
  EXPECT_NE(text.find("time steps 100/100 done"), std::string::npos) << text;
}

}  // namespace
}  // namespace kinetofem
