// Motion laws (motion_law.hpp): end values, derivatives against finite
// differences, continuity of s', the integral of s' equal to the stroke, and
// CSV errors.
#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"

namespace kinetofem::mech {
namespace {

// Reference: definition s' = ds/dt, s'' = ds'/dt; central differences with step
// 1e-6 T have truncation error ~1e-12 T^2 |s'''| and round-off ~1e-10 |s|/T.
void check_derivatives(const MotionLaw& law, double t_end, const std::vector<double>& breakpoints = {}) {
  const double h = 1e-6 * t_end;
  for (int k = 1; k < 200; ++k) {
    const double t = t_end * k / 200.0;
    bool near_break = false;
    for (double b : breakpoints) near_break |= std::abs(t - b) < 2 * h;
    if (near_break) continue;
    const MotionState a = law.at(t - h), b = law.at(t + h), m = law.at(t);
    const double scale_v = std::abs(law.stroke()) / t_end;
    EXPECT_NEAR((b.s - a.s) / (2 * h), m.s_dot, 1e-6 * scale_v) << law.describe() << " t = " << t;
    EXPECT_NEAR((b.s_dot - a.s_dot) / (2 * h), m.s_ddot, 1e-5 * scale_v / t_end) << law.describe() << " t = " << t;
  }
}

// Reference: s(T) - s(0) = integral of s' over [0, T] (composite Simpson, 2000
// panels; exact for the piecewise polynomials up to the kinks at tP, T - tT, error
// < 1e-9 of the stroke); s' continuous (jump < 1e-9 of the cruise speed).
void check_integral_and_continuity(const MotionLaw& law) {
  const double T = law.duration();
  const int n = 2000;
  double sum = law.at(0).s_dot + law.at(T).s_dot;
  for (int k = 1; k < n; ++k) sum += (k % 2 ? 4.0 : 2.0) * law.at(T * k / n).s_dot;
  const double integral = sum * T / (3.0 * n);
  EXPECT_NEAR(integral, law.stroke(), 1e-6 * std::abs(law.stroke())) << law.describe();
  EXPECT_NEAR(law.at(T).s, law.stroke(), 1e-12 * std::abs(law.stroke()));
  EXPECT_EQ(law.at(0).s, 0.0);
  double max_jump = 0.0, max_speed = 0.0;
  for (int k = 0; k <= 10000; ++k) {
    const double t = T * k / 10000.0;
    max_jump = std::max(max_jump, std::abs(law.at(t + 1e-12 * T).s_dot - law.at(t - 1e-12 * T).s_dot));
    max_speed = std::max(max_speed, std::abs(law.at(t).s_dot));
  }
  EXPECT_LT(max_jump, 1e-9 * max_speed) << law.describe();
}

TEST(MotionLaw, TrapezoidalMatchesSpec5Timing) {
  // SPEC §5: T_c = l_ab / (V (1 - 0.5 kP - 0.5 kT)), tP = kP T_c, tT = kT T_c.
  const TrapezoidalLaw law = TrapezoidalLaw::from_speed(1.2, 0.8, 0.3, 0.2);
  EXPECT_NEAR(law.duration(), 1.2 / (0.8 * (1 - 0.15 - 0.1)), 1e-15);
  EXPECT_NEAR(law.cruise_speed(), 0.8, 1e-14);
  EXPECT_NEAR(law.at(0.5 * law.duration()).s_dot, 0.8, 1e-14);
  EXPECT_NEAR(law.acceleration(), 0.8 / (0.3 * law.duration()), 1e-13);
  check_integral_and_continuity(law);
  check_derivatives(law, law.duration(), {0.3 * law.duration(), 0.8 * law.duration()});
}

TEST(MotionLaw, CycloidalAndPolynomialRise) {
  const CycloidalLaw cyc(0.7, 1.5);
  const Polynomial345Law poly(-2.0, 0.8);
  for (const MotionLaw* law : std::vector<const MotionLaw*>{&cyc, &poly}) {
    check_integral_and_continuity(*law);
    check_derivatives(*law, law->duration());
    // Both start and end at rest with zero acceleration (exact by construction).
    EXPECT_NEAR(law->at(1e-12).s_ddot, 0.0, 1e-9);
    EXPECT_NEAR(law->at(law->duration()).s_dot, 0.0, 0.0);
  }
  // 3-4-5 peak speed 15/8 h/T at mid-rise (analytic).
  EXPECT_NEAR(poly.at(0.4).s_dot, 15.0 / 8.0 * -2.0 / 0.8, 1e-12);
  // Cycloidal peak speed 2 h/T at mid-rise (analytic).
  EXPECT_NEAR(cyc.at(0.75).s_dot, 2.0 * 0.7 / 1.5, 1e-12);
}

TEST(MotionLaw, ConstantVelocity) {
  const ConstantVelocityLaw law(3.0, 0.5);
  EXPECT_DOUBLE_EQ(law.at(2.0).s, 6.5);
  EXPECT_DOUBLE_EQ(law.at(2.0).s_dot, 3.0);
  EXPECT_DOUBLE_EQ(law.at(2.0).s_ddot, 0.0);
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

TEST(MotionLaw, TabulatedReproducesACubicAndContinuity) {
  // A natural cubic spline reproduces linear data exactly.
  std::string csv = "t, s\n";
  for (int k = 0; k <= 20; ++k) csv += fmt::format("{}, {}\n", 0.1 * k, 2.0 * 0.1 * k + 1.0);
  const TabulatedLaw law = TabulatedLaw::from_csv(write_temp("law_ok.csv", csv));
  EXPECT_NEAR(law.at(0.537).s, 2.0 * 0.537 + 1.0, 1e-13);  // linear data: exact
  EXPECT_NEAR(law.at(0.537).s_dot, 2.0, 1e-12);
  EXPECT_NEAR(law.stroke(), 4.0, 1e-13);
  // Smooth data: s = sin t sampled at 41 points; spline error O(h^4) inside.
  std::vector<double> t, s;
  for (int k = 0; k <= 40; ++k) {
    t.push_back(0.05 * k);
    s.push_back(std::sin(0.05 * k));
  }
  const TabulatedLaw smooth(t, s);
  EXPECT_NEAR(smooth.at(1.013).s, std::sin(1.013), 1e-6);
  EXPECT_NEAR(smooth.at(1.013).s_dot, std::cos(1.013), 1e-4);
  check_derivatives(smooth, 2.0, t);  // the spline's third derivative jumps at the knots: skip them
}

TEST(MotionLaw, TabulatedBadFilesAreClearErrors) {
  const std::string bad_row = write_temp("law_bad.csv", "t,s\n0,0\n0.5,1\n1.0,abc\n1.5,2\n");
  try {
    TabulatedLaw::from_csv(bad_row);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(bad_row + ":4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TabulatedLaw::from_csv(write_temp("law_order.csv", "0,0\n1,1\n0.5,2\n")), Error);
  EXPECT_THROW(TabulatedLaw::from_csv(write_temp("law_short.csv", "0,0\n1,1\n")), Error);
  EXPECT_THROW(TabulatedLaw::from_csv(::testing::TempDir() + "does_not_exist.csv"), Error);
  EXPECT_THROW(TrapezoidalLaw(1.0, 1.0, 0.7, 0.5), Error);
}

}  // namespace
}  // namespace kinetofem::mech
