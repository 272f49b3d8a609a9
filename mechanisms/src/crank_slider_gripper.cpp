#include "kinetofem/mechanisms/crank_slider_gripper.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {
namespace {

constexpr double kPi = std::numbers::pi;

void check_parameters(double sigma, double gamma) {
  require(std::isfinite(sigma) && sigma > 0.0, "gripper: sigma = r/l = {} must be positive",
          sigma);
  require(std::isfinite(gamma), "gripper: gamma = e/l = {} is not finite", gamma);
}

// |cos(phi)| below this is treated as the tan singularity at 90 deg.
constexpr double kCosFloor = 1e-12;

bool criterion_holds(double phi, double sigma, double gamma, const GripperRangeOptions& o) {
  if (!gripper_assembles(phi, sigma, gamma) || std::abs(std::cos(phi)) < kCosFloor) return false;
  const double u = std::abs(gripper_index_offset(phi, sigma, gamma));
  if (!(std::abs(u - 1.0) <= o.tolerance)) return false;
  if (!o.pressure_limits) return true;
  return std::abs(gripper_pressure_angle_slider_rad(phi, sigma, gamma)) <= o.theta12_limit_rad &&
         std::abs(gripper_pressure_angle_rod_rocker_rad(phi, sigma, gamma)) <=
             o.theta23_limit_rad;
}

}  // namespace

double gripper_index_central(double phi_rad, double sigma) {
  check_parameters(sigma, 0.0);
  const double s = std::sin(phi_rad), c = std::cos(phi_rad);
  const double root_sq = 1.0 - sigma * sigma * s * s;
  require(root_sq > 0.0, "gripper: central crank-slider does not assemble at phi = {} rad "
                         "(sigma sin(phi) = {})", phi_rad, sigma * s);
  require(std::abs(c) >= kCosFloor, "gripper: index (4) is singular at phi = {} rad", phi_rad);
  return -(1.0 + sigma * c / std::sqrt(root_sq)) * std::tan(phi_rad);
}

bool gripper_assembles(double phi_rad, double sigma, double gamma) {
  const double q = std::sin(phi_rad) - gamma;
  return sigma > 0.0 && sigma * sigma * q * q < 1.0;
}

double gripper_index_offset(double phi_rad, double sigma, double gamma) {
  check_parameters(sigma, gamma);
  const double q = std::sin(phi_rad) - gamma;
  const double root_sq = 1.0 / (sigma * sigma) - q * q;
  require(root_sq > 0.0,
          "gripper: offset crank-slider does not assemble at phi = {} rad (sigma = {}, gamma = "
          "{}: sigma |sin(phi) - gamma| >= 1)",
          phi_rad, sigma, gamma);
  require(std::abs(std::cos(phi_rad)) >= kCosFloor,
          "gripper: index (6) is singular at phi = {} rad", phi_rad);
  return -std::tan(phi_rad) - q / std::sqrt(root_sq);
}

double gripper_pressure_angle_slider_rad(double phi_rad, double sigma, double gamma) {
  check_parameters(sigma, gamma);
  const double arg = gamma - sigma * std::sin(phi_rad);
  require(std::abs(arg) <= 1.0,
          "gripper: pressure angle (9) undefined at phi = {} rad (gamma - sigma sin(phi) = {})",
          phi_rad, arg);
  return std::asin(arg);
}

double gripper_pressure_angle_rod_rocker_rad(double phi_rad, double sigma, double gamma) {
  return phi_rad - gripper_pressure_angle_slider_rad(phi_rad, sigma, gamma) - 0.5 * kPi;
}

std::vector<PhiInterval> gripper_operating_ranges(double sigma, double gamma,
                                                  const GripperRangeOptions& o) {
  check_parameters(sigma, gamma);
  require(o.tolerance > 0.0, "gripper: tolerance {} must be positive", o.tolerance);
  require(o.phi_hi_rad > o.phi_lo_rad, "gripper: empty phi window [{}, {}] rad", o.phi_lo_rad,
          o.phi_hi_rad);
  require(o.step_rad > 0.0 && o.boundary_tol_rad > 0.0, "gripper: step and tolerance must be "
                                                         "positive");
  auto holds = [&](double phi) { return criterion_holds(phi, sigma, gamma, o); };
  // Bisection of a boundary between a sample where the criterion holds and one
  // where it does not; returns the last point where it holds.
  auto boundary = [&](double inside, double outside) {
    while (std::abs(outside - inside) > o.boundary_tol_rad) {
      const double mid = 0.5 * (inside + outside);
      (holds(mid) ? inside : outside) = mid;
    }
    return inside;
  };
  const auto n = static_cast<std::size_t>(std::ceil((o.phi_hi_rad - o.phi_lo_rad) / o.step_rad));
  std::vector<PhiInterval> ranges;
  double prev_phi = o.phi_lo_rad;
  bool prev = holds(prev_phi);
  double start = prev_phi;
  for (std::size_t k = 1; k <= n; ++k) {
    const double phi = std::min(o.phi_hi_rad, o.phi_lo_rad + static_cast<double>(k) * o.step_rad);
    const bool now = holds(phi);
    if (now && !prev) start = boundary(phi, prev_phi);
    if (!now && prev) ranges.push_back({start, boundary(prev_phi, phi)});
    prev = now;
    prev_phi = phi;
  }
  if (prev) ranges.push_back({start, prev_phi});
  return ranges;
}

std::vector<PhiInterval> gripper_operating_ranges_central(double sigma,
                                                          const GripperRangeOptions& options) {
  return gripper_operating_ranges(sigma, 0.0, options);
}

PhiInterval widest(const std::vector<PhiInterval>& ranges) {
  PhiInterval best;
  for (const auto& r : ranges)
    if (r.width_rad() > best.width_rad()) best = r;
  return best;
}

PhiInterval operating_hull(const std::vector<PhiInterval>& ranges) {
  if (ranges.empty()) return {};
  return {ranges.front().lo_rad, ranges.back().hi_rad};
}

GripperDesign search_widest_gripper_design(const GripperDesignSearch& s) {
  require(s.sigma_hi > s.sigma_lo && s.sigma_lo > 0.0,
          "gripper design search: bad sigma range [{}, {}]", s.sigma_lo, s.sigma_hi);
  require(s.gamma_hi > s.gamma_lo, "gripper design search: bad gamma range [{}, {}]", s.gamma_lo,
          s.gamma_hi);
  require(s.n_sigma >= 2 && s.n_gamma >= 2, "gripper design search: need >= 2 grid points");
  GripperDesign best;
  double s_lo = s.sigma_lo, s_hi = s.sigma_hi, g_lo = s.gamma_lo, g_hi = s.gamma_hi;
  for (std::size_t level = 0; level <= s.refinements; ++level) {
    const double ds = (s_hi - s_lo) / static_cast<double>(s.n_sigma - 1);
    const double dg = (g_hi - g_lo) / static_cast<double>(s.n_gamma - 1);
    for (std::size_t i = 0; i < s.n_sigma; ++i) {
      const double sigma = s_lo + ds * static_cast<double>(i);
      if (sigma < s.sigma_lo || sigma > s.sigma_hi) continue;
      for (std::size_t j = 0; j < s.n_gamma; ++j) {
        const double gamma = g_lo + dg * static_cast<double>(j);
        if (gamma < s.gamma_lo || gamma > s.gamma_hi) continue;
        if (s.offset_within_crank && gamma > sigma) continue;
        const PhiInterval w = widest(gripper_operating_ranges(sigma, gamma, s.range));
        ++best.evaluations;
        if (w.width_rad() > best.range.width_rad()) {
          best.sigma = sigma;
          best.gamma = gamma;
          best.range = w;
        }
      }
    }
    if (best.range.width_rad() <= 0.0) break;
    s_lo = best.sigma - ds;
    s_hi = best.sigma + ds;
    g_lo = best.gamma - dg;
    g_hi = best.gamma + dg;
  }
  return best;
}

GripperDimensions gripper_dimensions_from_offset(double e_m, double sigma, double gamma) {
  check_parameters(sigma, gamma);
  require(std::isfinite(e_m) && e_m > 0.0, "gripper: offset e = {} m must be positive", e_m);
  require(gamma > 0.0, "gripper: gamma = {} must be positive to size from the offset", gamma);
  GripperDimensions d;
  d.e_m = e_m;
  d.l_m = e_m / gamma;
  d.r_m = sigma * d.l_m;
  return d;
}

double gripper_jaw_travel_m(double r_m, double phi1_rad, double phi2_rad) {
  require(std::isfinite(r_m) && r_m > 0.0, "gripper: crank radius r = {} m must be positive",
          r_m);
  return 2.0 * r_m * std::abs(std::sin(phi2_rad) - std::sin(phi1_rad));
}

GripperObjectRange gripper_object_range(double open_m, double r_m, double phi1_rad, double phi2_rad) {
  require(std::isfinite(open_m) && open_m > 0.0, "gripper: jaw opening {} m must be positive", open_m);
  require(phi1_rad < phi2_rad && phi1_rad >= 0.5 * std::numbers::pi && phi2_rad <= std::numbers::pi,
          "gripper: the operating range {}..{} deg must be an interval of the second quadrant", phi1_rad * 180.0 / std::numbers::pi,
          phi2_rad * 180.0 / std::numbers::pi);
  return {open_m - gripper_jaw_travel_m(r_m, phi1_rad, phi2_rad), open_m};
}

double gripper_clamp_angle_rad(double thickness_m, double open_m, double r_m, double phi1_rad, double phi2_rad) {
  const GripperObjectRange range = gripper_object_range(open_m, r_m, phi1_rad, phi2_rad);
  require(std::isfinite(thickness_m) && thickness_m >= range.thickness_min_m && thickness_m <= range.thickness_max_m,
          "gripper: an object {} mm thick is outside the jaws' range {:.2f}..{:.2f} mm", thickness_m * 1e3,
          range.thickness_min_m * 1e3, range.thickness_max_m * 1e3);
  // sin falls monotonically from phi1 to phi2 in the second quadrant; clamp
  // the argument against round-off at the ends.
  const double s = std::clamp(std::sin(phi2_rad) + (open_m - thickness_m) / (2.0 * r_m), std::sin(phi2_rad), std::sin(phi1_rad));
  return std::numbers::pi - std::asin(s);
}

}  // namespace kinetofem::mech
