#include "kinetofem/mechanisms/lever_chain.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kPi = std::numbers::pi;

// Point fixed on a body: P = base + R(theta) p_local, with base and theta
// functions of the input; returns P and its first two derivatives.
PointKinematics body_point(const PointKinematics& base, double theta, double theta_d1,
                           double theta_d2, const Eigen::Vector2d& p_local) {
  const Eigen::Rotation2Dd rot(theta);
  const Eigen::Vector2d rp = rot * p_local;
  const Eigen::Vector2d jrp(-rp.y(), rp.x());  // d(R p)/d theta
  PointKinematics out;
  out.p = base.p + rp;
  out.d1 = base.d1 + theta_d1 * jrp;
  out.d2 = base.d2 + theta_d2 * jrp - theta_d1 * theta_d1 * rp;
  return out;
}

}  // namespace

PointMotion point_motion(const PointKinematics& k, double dphi_dot_radps,
                         double dphi_ddot_radps2) {
  PointMotion m;
  m.velocity_mps = dphi_dot_radps * k.d1;
  m.acceleration_mps2 = dphi_dot_radps * dphi_dot_radps * k.d2 + dphi_ddot_radps2 * k.d1;
  const double s1 = k.d1.norm();
  m.speed_mps = dphi_dot_radps * s1;
  // At a stationary point of the path (|P'| = 0) the tangent is undefined; the
  // tangential acceleration is then the whole acceleration along P''.
  const double s2 = s1 > 0.0 ? k.d1.dot(k.d2) / s1 : k.d2.norm();
  m.tangential_acceleration_mps2 = dphi_dot_radps * dphi_dot_radps * s2 + dphi_ddot_radps2 * s1;
  return m;
}

LeverChainGeometry make_lever_chain_geometry(double a_m, double c_m, double h_m, double r_m) {
  require(std::isfinite(a_m) && a_m > 0.0, "lever chain: lever length a = {} m must be positive",
          a_m);
  require(std::isfinite(c_m) && c_m > 0.0, "lever chain: arm length c = {} m must be positive",
          c_m);
  require(std::isfinite(h_m) && h_m >= 0.0,
          "lever chain: gripper offset h = {} m must be non-negative", h_m);
  require(std::isfinite(r_m) && r_m > 0.0, "lever chain: roller radius r = {} m must be positive",
          r_m);
  LeverChainGeometry g;
  g.a_m = a_m;
  g.c_m = c_m;
  g.h_m = h_m;
  g.r_m = r_m;
  g.b0_m = a_m * c_m / (c_m + r_m);                                    // (1)
  g.l0_m = std::sqrt((a_m - g.b0_m) * (a_m - g.b0_m) + r_m * r_m);    // (2)
  g.alpha0_rad = std::acos(r_m / g.l0_m);                              // (3)
  g.b0_point_m = {r_m, a_m - g.b0_m};
  return g;
}

PrimaryChainSynthesis synthesize_primary_chain(const Eigen::Vector2d& h0_m,
                                               const Eigen::Vector2d& hf_m,
                                               double phi_of_rad) {
  require(h0_m.allFinite() && hf_m.allFinite() && std::isfinite(phi_of_rad),
          "primary chain synthesis: non-finite input");
  require(h0_m.x() < 0.0,
          "primary chain synthesis: x_H0 = {} m must be negative (c = -x_H0 > 0)", h0_m.x());
  PrimaryChainSynthesis s;
  const double cf = std::cos(phi_of_rad), sf = std::sin(phi_of_rad);
  s.hf_in_lever_frame_m = {hf_m.x() * cf + hf_m.y() * sf, -hf_m.x() * sf + hf_m.y() * cf};
  const Eigen::Vector2d& h1 = s.hf_in_lever_frame_m;
  s.midpoint_m = 0.5 * (h0_m + h1);
  const double dy = h1.y() - h0_m.y();
  // The bisector is vertical when H0 and Hf1 have the same y: it meets the Y
  // axis only if it is the Y axis itself, i.e. A is not determined.
  require(std::abs(dy) > 1e-12 * (h0_m.norm() + h1.norm()),
          "primary chain synthesis: H0 = ({}, {}) and Hf1 = ({}, {}) have equal y; the "
          "perpendicular bisector does not cross the Y axis",
          h0_m.x(), h0_m.y(), h1.x(), h1.y());
  const double km = (h0_m.x() - h1.x()) / dy;
  s.a_m = s.midpoint_m.y() - km * s.midpoint_m.x();
  s.c_m = -h0_m.x();
  s.h_m = h0_m.y() - s.a_m;
  require(s.a_m > 0.0, "primary chain synthesis: lever length a = {} m is not positive", s.a_m);
  require(s.h_m >= 0.0,
          "primary chain synthesis: h = y_H0 - a = {} m is negative (H below the arm)", s.h_m);
  return s;
}

LeverChainGeometry synthesize_lever_chain(const Eigen::Vector2d& h0_m,
                                          const Eigen::Vector2d& hf_m, double phi_of_rad,
                                          double r_m) {
  const PrimaryChainSynthesis s = synthesize_primary_chain(h0_m, hf_m, phi_of_rad);
  return make_lever_chain_geometry(s.a_m, s.c_m, s.h_m, r_m);
}

LeverChain::LeverChain(const LeverChainGeometry& geometry) : geometry_(geometry) {
  // Re-derive (1)-(3) so that a hand-filled struct cannot be inconsistent.
  const LeverChainGeometry check =
      make_lever_chain_geometry(geometry.a_m, geometry.c_m, geometry.h_m, geometry.r_m);
  const double tol = 1e-9 * geometry.a_m;
  require(std::abs(check.b0_m - geometry.b0_m) <= tol &&
              std::abs(check.l0_m - geometry.l0_m) <= tol &&
              std::abs(check.alpha0_rad - geometry.alpha0_rad) <= 1e-9,
          "lever chain: geometry b0 = {} m, l0 = {} m, alpha0 = {} rad is not consistent with "
          "(1)-(3) for a = {}, c = {}, r = {} m",
          geometry.b0_m, geometry.l0_m, geometry.alpha0_rad, geometry.a_m, geometry.c_m,
          geometry.r_m);
}

bool LeverChain::can_assemble(double dphi_rad) const {
  const auto& g = geometry_;
  const double d2 = g.l0_m * g.l0_m + g.a_m * g.a_m -
                    2.0 * g.l0_m * g.a_m * std::sin(g.alpha0_rad - dphi_rad);
  return std::isfinite(dphi_rad) && d2 > g.r_m * g.r_m;
}

LeverChainCtm LeverChain::ctm(double dphi_rad) const {
  const auto& g = geometry_;
  require(std::isfinite(dphi_rad), "lever chain: lever rotation dphi = {} is not finite",
          dphi_rad);
  const double a = g.a_m, l0 = g.l0_m, r = g.r_m;
  const double u = g.alpha0_rad - dphi_rad;
  const double n = l0 * std::sin(u);  // dN/dphi = -M
  const double m = l0 * std::cos(u);  // dM/dphi = N
  LeverChainCtm s;
  const double d_sq = l0 * l0 + a * a - 2.0 * a * n;  // (6)
  require(d_sq > r * r,
          "lever chain: cannot be assembled at dphi = {:.6g} rad ({:.4g} deg): |A B0| = {:.6g} m "
          "is not larger than the roller radius r = {:.6g} m",
          dphi_rad, dphi_rad * 180.0 / kPi, std::sqrt(std::max(d_sq, 0.0)), r);
  s.d_m = std::sqrt(d_sq);
  s.d_d1 = a * m / s.d_m;
  s.d_d2 = (a * n - s.d_d1 * s.d_d1) / s.d_m;
  s.b_m = std::sqrt(d_sq - r * r);  // (5)
  s.b_d1 = s.d_m * s.d_d1 / s.b_m;
  s.b_d2 = (s.d_d1 * s.d_d1 + s.d_m * s.d_d2 - s.b_d1 * s.b_d1) / s.b_m;
  // (7): beta = atan(b/r) + [angle between -Y and A->B0 in lever 1's frame].
  const double t1 = std::atan(s.b_m / r);
  const double t1_d1 = r * s.b_d1 / d_sq;
  const double t1_d2 = r * (s.b_d2 * d_sq - 2.0 * s.b_d1 * s.d_m * s.d_d1) / (d_sq * d_sq);
  const double t2 = std::atan2(m, a - n);
  const double t2_d1 = (a * n - l0 * l0) / d_sq;
  const double t2_d2 = -a * m * (a * a - l0 * l0) / (d_sq * d_sq);
  s.beta_rad = t1 + t2;
  s.beta_d1 = t1_d1 + t2_d1;
  s.beta_d2 = t1_d2 + t2_d2;
  constexpr double beta0 = 0.5 * kPi;
  s.dpsi_rad = (g.b0_m - s.b_m) / r - beta0 + s.beta_rad;  // (4)
  s.dpsi_d1 = -s.b_d1 / r + s.beta_d1;
  s.dpsi_d2 = -s.b_d2 / r + s.beta_d2;
  return s;
}

LeverChainPose LeverChain::pose(double dphi_rad) const {
  const auto& g = geometry_;
  LeverChainPose pose;
  pose.dphi_rad = dphi_rad;
  pose.ctm = ctm(dphi_rad);
  pose.theta_rad = dphi_rad + pose.ctm.dpsi_rad;
  pose.theta_d1 = 1.0 + pose.ctm.dpsi_d1;
  pose.theta_d2 = pose.ctm.dpsi_d2;
  pose.chain_angle_rad = dphi_rad + pose.ctm.beta_rad;

  // A = R(dphi) (0, a): the lever is a body turning with theta = dphi.
  const PointKinematics origin;  // A0, fixed
  pose.a = body_point(origin, dphi_rad, 1.0, 0.0, Eigen::Vector2d(0.0, g.a_m));
  pose.c = body_point(pose.a, pose.theta_rad, pose.theta_d1, pose.theta_d2,
                      Eigen::Vector2d(-g.c_m, 0.0));  // (12)
  pose.h = body_point(pose.a, pose.theta_rad, pose.theta_d1, pose.theta_d2,
                      Eigen::Vector2d(-g.c_m, g.h_m));  // (15)
  // The radius AB is perpendicular to the chain: its absolute angle is
  // dphi + beta - pi/2 (0 in the design position).
  pose.tangent_point =
      body_point(pose.a, dphi_rad + pose.ctm.beta_rad - 0.5 * kPi, 1.0 + pose.ctm.beta_d1,
                 pose.ctm.beta_d2, Eigen::Vector2d(g.r_m, 0.0));
  return pose;
}

LeverChainPath sample_lever_chain_path(const LeverChain& mechanism, double dphi_lo_rad,
                                       double dphi_hi_rad, std::size_t n) {
  require(n >= 2, "lever chain path: need at least 2 samples, got {}", n);
  require(dphi_hi_rad > dphi_lo_rad, "lever chain path: empty range [{}, {}] rad", dphi_lo_rad,
          dphi_hi_rad);
  LeverChainPath path;
  path.dphi_rad.reserve(n);
  path.c_m.reserve(n);
  path.h_m.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n - 1);
    const double dphi = dphi_lo_rad + t * (dphi_hi_rad - dphi_lo_rad);
    const LeverChainPose p = mechanism.pose(dphi);
    path.dphi_rad.push_back(dphi);
    path.c_m.push_back(p.c.p);
    path.h_m.push_back(p.h.p);
  }
  return path;
}

LeverRange lever_chain_published_range() {
  return {-73.0 * kPi / 180.0, 90.0 * kPi / 180.0};
}

}  // namespace kinetofem::mech
