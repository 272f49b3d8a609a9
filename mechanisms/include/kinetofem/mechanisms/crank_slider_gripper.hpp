#pragma once
// Crank-slider gripper synthesis by the energy transmission index (SPEC §6;
// source seeds/004, Pogrebnyak & Pogrebnyak 2019).
//
// A driving slider 1 moves, through rods 2, rockers 3 (crank radius r) whose
// jaws clamp the object; l is the rod length, e the offset ("de-axial") of the
// slider line. Dimensionless: sigma = r/l, gamma = e/l; phi = crank (rocker)
// angle, in the source's convention, for which the useful zone is the second
// quadrant 90 < phi < 180 deg ("such functions exist only in the second
// quadrant"). The index U_V = V_out cos(alpha) / V_in should stay near 1 so
// that the clamping force equals the drive force for every object size.
//
//   central (e = 0):  U_V = -(1 + sigma cos(phi)/sqrt(1 - sigma^2 sin^2 phi)) tan(phi)   (4)
//   offset:           U_V = -tan(phi) - (sin(phi) - gamma)/sqrt(1/sigma^2 - (sin(phi) - gamma)^2)  (6)
//   r = e (gamma = sigma, since gamma/sigma = e/r):  (6) becomes (7)
//   pressure angle slider-guide:  theta12 = asin(gamma - sigma sin(phi))   (9)
//                                 (8): theta12 = asin(sigma (1 - sin phi)) for r = e
//   pressure angle rod-rocker:    theta23 = phi - theta12 - 90 deg         (10)
//   limits |theta12| <= 30 deg, |theta23| <= 45 deg.
//
// Conventions pinned from the source: (6) and (9) are used exactly as printed,
// since the published ranges come from them. Note a source inconsistency: (6)
// equals the velocity ratio (5) divided by cos(phi) only with the offset
// e = -gamma r (gamma normalised by r, opposite sign), whereas (9) and the
// design formulas (l = r/sigma, e = gamma r/sigma) take gamma = e/l. The two
// agree only for sigma = 1; our results follow the printed formulas. In the
// first quadrant U_V < 0 for the central
// mechanism (the source's fig. 2 plots |U_V|, "two symmetric zones"), so the
// criterion is applied to |U_V|: |U_V| in [1 - tol, 1 + tol]. The mechanism
// assembles where sigma^2 (sin(phi) - gamma)^2 < 1; (4), (6) are singular at
// phi = 90 deg (tan).
//
// Published results (SPEC §6): r = e, sigma = gamma = 0.905: 142 < phi < 170
// deg, 142..154 with the theta12 limit; sigma = 1.1, gamma = 0.82: 139..165 deg,
// 139..163 with the theta12 limit. With the printed (rounded) sigma = 1.1,
// gamma = 0.82, U_V dips to 0.9493 at phi = 152.7 deg, just under 0.95, so the
// strict criterion splits that range in two (139.2..151.6 and 153.8..164.9):
// the source reads the curve at plotting resolution. operating_ranges reports
// the intervals as they are; operating_hull gives first entry .. last exit.
#include <cstddef>
#include <vector>

namespace kinetofem::mech {

double gripper_index_central(double phi_rad, double sigma);               // (4)
double gripper_index_offset(double phi_rad, double sigma, double gamma);  // (6)
bool gripper_assembles(double phi_rad, double sigma, double gamma);
double gripper_pressure_angle_slider_rad(double phi_rad, double sigma, double gamma);     // (9)
double gripper_pressure_angle_rod_rocker_rad(double phi_rad, double sigma, double gamma); // (10)

struct PhiInterval {
  double lo_rad = 0.0;
  double hi_rad = 0.0;
  double width_rad() const { return hi_rad - lo_rad; }
};

struct GripperRangeOptions {
  double tolerance = 0.05;             // |U_V| in [1 - tol, 1 + tol]
  bool pressure_limits = false;        // also require |theta12|, |theta23| within limits
  double theta12_limit_rad = 30.0 * 3.141592653589793 / 180.0;
  double theta23_limit_rad = 45.0 * 3.141592653589793 / 180.0;
  double phi_lo_rad = 90.0 * 3.141592653589793 / 180.0;   // search window (second quadrant)
  double phi_hi_rad = 180.0 * 3.141592653589793 / 180.0;
  double step_rad = 0.05 * 3.141592653589793 / 180.0;     // sampling step before bisection
  double boundary_tol_rad = 1e-10;
};

// Contiguous phi intervals where the criterion holds, in increasing phi; each
// boundary is bisected to boundary_tol_rad. The central mechanism is gamma = 0
// with (4), which equals (6) at gamma = 0.
std::vector<PhiInterval> gripper_operating_ranges(double sigma, double gamma,
                                                  const GripperRangeOptions& options = {});
std::vector<PhiInterval> gripper_operating_ranges_central(double sigma,
                                                          const GripperRangeOptions& options = {});
// Widest interval (zero width if none).
PhiInterval widest(const std::vector<PhiInterval>& ranges);
// From the first interval's start to the last one's end (zero width if none).
PhiInterval operating_hull(const std::vector<PhiInterval>& ranges);

// Grid search over sigma x gamma for the widest single interval, then
// `refinements` zooms: each new grid spans +- one previous step around the
// best point. offset_within_crank restricts to e <= r (gamma <= sigma), the
// source's search region ("the offset smaller than the crank").
struct GripperDesignSearch {
  double sigma_lo = 0.5, sigma_hi = 2.0;
  double gamma_lo = 0.0, gamma_hi = 1.0;
  std::size_t n_sigma = 31, n_gamma = 31;
  std::size_t refinements = 3;
  bool offset_within_crank = true;
  GripperRangeOptions range;
};
struct GripperDesign {
  double sigma = 0.0;
  double gamma = 0.0;
  PhiInterval range;
  std::size_t evaluations = 0;
};
GripperDesign search_widest_gripper_design(const GripperDesignSearch& search);

// Dimensions from the offset e (the source's compact choice e = H_max / 2):
// l = e / gamma, r = sigma l.
struct GripperDimensions {
  double r_m = 0.0;
  double l_m = 0.0;
  double e_m = 0.0;
};
GripperDimensions gripper_dimensions_from_offset(double e_m, double sigma, double gamma);
// Jaw travel along the clamping direction between two crank angles:
// h = 2 r |sin(phi2) - sin(phi1)| (both jaws).
double gripper_jaw_travel_m(double r_m, double phi1_rad, double phi2_rad);

// The objects the jaws hold over an operating range phi1 < phi2 (second
// quadrant, where the jaws close as phi falls): they are open_m apart at phi2
// (the source's compact choice: open_m = 2 e = H_max) and close by the jaw
// travel toward phi1, so thickness_min = open_m - jaw travel, thickness_max =
// open_m (m).
struct GripperObjectRange {
  double thickness_min_m = 0.0;
  double thickness_max_m = 0.0;
};
GripperObjectRange gripper_object_range(double open_m, double r_m, double phi1_rad, double phi2_rad);
// The crank angle at which the jaws hold an object of thickness H in that
// range: sin(phi) = sin(phi2) + (open_m - H) / (2 r), phi in the second
// quadrant. Throws, naming H and the range, outside it.
double gripper_clamp_angle_rad(double thickness_m, double open_m, double r_m, double phi1_rad, double phi2_rad);

}  // namespace kinetofem::mech
