#pragma once
// Progress of a long iterative solve (AmgSolver's PCG): how many iterations
// are still needed, extrapolated from the convergence so far, and a reporter
// that prints a line through a Log at most every `interval_s` seconds:
//
//   AMG-PCG column 3/37: iteration 80, relative residual 3.2e-06 (target 1e-08), ~45 s left
//
// The clock is passed in (seconds on any monotone scale), so tests drive the
// reporter with a fake one; there is no global state.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"

namespace kinetofem::fem {

// Iterations still needed to bring a relative residual from `residual`
// (after `iterations` iterations, started from `initial_residual`) to at or
// below `target`, from the mean convergence rate so far:
//   c = ln(residual / initial_residual) / iterations  (per iteration, < 0),
//   n = ln(target / residual) / c,
// rounded up; 0 when the target is already reached. Exact for a geometric
// sequence rho_k = rho_0 q^k (round-off in the logarithms is absorbed before
// rounding up). nullopt when not estimable: no iteration yet, no decrease so
// far (c >= 0), or a non-finite or non-positive argument.
std::optional<long> estimated_remaining_iterations(int iterations, double initial_residual,
                                                   double residual, double target);

// Seconds on a monotone clock (std::chrono::steady_clock by default).
using SecondsClock = std::function<double()>;
double steady_clock_seconds();

// Prints the progress of one solve after another. A solve starts with
// start(); iteration() is called after each iteration with the relative
// residual reached. A line is printed when the solve has run at least
// `interval_s` and the last line is at least `interval_s` old: 0 prints
// every iteration, a negative interval never. The time left is the
// estimated remaining iterations times the mean seconds per iteration so far;
// the remaining iterations come from the rate over the LATER HALF of the
// iterations so far (from iteration i/2 to i): a preconditioned residual
// often rises first and then converges faster and faster, and a rate from
// iteration 0 overestimated the time left 2-10x on a 180 k-DoF TET10
// cantilever. A geometric sequence gives the same (exact) count either way.
class PcgProgress {
 public:
  PcgProgress(const Log& log, double interval_s, SecondsClock clock = steady_clock_seconds);
  PcgProgress(Log&&, double, SecondsClock = steady_clock_seconds) = delete;  // the log would dangle

  // `label` names the solve in the line ("AMG-PCG column 3/37"); `target` is
  // the relative residual at which it stops, `initial_residual` the one at
  // iteration 0 (1 from a zero initial guess).
  void start(std::string label, double target, double initial_residual = 1.0);
  void iteration(int iterations, double relative_residual);
  int lines() const { return lines_; }  // lines printed since construction

 private:
  const Log& log_;
  double interval_s_;
  SecondsClock clock_;
  std::string label_;
  double target_ = 0.0, initial_residual_ = 1.0;
  std::vector<double> history_;  // relative residual after iteration k (k = 0: the initial one)
  double start_s_ = 0.0, last_line_s_ = 0.0;
  bool reported_ = false;  // a line of the current solve is out
  int lines_ = 0;
};

}  // namespace kinetofem::fem
