#include "kinetofem/vibration/modal_response.hpp"

#include <cmath>
#include <limits>

#include <unsupported/Eigen/MatrixFunctions>

#include "kinetofem/core/error.hpp"

namespace kinetofem::vibration {

namespace {

void check_damping(double zeta) {
  require(std::isfinite(zeta) && zeta >= 0.0 && zeta < 1.0,
          "modal damping ratio {} is outside [0, 1)", zeta);
}

}  // namespace

ModalStepper::ModalStepper(double omega, double zeta) : omega_(omega), zeta_(zeta) {
  require(std::isfinite(omega) && omega > 0.0,
          "modal response: natural frequency {} rad/s must be positive (remove rigid-body modes)",
          omega);
  check_damping(zeta);
}

void ModalStepper::step(double dt, double f0, double f1, double& q, double& v) const {
  require(dt > 0.0 && std::isfinite(dt), "modal response: time step {} s must be positive", dt);
  if (dt != cached_dt_) {
    Eigen::Matrix4d Z = Eigen::Matrix4d::Zero();
    Z(0, 1) = 1.0;
    Z(1, 0) = -omega_ * omega_;
    Z(1, 1) = -2.0 * zeta_ * omega_;
    Z(1, 2) = 1.0;  // b f
    Z(2, 3) = 1.0;  // f' = r
    cached_ = (Z * dt).exp();
    cached_dt_ = dt;
  }
  const double r = (f1 - f0) / dt;
  const Eigen::Vector4d x0(q, v, f0, r);
  const Eigen::Vector4d x1 = cached_ * x0;
  q = x1[0];
  v = x1[1];
}

ModalResponse integrate_modal_response(const Eigen::VectorXd& omega, double zeta,
                                       const std::vector<double>& time_s,
                                       const Eigen::MatrixXd& force) {
  check_damping(zeta);
  const Eigen::Index m = omega.size(), nt = Eigen::Index(time_s.size());
  require(nt >= 1, "modal response: no output times");
  require(force.rows() == m && force.cols() == nt,
          "modal response: load history is {} x {}, expected {} modes x {} times", force.rows(),
          force.cols(), m, nt);
  require(force.allFinite(), "modal response: the modal load history is not finite");
  for (Eigen::Index k = 1; k < nt; ++k)
    require(time_s[size_t(k)] > time_s[size_t(k - 1)],
            "modal response: times must increase strictly (t[{}] = {} s, t[{}] = {} s)", k - 1,
            time_s[size_t(k - 1)], k, time_s[size_t(k)]);
  ModalResponse out;
  out.time_s = time_s;
  out.displacement.resize(m, nt);
  out.velocity.resize(m, nt);
  out.quasi_static.resize(m, nt);
  for (Eigen::Index i = 0; i < m; ++i) {
    const ModalStepper stepper(omega[i], zeta);
    const double w2 = omega[i] * omega[i];
    double q = force(i, 0) / w2, v = 0.0;
    out.displacement(i, 0) = q;
    out.velocity(i, 0) = v;
    for (Eigen::Index k = 1; k < nt; ++k) {
      stepper.step(time_s[size_t(k)] - time_s[size_t(k - 1)], force(i, k - 1), force(i, k), q, v);
      out.displacement(i, k) = q;
      out.velocity(i, k) = v;
    }
    out.quasi_static.row(i) = force.row(i) / w2;
  }
  return out;
}

OutputHistory output_history(const ModalResponse& r, const Eigen::MatrixXd& output,
                             double stop_time_s) {
  require(output.cols() == r.displacement.rows(),
          "output history: output has {} columns, the response {} modes", output.cols(),
          r.displacement.rows());
  OutputHistory out;
  out.dynamic = output * r.displacement;
  out.quasi_static = output * r.quasi_static;
  for (size_t k = 0; k < r.time_s.size() && r.time_s[k] <= stop_time_s; ++k) {
    const double d = out.dynamic.col(Eigen::Index(k)).norm();
    const double q = out.quasi_static.col(Eigen::Index(k)).norm();
    if (d > out.peak_dynamic) {
      out.peak_dynamic = d;
      out.peak_dynamic_time_s = r.time_s[k];
    }
    if (q > out.peak_quasi_static) {
      out.peak_quasi_static = q;
      out.peak_quasi_static_time_s = r.time_s[k];
    }
  }
  out.dynamic_amplification =
      out.peak_quasi_static > 0 ? out.peak_dynamic / out.peak_quasi_static : 0.0;
  return out;
}

Settling settling_after_stop(const Eigen::VectorXd& omega, double zeta,
                             const Eigen::VectorXd& q_stop, const Eigen::VectorXd& v_stop,
                             const Eigen::VectorXd& f_end, const Eigen::MatrixXd& output,
                             double tolerance) {
  check_damping(zeta);
  require(std::isfinite(tolerance) && tolerance > 0.0,
          "settling tolerance {} must be positive", tolerance);
  const Eigen::Index m = omega.size();
  require(q_stop.size() == m && v_stop.size() == m && f_end.size() == m && output.cols() == m,
          "settling: {} modes, state {} / {}, load {}, output {} columns", m, q_stop.size(),
          v_stop.size(), f_end.size(), output.cols());
  Eigen::VectorXd amplitude(m), decay(m), e0(m);
  for (Eigen::Index i = 0; i < m; ++i) {
    require(omega[i] > 0, "settling: natural frequency {} rad/s must be positive", omega[i]);
    const double wd = omega[i] * std::sqrt(1.0 - zeta * zeta);
    e0[i] = q_stop[i] - f_end[i] / (omega[i] * omega[i]);
    const double s = (v_stop[i] + zeta * omega[i] * e0[i]) / wd;
    amplitude[i] = output.col(i).norm() * std::hypot(e0[i], s);
    decay[i] = zeta * omega[i];
  }
  Settling out;
  out.deviation_at_stop = (output * e0).norm();
  out.envelope_at_stop = amplitude.sum();
  auto bound = [&](double s) { return (amplitude.array() * (-decay.array() * s).exp()).sum(); };
  if (out.envelope_at_stop <= tolerance) return out;
  if (zeta == 0.0) {
    out.time_after_stop_s = std::numeric_limits<double>::infinity();
    return out;
  }
  // B is decreasing: bracket, then bisect to 1e-12 relative.
  double lo = 0.0, hi = 1.0 / decay.minCoeff();
  while (bound(hi) > tolerance) hi *= 2.0;
  while (hi - lo > 1e-12 * hi) {
    const double mid = 0.5 * (lo + hi);
    (bound(mid) > tolerance ? lo : hi) = mid;
  }
  out.time_after_stop_s = hi;
  return out;
}

}  // namespace kinetofem::vibration
