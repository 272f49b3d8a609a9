#include "kinetofem/mechanisms/motion_law.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

namespace {

void require_positive(double value, const char* what) {
  require(std::isfinite(value) && value > 0.0, "motion law: {} must be positive, got {}", what, value);
}

}  // namespace

// ---- trapezoidal ----------------------------------------------------------

TrapezoidalLaw::TrapezoidalLaw(double stroke, double duration_s, double k_accel, double k_decel)
    : stroke_(stroke), duration_(duration_s) {
  require_positive(duration_s, "trapezoidal duration");
  require(k_accel > 0.0 && k_decel > 0.0 && k_accel + k_decel <= 1.0 + 1e-12,
          "trapezoidal law: need kP > 0, kT > 0, kP + kT <= 1, got kP = {}, kT = {}", k_accel, k_decel);
  t_accel_ = k_accel * duration_s;
  t_decel_ = k_decel * duration_s;
  speed_ = stroke / (duration_s * (1.0 - 0.5 * k_accel - 0.5 * k_decel));
  accel_ = speed_ / t_accel_;
  decel_ = speed_ / t_decel_;
}

TrapezoidalLaw TrapezoidalLaw::from_speed(double stroke, double speed, double k_accel, double k_decel) {
  require_positive(speed, "trapezoidal cruise speed");
  const double duration = std::abs(stroke) / (speed * (1.0 - 0.5 * k_accel - 0.5 * k_decel));
  return TrapezoidalLaw(stroke, duration, k_accel, k_decel);
}

MotionState TrapezoidalLaw::at(double t) const {
  if (t <= 0.0) return {0.0, 0.0, 0.0};
  if (t >= duration_) return {stroke_, 0.0, 0.0};
  if (t < t_accel_) return {0.5 * accel_ * t * t, accel_ * t, accel_};
  const double s_accel = 0.5 * speed_ * t_accel_;
  const double t_cruise_end = duration_ - t_decel_;
  if (t <= t_cruise_end) return {s_accel + speed_ * (t - t_accel_), speed_, 0.0};
  const double tr = duration_ - t;  // time left
  return {stroke_ - 0.5 * decel_ * tr * tr, decel_ * tr, -decel_};
}

std::string TrapezoidalLaw::describe() const {
  return fmt::format("trapezoidal(stroke {}, T {} s, tP {} s, tT {} s, V {})", stroke_, duration_,
                     t_accel_, t_decel_, speed_);
}

// ---- cycloidal --------------------------------------------------------------

RestToRestLaw::RestToRestLaw(double stroke, double duration_s, const char* what)
    : stroke_(stroke), duration_(duration_s) {
  require_positive(duration_s, what);
}

MotionState RestToRestLaw::at(double t) const {
  if (t <= 0.0) return {0.0, 0.0, 0.0};
  if (t >= duration_) return {stroke_, 0.0, 0.0};
  return during(t);
}

CycloidalLaw::CycloidalLaw(double stroke, double duration_s)
    : RestToRestLaw(stroke, duration_s, "cycloidal duration") {}

MotionState CycloidalLaw::during(double t) const {
  constexpr double two_pi = 2.0 * std::numbers::pi;
  const double tau = t / duration_;
  const double h = stroke_, T = duration_;
  return {h * (tau - std::sin(two_pi * tau) / two_pi), h / T * (1.0 - std::cos(two_pi * tau)),
          h * two_pi / (T * T) * std::sin(two_pi * tau)};
}

std::string CycloidalLaw::describe() const {
  return fmt::format("cycloidal(stroke {}, T {} s)", stroke_, duration_);
}

// ---- 3-4-5 polynomial -------------------------------------------------------

Polynomial345Law::Polynomial345Law(double stroke, double duration_s)
    : RestToRestLaw(stroke, duration_s, "3-4-5 polynomial duration") {}

MotionState Polynomial345Law::during(double t) const {
  const double x = t / duration_, h = stroke_, T = duration_;
  const double x2 = x * x, x3 = x2 * x;
  return {h * (10.0 * x3 - 15.0 * x3 * x + 6.0 * x3 * x2), h / T * (30.0 * x2 - 60.0 * x3 + 30.0 * x3 * x),
          h / (T * T) * (60.0 * x - 180.0 * x2 + 120.0 * x3)};
}

std::string Polynomial345Law::describe() const {
  return fmt::format("polynomial 3-4-5(stroke {}, T {} s)", stroke_, duration_);
}

// ---- constant velocity ------------------------------------------------------

ConstantVelocityLaw::ConstantVelocityLaw(double velocity, double initial) : velocity_(velocity), initial_(initial) {
  require(std::isfinite(velocity) && std::isfinite(initial), "constant-velocity law: non-finite input");
}

MotionState ConstantVelocityLaw::at(double t) const { return {initial_ + velocity_ * t, velocity_, 0.0}; }
double ConstantVelocityLaw::stroke() const { return std::numeric_limits<double>::infinity(); }
double ConstantVelocityLaw::duration() const { return std::numeric_limits<double>::infinity(); }
std::string ConstantVelocityLaw::describe() const {
  return fmt::format("constant velocity({} per s from {})", velocity_, initial_);
}

// ---- tabulated ----------------------------------------------------------------

TabulatedLaw::TabulatedLaw(std::vector<double> times_s, std::vector<double> values, std::string source)
    : times_(std::move(times_s)), values_(std::move(values)), source_(std::move(source)) {
  const std::size_t n = times_.size();
  require(n == values_.size(), "tabulated law {}: {} times but {} values", source_, n, values_.size());
  require(n >= 3, "tabulated law {}: needs at least 3 rows, got {}", source_, n);
  for (std::size_t i = 1; i < n; ++i)
    require(times_[i] > times_[i - 1], "tabulated law {}: times must increase strictly, row {} has t = {} after {}",
            source_, i + 1, times_[i], times_[i - 1]);
  // Natural cubic spline: tridiagonal system for the knot second derivatives M_i,
  // M_0 = M_{n-1} = 0 (Thomas algorithm).
  second_.assign(n, 0.0);
  std::vector<double> diag(n, 1.0), upper(n, 0.0), rhs(n, 0.0), lower(n, 0.0);
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = times_[i] - times_[i - 1], h1 = times_[i + 1] - times_[i];
    lower[i] = h0;
    diag[i] = 2.0 * (h0 + h1);
    upper[i] = h1;
    rhs[i] = 6.0 * ((values_[i + 1] - values_[i]) / h1 - (values_[i] - values_[i - 1]) / h0);
  }
  for (std::size_t i = 1; i < n; ++i) {
    const double w = lower[i] / diag[i - 1];
    diag[i] -= w * upper[i - 1];
    rhs[i] -= w * rhs[i - 1];
  }
  second_[n - 1] = rhs[n - 1] / diag[n - 1];
  for (std::size_t i = n - 1; i-- > 0;) second_[i] = (rhs[i] - upper[i] * second_[i + 1]) / diag[i];
}

TabulatedLaw TabulatedLaw::from_csv(const std::string& path) {
  std::ifstream in(path);
  require(in.good(), "tabulated law: cannot open CSV file '{}'", path);
  std::vector<double> t, s;
  std::string line;
  int line_no = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++line_no;
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    for (char& c : line)
      if (c == ',' || c == ';' || c == '\t') c = ' ';
    std::istringstream fields(line);
    double a = 0.0, b = 0.0;
    std::string extra;
    const bool ok = static_cast<bool>(fields >> a >> b) && !(fields >> extra);
    if (!ok) {
      if (t.empty() && !header_seen) {
        header_seen = true;  // one header line before the data
        continue;
      }
      fail("tabulated law: {}:{}: expected two numbers 't, s', got '{}'", path, line_no, line);
    }
    require(std::isfinite(a) && std::isfinite(b), "tabulated law: {}:{}: non-finite value", path, line_no);
    t.push_back(a);
    s.push_back(b);
  }
  require(t.size() >= 3, "tabulated law: {}: needs at least 3 data rows, found {}", path, t.size());
  return TabulatedLaw(std::move(t), std::move(s), path);
}

MotionState TabulatedLaw::at(double t) const {
  if (t <= times_.front()) return {values_.front(), 0.0, 0.0};
  if (t >= times_.back()) return {values_.back(), 0.0, 0.0};
  std::size_t i = 0, j = times_.size() - 1;
  while (j - i > 1) {
    const std::size_t m = (i + j) / 2;
    (times_[m] <= t ? i : j) = m;
  }
  const double h = times_[j] - times_[i];
  const double a = (times_[j] - t) / h, b = (t - times_[i]) / h;
  const double Mi = second_[i], Mj = second_[j];
  const double s = a * values_[i] + b * values_[j] + ((a * a * a - a) * Mi + (b * b * b - b) * Mj) * h * h / 6.0;
  const double sd = (values_[j] - values_[i]) / h + (-(3.0 * a * a - 1.0) * Mi + (3.0 * b * b - 1.0) * Mj) * h / 6.0;
  const double sdd = a * Mi + b * Mj;
  return {s, sd, sdd};
}

std::string TabulatedLaw::describe() const {
  return fmt::format("tabulated({}, {} rows, t {}..{} s)", source_, times_.size(), times_.front(), times_.back());
}

DelayedLaw::DelayedLaw(std::shared_ptr<const MotionLaw> law, double delay_s) : law_(std::move(law)), delay_(delay_s) {
  require(law_ != nullptr, "delayed motion law: no law to delay");
  require(std::isfinite(delay_s) && delay_s >= 0, "delayed motion law: the delay {} s must be finite and >= 0", delay_s);
}

std::string DelayedLaw::describe() const { return fmt::format("{}, started at t = {:.6g} s", law_->describe(), delay_); }

}  // namespace kinetofem::mech
