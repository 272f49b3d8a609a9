#include "kinetofem/core/log.hpp"

namespace kinetofem {

void Log::write(const std::string& line) const {
  std::fputs(line.c_str(), stream_);
  std::fputc('\n', stream_);
  std::fflush(stream_);
}

Progress::Progress(const Log& log, std::string task, long total, double interval_s)
    : log_(log),
      task_(std::move(task)),
      total_(total),
      interval_s_(interval_s),
      start_(std::chrono::steady_clock::now()),
      last_report_(start_) {}

void Progress::advance(long done) {
  const auto now = std::chrono::steady_clock::now();
  const double since_report = std::chrono::duration<double>(now - last_report_).count();
  if (since_report < interval_s_ || done >= total_) return;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  if (done < kMinItemsForEstimate || elapsed < kMinSecondsForEstimate) return;  // no estimate yet: no line
  last_report_ = now;
  const double remaining = elapsed * double(total_ - done) / double(done);
  log_.info("  {} {}/{}: {:.1f} s elapsed, ~{:.1f} s left", task_, done, total_, elapsed,
            remaining);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  log_.info("  {} {}/{} done in {:.2f} s", task_, total_, total_, elapsed);
}

}  // namespace kinetofem
