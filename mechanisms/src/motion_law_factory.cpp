#include "kinetofem/mechanisms/motion_law_factory.hpp"

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

namespace {

// A law whose values are those of another times a factor (tables in deg or mm).
class ScaledLaw final : public MotionLaw {
 public:
  ScaledLaw(std::shared_ptr<const MotionLaw> law, double factor) : law_(std::move(law)), factor_(factor) {}
  MotionState at(double t) const override {
    const MotionState m = law_->at(t);
    return {factor_ * m.s, factor_ * m.s_dot, factor_ * m.s_ddot};
  }
  double stroke() const override { return factor_ * law_->stroke(); }
  double duration() const override { return law_->duration(); }
  std::string describe() const override { return fmt::format("{} (x {:g} to SI)", law_->describe(), factor_); }

 private:
  std::shared_ptr<const MotionLaw> law_;
  double factor_;
};

}  // namespace

const std::vector<std::string>& motion_law_names() {
  static const std::vector<std::string> names = {"polynomial345", "cycloidal", "trapezoidal", "constant_velocity",
                                                 "csv"};
  return names;
}

std::shared_ptr<const MotionLaw> make_motion_law(const MotionLawSpec& spec) {
  const std::string& law = spec.law;
  if (law == "csv") {
    require(!spec.table_file.empty(), "motion law \"csv\" needs a table file (rows t_s, s)");
    auto table = std::make_shared<TabulatedLaw>(TabulatedLaw::from_csv(spec.table_file.string()));
    if (spec.table_to_si == 1.0) return table;
    return std::make_shared<ScaledLaw>(table, spec.table_to_si);
  }
  if (law == "constant_velocity") {
    require(spec.speed.has_value(), "motion law \"constant_velocity\" needs a speed");
    return std::make_shared<ConstantVelocityLaw>(*spec.speed);
  }
  require(law == "polynomial345" || law == "cycloidal" || law == "trapezoidal",
          "motion law \"{}\" is not known (known: polynomial345, cycloidal, trapezoidal, constant_velocity, csv)", law);
  require(spec.stroke.has_value(), "motion law \"{}\" needs a stroke", law);
  require(spec.duration_s.has_value(), "motion law \"{}\" needs a duration", law);
  if (law == "cycloidal") return std::make_shared<CycloidalLaw>(*spec.stroke, *spec.duration_s);
  if (law == "trapezoidal") {
    const double kp = spec.accel_fraction, kt = spec.decel_fraction;
    require(kp > 0 && kt > 0 && kp + kt <= 1.0,
            "motion law \"trapezoidal\": accel_fraction {:g} and decel_fraction {:g} must be positive with a sum of at "
            "most 1",
            kp, kt);
    return std::make_shared<TrapezoidalLaw>(*spec.stroke, *spec.duration_s, kp, kt);
  }
  return std::make_shared<Polynomial345Law>(*spec.stroke, *spec.duration_s);
}

}  // namespace kinetofem::mech
