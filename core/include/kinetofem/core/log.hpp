#pragma once
// Terminal output of a run: info lines, detail lines and progress of long steps.
//
// A Log is passed by reference to whatever reports; there is no global logger.
// The console is for a person: at the Normal level a run prints a line per
// stage with its progress, time and the numbers that let a user trust it (mesh
// size, DoFs, factor nnz/flops/time, residuals, drift), then its tables.
// detail() lines (per-solve solver statistics, orderings, sub-step timings)
// are printed only at the Verbose level (`kinetofem run -v`).
// Quiet logs (tests, --quiet) drop both. Progress lines show elapsed and
// estimated remaining time.
#include <chrono>
#include <cstdio>
#include <string>

#include <fmt/format.h>

namespace kinetofem {

class Log {
 public:
  enum class Level { Quiet, Normal, Verbose };
  explicit Log(Level level = Level::Normal, std::FILE* stream = stdout)
      : level_(level), stream_(stream) {}

  static Log quiet() { return Log(Level::Quiet); }

  template <typename... Args>
  void info(fmt::format_string<Args...> format, Args&&... args) const {
    if (level_ == Level::Quiet) return;
    write(fmt::format(format, std::forward<Args>(args)...));
  }
  // A line for -v only: statistics of one solve, of one sub-step.
  template <typename... Args>
  void detail(fmt::format_string<Args...> format, Args&&... args) const {
    if (level_ != Level::Verbose) return;
    write(fmt::format(format, std::forward<Args>(args)...));
  }
  bool is_quiet() const { return level_ == Level::Quiet; }
  bool is_verbose() const { return level_ == Level::Verbose; }
  Level level() const { return level_; }

 private:
  void write(const std::string& line) const;
  Level level_;
  std::FILE* stream_;
};

// Reports progress of a counted task ("time steps 37/100, 1.2 s elapsed,
// ~2.0 s left") at most every `interval_s` seconds, and once at the end. A
// line is printed only once the time left can be extrapolated from the items
// done: at least two of them and a second passed. The first item often
// carries the task's setup (a factorization, a first solve) and alone would
// make the estimate far too long.
class Progress {
 public:
  Progress(const Log& log, std::string task, long total, double interval_s = 2.0);
  Progress(Log&&, std::string, long, double = 2.0) = delete;  // the log would dangle
  void advance(long done);  // `done` items of `total` are finished
  void finish();

  static constexpr long kMinItemsForEstimate = 2;
  static constexpr double kMinSecondsForEstimate = 1.0;

 private:
  const Log& log_;
  std::string task_;
  long total_;
  double interval_s_;
  std::chrono::steady_clock::time_point start_, last_report_;
  bool finished_ = false;
};

// Wall-clock stopwatch in seconds.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace kinetofem
