#include "kinetofem/mechanisms/four_bar.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kPi = std::numbers::pi;

Eigen::Vector2d unit(double t) { return {std::cos(t), std::sin(t)}; }
Eigen::Vector2d unit_perp(double t) { return {-std::sin(t), std::cos(t)}; }

double wrap_pi(double t) { return std::remainder(t, 2.0 * kPi); }

double angle_between(const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
  return std::atan2(std::abs(u.x() * v.y() - u.y() * v.x()), u.dot(v));
}

}  // namespace

std::string_view to_string(GrashofClass c) {
  switch (c) {
    case GrashofClass::crank_rocker: return "Grashof crank-rocker";
    case GrashofClass::rocker_crank: return "Grashof rocker-crank";
    case GrashofClass::double_crank: return "Grashof double-crank";
    case GrashofClass::double_rocker: return "Grashof double-rocker";
    case GrashofClass::change_point: return "change-point";
    case GrashofClass::triple_rocker: return "non-Grashof triple-rocker";
  }
  return "unknown";
}

FourBar FourBar::from_design_position(const Eigen::Vector2d& a0_m, const Eigen::Vector2d& a_m,
                                      const Eigen::Vector2d& b_m, const Eigen::Vector2d& b0_m) {
  require(a0_m.allFinite() && a_m.allFinite() && b_m.allFinite() && b0_m.allFinite(),
          "four-bar: non-finite design point");
  FourBar fb;
  fb.a0_ = a0_m;
  fb.b0_ = b0_m;
  fb.a_len_ = (a_m - a0_m).norm();
  fb.l2_ = (b_m - a_m).norm();
  fb.l3_ = (b_m - b0_m).norm();
  const double scale = fb.a_len_ + fb.l2_ + fb.l3_ + (b0_m - a0_m).norm();
  require(fb.a_len_ > 1e-12 * scale, "four-bar: crank A0A has zero length");
  require(fb.l2_ > 1e-12 * scale, "four-bar: coupler AB has zero length");
  require(fb.l3_ > 1e-12 * scale, "four-bar: rocker B0B has zero length");
  require((b0_m - a0_m).norm() > 1e-12 * scale, "four-bar: ground A0B0 has zero length");
  fb.phi_design_ = std::atan2(a_m.y() - a0_m.y(), a_m.x() - a0_m.x());
  fb.coupler_design_rad_ = std::atan2(b_m.y() - a_m.y(), b_m.x() - a_m.x());
  const Eigen::Vector2d w = b0_m - a_m;
  const double side = wrap_pi(fb.coupler_design_rad_ - std::atan2(w.y(), w.x()));
  const double mu = angle_between(a_m - b_m, b0_m - b_m);
  require(mu > 1e-9 && mu < kPi - 1e-9,
          "four-bar: design position is a limit of assembly (transmission angle {} rad)", mu);
  fb.branch_ = side >= 0.0 ? 1 : -1;
  return fb;
}

std::size_t FourBar::add_coupler_point(const Eigen::Vector2d& p_design_m) {
  require(p_design_m.allFinite(), "four-bar: non-finite coupler point");
  const Eigen::Vector2d a = a0_ + a_len_ * unit(phi_design_);
  coupler_local_.push_back(Eigen::Rotation2Dd(-coupler_design_rad_) * (p_design_m - a));
  return coupler_local_.size() - 1;
}

GrashofClass FourBar::grashof() const {
  // Index: 0 ground, 1 crank, 2 coupler, 3 rocker.
  std::array<double, 4> len{ground_length_m(), a_len_, l2_, l3_};
  const auto shortest = static_cast<std::size_t>(
      std::min_element(len.begin(), len.end()) - len.begin());
  std::array<double, 4> sorted = len;
  std::sort(sorted.begin(), sorted.end());
  const double lhs = sorted[0] + sorted[3];
  const double rhs = sorted[1] + sorted[2];
  if (std::abs(lhs - rhs) <= 1e-12 * (lhs + rhs)) return GrashofClass::change_point;
  if (lhs > rhs) return GrashofClass::triple_rocker;
  switch (shortest) {
    case 0: return GrashofClass::double_crank;
    case 1: return GrashofClass::crank_rocker;
    case 2: return GrashofClass::double_rocker;
    default: return GrashofClass::rocker_crank;
  }
}

double FourBar::assembly_margin_m(double input_rad) const {
  const Eigen::Vector2d a = a0_ + a_len_ * unit(input_rad);
  const double dist = (b0_ - a).norm();
  return std::min(dist - std::abs(l2_ - l3_), l2_ + l3_ - dist);
}

FourBarPose FourBar::pose(double input_rad) const {
  require(std::isfinite(input_rad), "four-bar: input angle {} is not finite", input_rad);
  FourBarPose p;
  p.input_rad = input_rad;
  const double margin = assembly_margin_m(input_rad);
  require(margin > 0.0,
          "four-bar: cannot be assembled at input {:.6g} rad ({:.4g} deg; rotation {:.4g} deg "
          "from design): |A B0| is outside [|l2 - l3|, l2 + l3] by {:.3g} m",
          input_rad, input_rad * 180.0 / kPi, (input_rad - phi_design_) * 180.0 / kPi, -margin);
  p.a_m = a0_ + a_len_ * unit(input_rad);
  const Eigen::Vector2d w = b0_ - p.a_m;
  const double dist = w.norm();
  const double cos_g = std::clamp(
      (l2_ * l2_ + dist * dist - l3_ * l3_) / (2.0 * l2_ * dist), -1.0, 1.0);
  const double th2 = std::atan2(w.y(), w.x()) + branch_ * std::acos(cos_g);
  p.b_m = p.a_m + l2_ * unit(th2);
  const Eigen::Vector2d rb = p.b_m - b0_;
  const double th3 = std::atan2(rb.y(), rb.x());
  p.coupler_angle_rad = th2;
  p.rocker_angle_rad = th3;
  p.transmission_angle_rad = angle_between(p.a_m - p.b_m, b0_ - p.b_m);

  const Eigen::Vector2d a_d1 = a_len_ * unit_perp(input_rad);
  const Eigen::Vector2d a_d2 = -a_len_ * unit(input_rad);
  Eigen::Matrix2d jac;
  jac.col(0) = l2_ * unit_perp(th2);
  jac.col(1) = -l3_ * unit_perp(th3);
  const Eigen::PartialPivLU<Eigen::Matrix2d> lu(jac);
  const Eigen::Vector2d w1 = lu.solve(-a_d1);
  p.coupler_d1 = w1(0);
  p.rocker_d1 = w1(1);
  const Eigen::Vector2d rhs2 =
      -a_d2 + l2_ * w1(0) * w1(0) * unit(th2) - l3_ * w1(1) * w1(1) * unit(th3);
  const Eigen::Vector2d w2 = lu.solve(rhs2);
  p.coupler_d2 = w2(0);
  p.rocker_d2 = w2(1);

  p.coupler_points.reserve(coupler_local_.size());
  for (const auto& local : coupler_local_) {
    const Eigen::Vector2d rp = Eigen::Rotation2Dd(th2) * local;
    const Eigen::Vector2d jrp(-rp.y(), rp.x());
    PointKinematics k;
    k.p = p.a_m + rp;
    k.d1 = a_d1 + p.coupler_d1 * jrp;
    k.d2 = a_d2 + p.coupler_d2 * jrp - p.coupler_d1 * p.coupler_d1 * rp;
    p.coupler_points.push_back(k);
  }
  return p;
}

AssemblyRange FourBar::assembly_range(double step_rad, double tol_rad) const {
  require(step_rad > 0.0 && step_rad < kPi, "four-bar: assembly search step {} rad out of range",
          step_rad);
  require(tol_rad > 0.0, "four-bar: assembly search tolerance {} rad must be positive", tol_rad);
  AssemblyRange range;
  // A limit is a root of the margin; stepping finds the first sign change in each
  // direction. A limit where the margin only touches zero (change-point
  // linkages) within one step can be missed: the search then reports the next one.
  auto find_limit = [&](double direction, double& limit) {
    double inside = phi_design_;
    const auto steps = static_cast<int>(std::ceil(2.0 * kPi / step_rad));
    for (int i = 1; i <= steps; ++i) {
      const double trial = phi_design_ + direction * i * step_rad;
      if (assembly_margin_m(trial) <= 0.0) {
        double lo = inside, hi = trial;  // lo assembles, hi does not
        while (std::abs(hi - lo) > tol_rad) {
          const double mid = 0.5 * (lo + hi);
          (assembly_margin_m(mid) > 0.0 ? lo : hi) = mid;
        }
        limit = lo;
        return true;
      }
      inside = trial;
    }
    return false;
  };
  require(can_assemble(phi_design_), "four-bar: design position does not assemble");
  double lo = 0.0, hi = 0.0;
  const bool has_hi = find_limit(+1.0, hi);
  const bool has_lo = find_limit(-1.0, lo);
  if (!has_hi && !has_lo) {
    range.full_rotation = true;
    range.lo_rad = phi_design_ - kPi;
    range.hi_rad = phi_design_ + kPi;
    return range;
  }
  require(has_hi && has_lo,
          "four-bar: assembly limit found on one side of the design input only (step {} rad)",
          step_rad);
  range.lo_rad = lo;
  range.hi_rad = hi;
  return range;
}

FourBar make_equivalent_four_bar(const LeverChainGeometry& g) {
  FourBar fb = FourBar::from_design_position(
      Eigen::Vector2d(0.0, 0.0), Eigen::Vector2d(0.0, g.a_m), Eigen::Vector2d(g.r_m, g.a_m),
      Eigen::Vector2d(g.r_m, g.a_m - g.b0_m));
  fb.add_coupler_point(Eigen::Vector2d(-g.c_m, g.a_m));
  fb.add_coupler_point(Eigen::Vector2d(-g.c_m, g.a_m + g.h_m));
  return fb;
}

LeverVsFourBarStudy compare_lever_chain_with_four_bar(const LeverChainGeometry& geometry,
                                                      double dphi_lo_rad, double dphi_hi_rad,
                                                      std::size_t n, double window_length_m) {
  require(n >= 2, "lever/four-bar study: need at least 2 samples, got {}", n);
  require(dphi_lo_rad < 0.0 && dphi_hi_rad > 0.0,
          "lever/four-bar study: range [{}, {}] rad must contain the design position 0",
          dphi_lo_rad, dphi_hi_rad);
  const LeverChain chain(geometry);
  const FourBar fb = make_equivalent_four_bar(geometry);
  LeverVsFourBarStudy study;
  study.four_bar_range_dphi = fb.assembly_range();
  study.four_bar_range_dphi.lo_rad -= fb.design_input_rad();
  study.four_bar_range_dphi.hi_rad -= fb.design_input_rad();

  std::vector<Eigen::Vector2d> h_chain, h_fb;
  study.min_transmission_angle_four_bar_rad = kPi;
  study.max_transmission_angle_four_bar_rad = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / static_cast<double>(n - 1);
    LeverVsFourBarSample s;
    s.dphi_rad = dphi_lo_rad + t * (dphi_hi_rad - dphi_lo_rad);
    const LeverChainPose lc = chain.pose(s.dphi_rad);
    s.h_lever_chain_m = lc.h.p;
    s.transmission_angle_lever_chain_rad =
        angle_between(lc.a.p - lc.tangent_point.p, geometry.b0_point_m - lc.tangent_point.p);
    h_chain.push_back(s.h_lever_chain_m);
    // Only the assembled interval that contains the design position belongs to
    // the motion on the design branch.
    const bool inside = study.four_bar_range_dphi.full_rotation ||
                        (s.dphi_rad > study.four_bar_range_dphi.lo_rad &&
                         s.dphi_rad < study.four_bar_range_dphi.hi_rad);
    if (inside) {
      const FourBarPose p = fb.pose_at_rotation(s.dphi_rad);
      s.four_bar_assembles = true;
      s.h_four_bar_m = p.coupler_points[1].p;
      s.transmission_angle_four_bar_rad = p.transmission_angle_rad;
      h_fb.push_back(s.h_four_bar_m);
      study.min_transmission_angle_four_bar_rad =
          std::min(study.min_transmission_angle_four_bar_rad, p.transmission_angle_rad);
      study.max_transmission_angle_four_bar_rad =
          std::max(study.max_transmission_angle_four_bar_rad, p.transmission_angle_rad);
    }
    study.samples.push_back(s);
  }
  const double y_ref = geometry.a_m + geometry.h_m;
  study.h_lever_chain = horizontal_straightness(h_chain, window_length_m, y_ref);
  study.h_extent_lever_chain_m = horizontal_extent(h_chain);
  require(h_fb.size() >= 2, "lever/four-bar study: fewer than 2 four-bar samples assemble");
  study.h_four_bar = horizontal_straightness(h_fb, window_length_m, y_ref);
  study.h_extent_four_bar_m = horizontal_extent(h_fb);
  return study;
}

}  // namespace kinetofem::mech
