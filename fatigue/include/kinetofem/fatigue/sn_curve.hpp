#pragma once
// The EN 1993-1-9:2005 fatigue strength (S-N) curve for direct stress ranges,
// section 7.1(3) and figure 7.1.
//
// Units: stress ranges in Pa (the detail category is given in MPa = N/mm^2,
// as the standard's tables write it), endurance in cycles (double).
//
// Detail category Delta sigma_C: the reference fatigue strength at
// N_C = 2e6 cycles, one of the categories of tables 8.1 to 8.10:
//   160 140 125 112 100 90 80 71 63 56 50 45 40 36  (MPa).
// The curve (characteristic, without partial factors):
//   Delta sigma_R^3 N_R = Delta sigma_C^3 * 2e6          N_R <= 5e6 (m = 3)
//   Delta sigma_D = (2/5)^(1/3) Delta sigma_C = 0.737 Delta sigma_C
//                                  constant amplitude fatigue limit, N_D = 5e6
//   Delta sigma_R^5 N_R = Delta sigma_D^5 * 5e6    5e6 <= N_R <= 1e8 (m = 5)
//   Delta sigma_L = (5/100)^(1/5) Delta sigma_D = 0.549 Delta sigma_D
//                 = 0.405 Delta sigma_C              cut-off limit, N_L = 1e8
//   Delta sigma < Delta sigma_L: no damage (N infinite).
// The m = 3 line is used for every range above Delta sigma_D (the check of
// the range against the static strength, e.g. Delta sigma <= 1.5 f_y, is not
// part of this curve).
//
// Partial factors (EN 1993-1-9 section 3 and the verification of section 8):
// gamma_Ff on the stress range, gamma_Mf on the fatigue strength, each >= 1
// (gamma_Mf: EN 1993-1-9 table 3.1 or the National Annex). The design
// endurance of a range Delta sigma is the N where
//   gamma_Ff Delta sigma = Delta sigma_R(N) / gamma_Mf,
// i.e. the characteristic endurance of gamma_Ff gamma_Mf Delta sigma.
//
// Size effect (only for the details whose table entry gives k_s, e.g.
// transverse butt welds): Delta sigma_C,red = k_s Delta sigma_C,
// k_s = (25 mm / t)^0.2
// for t > 25 mm (thickness_size_factor); the whole curve scales with it.
#include <span>

namespace kinetofem::fatigue {

inline constexpr double kNc = 2e6;  // N_C: cycles of the detail category
inline constexpr double kNd = 5e6;  // N_D: constant amplitude fatigue limit
inline constexpr double kNl = 1e8;  // N_L: cut-off limit

// The detail categories of EN 1993-1-9 tables 8.1 to 8.10, MPa, descending.
std::span<const double> detail_categories_mpa();

// k_s = (25 mm / t)^0.2 for t > 25 mm, 1 otherwise (t in m). Error if t <= 0.
double thickness_size_factor(double thickness_m);

struct SnCurveSpec {
  double detail_category_mpa = 0.0;  // Delta sigma_C, one of detail_categories_mpa()
  double gamma_ff = 1.0;             // partial factor on the stress range, >= 1
  double gamma_mf = 1.0;             // partial factor on the fatigue strength, >= 1
  double size_factor = 1.0;          // k_s, 0 < k_s <= 1 (1: no size effect)
};

class SnCurve {
 public:
  // Error naming the value: a category not in the list (the message lists
  // them), gamma_Ff or gamma_Mf below 1 (or not finite), k_s outside (0, 1].
  explicit SnCurve(const SnCurveSpec& spec);

  const SnCurveSpec& spec() const { return spec_; }
  // Characteristic values (with k_s, without partial factors), Pa.
  double detail_category_pa() const { return delta_sigma_c_pa_; }          // Delta sigma_C(,red)
  double constant_amplitude_limit_pa() const { return delta_sigma_d_pa_; }  // Delta sigma_D
  double cut_off_limit_pa() const { return delta_sigma_l_pa_; }             // Delta sigma_L

  // N_R(Delta sigma) of the characteristic curve; infinity below
  // Delta sigma_L (and for a zero range). Error if the range is negative or
  // not finite.
  double characteristic_endurance(double range_pa) const;
  // The design endurance: characteristic_endurance(gamma_Ff gamma_Mf range).
  double endurance(double range_pa) const;

 private:
  SnCurveSpec spec_;
  double delta_sigma_c_pa_ = 0.0;
  double delta_sigma_d_pa_ = 0.0;
  double delta_sigma_l_pa_ = 0.0;
};

}  // namespace kinetofem::fatigue
