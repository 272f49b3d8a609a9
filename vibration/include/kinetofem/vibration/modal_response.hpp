#pragma once
// Modal response along a motion (docs/vibration.md).
//
// Each mode i (unit modal mass) obeys
//   q_i'' + 2 zeta w_i q_i' + w_i^2 q_i = f_i(t),        f_i = phi_i^T f(t)
// with f(t) the motion's inertia and weight loads (N) projected on the mode
// (f_i in N / sqrt(kg) = m/s^2 sqrt(kg)); for a single-degree-of-freedom
// system under base acceleration a(t), f = -a (m/s^2) and q is the relative
// displacement (m). zeta: the modal damping ratio, the same for every mode,
// 0 <= zeta < 1.
//
// Integration: f is linear between the given samples, and each step is the
// EXACT solution for that load (no integration error beyond the load's
// piecewise-linear interpolation): the state x = [q; q'] advances by the
// exponential of the augmented matrix
//   Z = [[A, b, 0], [0, 0, 1], [0, 0, 0]],  A = [[0, 1], [-w^2, -2 zeta w]],  b = [0; 1]
// over the step (Van Loan; Eigen's Pade scaling-and-squaring matrix
// exponential): x_{k+1} = E_xx x_k + E_xf f_k + E_xr (f_{k+1} - f_k) / dt.
// Unconditionally stable, any step, any w dt.
//
// Start: at rest in the quasi-static state of the first load, q(0) =
// f(0) / w^2, q'(0) = 0 (the manipulator waits in its start pose under its
// weight), so a constant load gives q = f / w^2 exactly: the quasi-static
// response q_s(t) = f(t) / w^2.
//
// Settling after the stop. With the load constant after t_stop (f_end), each
// mode rings freely about f_end / w^2:
//   e_i(s) = exp(-zeta w_i s) (e0 cos w_d s + (v0 + zeta w_i e0) / w_d sin w_d s),
// whose envelope is R_i exp(-zeta w_i s), R_i = |(e0, (v0 + zeta w_i e0) / w_d)|.
// An output y = C q (a point's displacement, C: k x m, m per modal unit)
// deviates from its final value by at most B(s) = sum_i |C_i| R_i exp(-zeta w_i s);
// the settling time is the smallest s with B(s) <= tolerance (a guaranteed
// bound: |y - y_end| stays below it afterwards; infinite with zeta = 0).
#include <vector>

#include <Eigen/Core>

namespace kinetofem::vibration {

// One mode's exact stepper for piecewise-linear loads.
class ModalStepper {
 public:
  // Throws Error unless w > 0 (rad/s, finite) and 0 <= zeta < 1.
  ModalStepper(double omega_rad_s, double damping_ratio);
  // Advances (q, v) over dt (s, > 0) with the load going linearly f0 -> f1.
  void step(double dt_s, double f0, double f1, double& q, double& v) const;
  double omega() const { return omega_; }
  double damping_ratio() const { return zeta_; }

 private:
  double omega_, zeta_;
  mutable double cached_dt_ = -1.0;
  mutable Eigen::Matrix4d cached_;
};

struct ModalResponse {
  std::vector<double> time_s;
  Eigen::MatrixXd displacement;   // q, m x n_t
  Eigen::MatrixXd velocity;       // q', m x n_t
  Eigen::MatrixXd quasi_static;   // f / w^2, m x n_t
};

// q(t) of every mode for the load history modal_force (m x n_t, column k at
// time_s[k], strictly increasing). Throws Error on bad input (sizes, times,
// w <= 0, zeta outside [0, 1), loads not finite).
ModalResponse integrate_modal_response(const Eigen::VectorXd& omega_rad_s, double damping_ratio,
                                       const std::vector<double>& time_s,
                                       const Eigen::MatrixXd& modal_force);

// A physical output y(t) = C q(t) (e.g. the gripper point's elastic
// displacement: C = the rows of the mode shapes there, k x m, m per modal
// unit) beside its quasi-static counterpart C q_s(t), and their peaks (vector
// norm |y|) during the stroke, t <= stop_time_s. Dynamic amplification =
// peak |y| / peak |y_s| over the stroke (0 when the quasi-static peak is 0).
struct OutputHistory {
  Eigen::MatrixXd dynamic;       // k x n_t
  Eigen::MatrixXd quasi_static;  // k x n_t
  double peak_dynamic = 0.0, peak_dynamic_time_s = 0.0;
  double peak_quasi_static = 0.0, peak_quasi_static_time_s = 0.0;
  double dynamic_amplification = 0.0;
};
OutputHistory output_history(const ModalResponse& response, const Eigen::MatrixXd& output,
                             double stop_time_s);

struct Settling {
  double deviation_at_stop = 0.0;  // |y(t_stop) - y_end|
  double envelope_at_stop = 0.0;   // B(0) >= deviation_at_stop
  double time_after_stop_s = 0.0;  // smallest s with B(s) <= tolerance; +inf if never
};

// Settling of y = C q after the stop from the modal state (q, v) at the stop
// and the constant modal load f_end after it (header). Throws Error unless
// tolerance > 0 and 0 <= zeta < 1.
Settling settling_after_stop(const Eigen::VectorXd& omega_rad_s, double damping_ratio,
                             const Eigen::VectorXd& q_stop, const Eigen::VectorXd& v_stop,
                             const Eigen::VectorXd& f_end, const Eigen::MatrixXd& output,
                             double tolerance);

}  // namespace kinetofem::vibration
