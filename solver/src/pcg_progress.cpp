#include "kinetofem/solver/pcg_progress.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>

namespace kinetofem::fem {

namespace {

// "~45 s left", "~3.2 s left", "~12.5 min left", or "time left unknown".
std::string time_left(std::optional<long> remaining_iterations, double seconds_per_iteration) {
  if (!remaining_iterations || !std::isfinite(seconds_per_iteration))
    return "time left unknown";
  const double seconds = double(*remaining_iterations) * seconds_per_iteration;
  if (seconds < 10.0) return fmt::format("~{:.1f} s left", seconds);
  if (seconds < 120.0) return fmt::format("~{:.0f} s left", seconds);
  return fmt::format("~{:.1f} min left", seconds / 60.0);
}

}  // namespace

std::optional<long> estimated_remaining_iterations(int iterations, double initial_residual,
                                                   double residual, double target) {
  if (iterations < 1 || !(initial_residual > 0.0) || !(residual > 0.0) || !(target > 0.0) ||
      !std::isfinite(initial_residual) || !std::isfinite(residual) || !std::isfinite(target))
    return std::nullopt;
  if (residual <= target) return 0;
  const double rate = std::log(residual / initial_residual) / double(iterations);
  if (!(rate < 0.0)) return std::nullopt;
  const double remaining = std::log(target / residual) / rate;
  // Round-off in the logarithms: 30 +- 1e-14 iterations are 30, not 31.
  const double rounded = std::ceil(remaining - 1e-6);
  if (!(rounded <= 1e9)) return std::nullopt;  // no useful estimate
  return long(std::max(rounded, 1.0));
}

double steady_clock_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

PcgProgress::PcgProgress(const Log& log, double interval_s, SecondsClock clock)
    : log_(log), interval_s_(interval_s), clock_(std::move(clock)) {}

void PcgProgress::start(std::string label, double target, double initial_residual) {
  label_ = std::move(label);
  target_ = target;
  initial_residual_ = initial_residual;
  start_s_ = last_line_s_ = clock_();
  reported_ = false;
  history_.assign(1, initial_residual);
}

void PcgProgress::iteration(int iterations, double relative_residual) {
  if (interval_s_ < 0.0) return;
  if (iterations >= 0) {
    if (history_.size() <= size_t(iterations)) history_.resize(size_t(iterations) + 1, relative_residual);
    history_[size_t(iterations)] = relative_residual;
  }
  const double now = clock_();
  const double elapsed = now - start_s_;
  if (elapsed < interval_s_ || (reported_ && now - last_line_s_ < interval_s_)) return;
  last_line_s_ = now;
  reported_ = true;
  ++lines_;
  const int from = iterations / 2;  // the later half's rate (header)
  const double from_residual = from < int(history_.size()) ? history_[size_t(from)] : initial_residual_;
  const auto remaining =
      estimated_remaining_iterations(iterations - from, from_residual, relative_residual, target_);
  log_.info("  {}: iteration {}, relative residual {:.1e} (target {:.2g}), {}", label_,
            iterations, relative_residual, target_,
            time_left(remaining, iterations > 0 ? elapsed / double(iterations) : NAN));
}

}  // namespace kinetofem::fem
