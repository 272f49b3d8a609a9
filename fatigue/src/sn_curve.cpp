#include "kinetofem/fatigue/sn_curve.hpp"

#include <array>
#include <cmath>
#include <limits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"

namespace kinetofem::fatigue {

namespace {

constexpr std::array<double, 14> kCategories = {160, 140, 125, 112, 100, 90, 80,
                                                71,  63,  56,  50,  45,  40, 36};

}  // namespace

std::span<const double> detail_categories_mpa() { return kCategories; }

double thickness_size_factor(double thickness_m) {
  require(std::isfinite(thickness_m) && thickness_m > 0.0,
          "fatigue: thickness {} m for the size effect k_s must be > 0", thickness_m);
  const double reference_m = 25.0 * units::kMm;
  return thickness_m > reference_m ? std::pow(reference_m / thickness_m, 0.2) : 1.0;
}

SnCurve::SnCurve(const SnCurveSpec& spec) : spec_(spec) {
  bool listed = false;
  for (double c : kCategories) {
    listed = listed || std::abs(spec.detail_category_mpa - c) <= 1e-9 * c;
  }
  require(listed,
          "fatigue: detail category {} MPa is not one of EN 1993-1-9 tables 8.1-8.10 ({} MPa)",
          spec.detail_category_mpa, fmt::join(kCategories, ", "));
  require(std::isfinite(spec.gamma_ff) && spec.gamma_ff >= 1.0,
          "fatigue: partial factor gamma_Ff = {} must be >= 1", spec.gamma_ff);
  require(std::isfinite(spec.gamma_mf) && spec.gamma_mf >= 1.0,
          "fatigue: partial factor gamma_Mf = {} must be >= 1", spec.gamma_mf);
  require(std::isfinite(spec.size_factor) && spec.size_factor > 0.0 && spec.size_factor <= 1.0,
          "fatigue: size factor k_s = {} must be in (0, 1]", spec.size_factor);
  delta_sigma_c_pa_ = spec.size_factor * spec.detail_category_mpa * units::kMpa;
  delta_sigma_d_pa_ = std::cbrt(kNc / kNd) * delta_sigma_c_pa_;          // (2/5)^(1/3)
  delta_sigma_l_pa_ = std::pow(kNd / kNl, 0.2) * delta_sigma_d_pa_;      // (5/100)^(1/5)
}

double SnCurve::characteristic_endurance(double range_pa) const {
  require(std::isfinite(range_pa) && range_pa >= 0.0,
          "fatigue: stress range {} Pa must be finite and >= 0", range_pa);
  if (range_pa < delta_sigma_l_pa_) return std::numeric_limits<double>::infinity();
  if (range_pa >= delta_sigma_d_pa_) {
    const double r = delta_sigma_c_pa_ / range_pa;
    return kNc * r * r * r;
  }
  const double r = delta_sigma_d_pa_ / range_pa;
  const double r2 = r * r;
  return kNd * r2 * r2 * r;
}

double SnCurve::endurance(double range_pa) const {
  require(std::isfinite(range_pa) && range_pa >= 0.0,
          "fatigue: stress range {} Pa must be finite and >= 0", range_pa);
  return characteristic_endurance(spec_.gamma_ff * spec_.gamma_mf * range_pa);
}

}  // namespace kinetofem::fatigue
