#include "kinetofem/verification/spec2_four_bar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace kinetofem::verification::spec2 {

double crank_pin_to_b0_m(const mech::LeverChainGeometry& g, double phi_rad) {
  return std::sqrt(g.a_m * g.a_m + g.l0_m * g.l0_m - 2 * g.a_m * g.l0_m * std::cos(phi_rad - g.alpha0_rad));
}

AssemblyLimits closed_form_assembly_limits(const mech::LeverChainGeometry& g, const mech::FourBar& four_bar) {
  const double design = four_bar.design_input_rad();
  AssemblyLimits limits{-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  for (double dist : {four_bar.coupler_length_m() + four_bar.rocker_length_m(),
                      std::abs(four_bar.coupler_length_m() - four_bar.rocker_length_m())}) {
    // |A B0| = dist: cos(phi - alpha0) = (a^2 + l0^2 - dist^2) / (2 a l0).
    const double c = (g.a_m * g.a_m + g.l0_m * g.l0_m - dist * dist) / (2 * g.a_m * g.l0_m);
    if (std::abs(c) > 1) continue;
    for (double s : {-1.0, 1.0}) {
      double phi = g.alpha0_rad + s * std::acos(c);
      phi = design + std::remainder(phi - design, 2 * std::numbers::pi);
      if (phi < design) limits.lo_rad = std::max(limits.lo_rad, phi);
      else limits.hi_rad = std::min(limits.hi_rad, phi);
    }
  }
  return limits;
}

}  // namespace kinetofem::verification::spec2
