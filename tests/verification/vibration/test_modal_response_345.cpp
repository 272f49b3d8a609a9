// Vibration verification 5 (docs/vibration.md): modal response of a single-degree-of-freedom
// system under a 3-4-5 polynomial ramp of its base, against the closed form.
//
// x'' + 2 zeta w x' + w^2 x = -a(t), a the base acceleration of
// s(t) = h (10 tau^3 - 15 tau^4 + 6 tau^5), tau = t / T, h = 1 m, T = 2 s,
// f_n = 5 Hz, zeta = 0.02; output every 0.5 ms over the stroke and 6 s after
// it. Reference: verification::Sdof345 (cubic particular solution + damped
// homogeneous one, then free vibration). The integrator is exact for a
// piecewise-linear load; the cubic load's interpolation error is O(dt^2)
// (2.1e-6 of the peak at dt = 1 ms, so 0.5 ms): tolerance 1e-6 of the peak
// response.
// With zero acceleration (only a constant weight load) the response is the
// quasi-static one, f / w^2, to round-off. Settling after the stop: the
// envelope bound against a sampled check. Bad inputs: damping outside
// [0, 1), tolerance <= 0.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/verification/beam_vibration.hpp"
#include "kinetofem/vibration/modal_response.hpp"

namespace kinetofem::vibration_tests {
namespace {

TEST(ModalResponse345, SdofUnderPolynomialRampMatchesClosedForm) {
  const Stopwatch clock;
  const verification::Sdof345 sdof;
  const double dt = 5e-4, t_end = sdof.duration_s + 6.0;
  std::vector<double> t;
  for (int k = 0; k * dt <= t_end + 1e-12; ++k) t.push_back(k * dt);
  Eigen::MatrixXd force(1, Eigen::Index(t.size()));
  for (size_t k = 0; k < t.size(); ++k) force(0, Eigen::Index(k)) = -sdof.base_acceleration_m_s2(t[k]);
  const Eigen::VectorXd omega = Eigen::VectorXd::Constant(1, sdof.omega_rad_s);
  const vibration::ModalResponse r =
      vibration::integrate_modal_response(omega, sdof.damping_ratio, t, force);
  double peak = 0.0, worst = 0.0, peak_qs = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double exact = sdof.relative_displacement_m(t[k]);
    peak = std::max(peak, std::abs(exact));
    peak_qs = std::max(peak_qs, std::abs(r.quasi_static(0, Eigen::Index(k))));
    worst = std::max(worst, std::abs(r.displacement(0, Eigen::Index(k)) - exact));
  }
  std::printf("3-4-5 ramp: peak relative displacement %.6e m (quasi-static %.6e m, dynamic "
              "amplification %.4f), max |error| %.3e m = %.3e of the peak, %zu steps, %.3f s\n",
              peak, peak_qs, peak / peak_qs, worst, worst / peak, t.size() - 1, clock.seconds());
  // Reference: closed form; tolerance 1e-6 of the peak.
  EXPECT_LT(worst / peak, 1e-6);
  // The output summary over the stroke: the closed form's peak and the
  // quasi-static peak |a|max / w^2 (a 3-4-5 law: |a|max = 5.7735 h / T^2).
  double peak_stroke = 0.0;
  for (size_t k = 0; k < t.size() && t[k] <= sdof.duration_s; ++k)
    peak_stroke = std::max(peak_stroke, std::abs(sdof.relative_displacement_m(t[k])));
  const vibration::OutputHistory h =
      vibration::output_history(r, Eigen::MatrixXd::Ones(1, 1), sdof.duration_s);
  const double qs_peak = 10.0 / std::sqrt(3.0) * sdof.stroke_m /
                         (sdof.duration_s * sdof.duration_s * sdof.omega_rad_s * sdof.omega_rad_s);
  std::printf("during the stroke: peak %.6e m at %.4f s (closed form %.6e m), quasi-static peak "
              "%.6e m at %.4f s (|a|max / w^2 = %.6e m), dynamic amplification %.5f\n",
              h.peak_dynamic, h.peak_dynamic_time_s, peak_stroke, h.peak_quasi_static,
              h.peak_quasi_static_time_s, qs_peak, h.dynamic_amplification);
  // References: the closed form's peak (1e-6) and |a|max / w^2 (sampling: 1e-5).
  EXPECT_NEAR(h.peak_dynamic / peak_stroke, 1.0, 1e-6);
  EXPECT_NEAR(h.peak_quasi_static / qs_peak, 1.0, 1e-5);

  // Settling after the stop (t = T): the envelope bound holds on the samples.
  const Eigen::Index stop = Eigen::Index(std::lround(sdof.duration_s / dt));
  const double tolerance = 1e-2 * peak;
  const vibration::Settling s = vibration::settling_after_stop(
      omega, sdof.damping_ratio, r.displacement.col(stop), r.velocity.col(stop),
      force.col(Eigen::Index(t.size()) - 1), Eigen::MatrixXd::Ones(1, 1), tolerance);
  double last_above = 0.0;
  for (Eigen::Index k = stop; k < Eigen::Index(t.size()); ++k)
    if (std::abs(r.displacement(0, k)) > tolerance) last_above = t[size_t(k)] - sdof.duration_s;
  std::printf("at the stop: deviation %.3e m, envelope %.3e m; settling to %.3e m: %.4f s after "
              "the stop (envelope bound), last sample above it %.4f s\n",
              s.deviation_at_stop, s.envelope_at_stop, tolerance, s.time_after_stop_s, last_above);
  // Reference: the sampled response; the bound is conservative: never earlier,
  // and tight to within one period of the 5 Hz mode.
  EXPECT_GE(s.time_after_stop_s, last_above);
  EXPECT_LT(s.time_after_stop_s, last_above + 0.2);
}

TEST(ModalResponse345, ZeroAccelerationGivesTheQuasiStaticResponse) {
  // Two modes under their weight only (constant modal loads): starting from
  // the quasi-static state, the response stays there.
  const Eigen::VectorXd omega = Eigen::Vector2d(2.0 * std::numbers::pi * 3.0, 2.0 * std::numbers::pi * 40.0);
  std::vector<double> t;
  for (int k = 0; k <= 500; ++k) t.push_back(0.004 * k);
  Eigen::MatrixXd force(2, Eigen::Index(t.size()));
  force.row(0).setConstant(-9.81 * 0.7);
  force.row(1).setConstant(9.81 * 0.2);
  const vibration::ModalResponse r = vibration::integrate_modal_response(omega, 0.03, t, force);
  const double error = (r.displacement - r.quasi_static).cwiseAbs().maxCoeff() /
                       r.quasi_static.cwiseAbs().maxCoeff();
  std::printf("zero acceleration: max |q - f / w^2| / max |f / w^2| = %.2e\n", error);
  // Reference: the quasi-static response f / w^2; tolerance 1e-12 (round-off).
  EXPECT_LT(error, 1e-12);
}

TEST(ModalResponse345, ExactForPiecewiseLinearLoadsAtAnyStep) {
  // A linear load f = 3 t on [0, 1] s, w = 2 pi 20 rad/s (w dt = 126 in one
  // step): one step and 1000 steps give the same state.
  const vibration::ModalStepper stepper(2.0 * std::numbers::pi * 20.0, 0.05);
  double q1 = 0.0, v1 = 0.0, qn = 0.0, vn = 0.0;
  stepper.step(1.0, 0.0, 3.0, q1, v1);
  for (int k = 0; k < 1000; ++k) stepper.step(1e-3, 3.0 * k * 1e-3, 3.0 * (k + 1) * 1e-3, qn, vn);
  std::printf("linear load, 1 step vs 1000: q %.15e / %.15e, v %.15e / %.15e\n", q1, qn, v1, vn);
  // Reference: the 1000-step result (exact too); tolerance 1e-10 relative.
  EXPECT_NEAR(q1 / qn, 1.0, 1e-10);
  EXPECT_NEAR(v1 / vn, 1.0, 1e-10);
}

TEST(ModalResponse345, BadInputsAreErrors) {
  const Eigen::VectorXd omega = Eigen::VectorXd::Constant(1, 10.0);
  const std::vector<double> t = {0.0, 0.1};
  const Eigen::MatrixXd f = Eigen::MatrixXd::Zero(1, 2);
  for (double zeta : {-0.1, 1.0, 1.5})
    EXPECT_THROW(vibration::integrate_modal_response(omega, zeta, t, f), Error) << zeta;
  EXPECT_THROW(vibration::integrate_modal_response(-omega, 0.02, t, f), Error);
  EXPECT_THROW(vibration::integrate_modal_response(omega, 0.02, {0.0, 0.0}, f), Error);
  const Eigen::VectorXd q = Eigen::VectorXd::Ones(1);
  for (double tol : {0.0, -1e-3})
    EXPECT_THROW(vibration::settling_after_stop(omega, 0.02, q, q, q, Eigen::MatrixXd::Ones(1, 1), tol),
                 Error)
        << tol;
}

}  // namespace
}  // namespace kinetofem::vibration_tests
