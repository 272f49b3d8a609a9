#pragma once
// Motion laws: a prescribed coordinate s(t) (a displacement in m or an angle in
// rad) with its first and second time derivatives s'(t), s''(t).
//
// Every law of finite duration rises from s = 0 at t = 0 to s = stroke at
// t = duration and dwells outside [0, duration] (s = 0 before, s = stroke after,
// s' = s'' = 0), so a law can drive a mechanism over a longer run. Laws are
// immutable after construction; they are shared between drives through
// std::shared_ptr<const MotionLaw>.
//
// Laws, with tau = t / T (T the duration, h the stroke):
//   trapezoidal speed (SPEC §5): acceleration over tP = kP*T, cruise at
//       V = h / (T*(1 - kP/2 - kT/2)), deceleration over tT = kT*T, both constant;
//   cycloidal:  s = h*(tau - sin(2*pi*tau)/(2*pi))            (s'' continuous, zero at ends)
//   3-4-5 polynomial: s = h*(10 tau^3 - 15 tau^4 + 6 tau^5)    (s', s'' zero at both ends)
//   constant velocity: s = v*t for all t (no dwell; e.g. a crank turning steadily)
//   tabulated: (t, s) pairs from a CSV file, interpolated by a natural cubic
//       spline so that s' and s'' are continuous; dwells outside the table.
#include <memory>
#include <string>
#include <vector>

namespace kinetofem::mech {

// Value of a law at one time: coordinate, its rate and its acceleration.
struct MotionState {
  double s = 0.0;
  double s_dot = 0.0;
  double s_ddot = 0.0;
};

class MotionLaw {
 public:
  virtual ~MotionLaw() = default;
  virtual MotionState at(double t) const = 0;
  // Stroke (final minus initial value) over the law's duration; for an unbounded
  // law (constant velocity) the value at t = duration().
  virtual double stroke() const = 0;
  // Duration in s; +infinity for an unbounded law.
  virtual double duration() const = 0;
  virtual std::string describe() const = 0;
};

// Trapezoidal speed law of SPEC §5. kP, kT in (0, 1) with kP + kT <= 1.
class TrapezoidalLaw final : public MotionLaw {
 public:
  TrapezoidalLaw(double stroke, double duration_s, double k_accel, double k_decel);
  // SPEC §5: T_c = stroke / (V*(1 - kP/2 - kT/2)) for a steady speed V.
  static TrapezoidalLaw from_speed(double stroke, double speed, double k_accel, double k_decel);
  MotionState at(double t) const override;
  double stroke() const override { return stroke_; }
  double duration() const override { return duration_; }
  std::string describe() const override;
  double cruise_speed() const { return speed_; }
  double acceleration() const { return accel_; }
  double deceleration() const { return decel_; }

 private:
  double stroke_, duration_, t_accel_, t_decel_, speed_, accel_, decel_;
};

// A rise of `stroke` in `duration` seconds from rest to rest: s = 0 before
// t = 0 and s = stroke after t = duration, both at rest; a derived law gives
// the motion in between.
class RestToRestLaw : public MotionLaw {
 public:
  MotionState at(double t) const final;
  double stroke() const final { return stroke_; }
  double duration() const final { return duration_; }

 protected:
  // Throws unless duration_s > 0; `what` names the law in the message.
  RestToRestLaw(double stroke, double duration_s, const char* what);
  // The motion at 0 < t < duration.
  virtual MotionState during(double t) const = 0;

  double stroke_, duration_;
};

class CycloidalLaw final : public RestToRestLaw {
 public:
  CycloidalLaw(double stroke, double duration_s);
  std::string describe() const override;

 private:
  MotionState during(double t) const override;
};

class Polynomial345Law final : public RestToRestLaw {
 public:
  Polynomial345Law(double stroke, double duration_s);
  std::string describe() const override;

 private:
  MotionState during(double t) const override;
};

// s = s0 + v*t for every t (no dwell). duration() is +infinity.
class ConstantVelocityLaw final : public MotionLaw {
 public:
  explicit ConstantVelocityLaw(double velocity, double initial = 0.0);
  MotionState at(double t) const override;
  double stroke() const override;
  double duration() const override;
  std::string describe() const override;

 private:
  double velocity_, initial_;
};

// Natural cubic spline through (t_i, s_i); times strictly increasing, at least
// 3 points. Before t_0 and after t_n the value is held (s' = s'' = 0); s is
// shifted so that the law starts at s(t_0) as given (no re-zeroing).
class TabulatedLaw final : public MotionLaw {
 public:
  TabulatedLaw(std::vector<double> times_s, std::vector<double> values, std::string source = "table");
  // CSV with two numeric columns t, s per line; '#' comments, blank lines and
  // one non-numeric header line are allowed. Any other malformed line, fewer
  // than 3 rows or non-increasing times is an Error naming file and line.
  static TabulatedLaw from_csv(const std::string& path);
  MotionState at(double t) const override;
  double stroke() const override { return values_.back() - values_.front(); }
  double duration() const override { return times_.back(); }
  std::string describe() const override;

 private:
  std::vector<double> times_, values_, second_;  // second_: spline s'' at the knots
  std::string source_;
};

// Another law started `delay_s` later: s(t) = law(t - delay), so it dwells at
// law(0) until the delay (a second motion after a first, e.g. a gripper
// turned after the arm's stroke). duration() = delay + the law's duration.
class DelayedLaw final : public MotionLaw {
 public:
  DelayedLaw(std::shared_ptr<const MotionLaw> law, double delay_s);
  MotionState at(double t) const override { return law_->at(t - delay_); }
  double stroke() const override { return law_->stroke(); }
  double duration() const override { return delay_ + law_->duration(); }
  std::string describe() const override;

 private:
  std::shared_ptr<const MotionLaw> law_;
  double delay_;
};

}  // namespace kinetofem::mech
