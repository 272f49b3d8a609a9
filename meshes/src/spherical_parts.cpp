#include "kinetofem/meshes/spherical_parts.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <tuple>
#include <utility>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/geometry_text.hpp"

namespace kinetofem::meshes {

namespace {

constexpr double pi = std::numbers::pi;

void require_positive(std::string_view what, std::initializer_list<std::pair<const char*, double>> values) {
  for (const auto& [name, value] : values)
    require(std::isfinite(value) && value > 0, "{} {} = {} must be positive", what, name, value);
}

// J(a, r) = integral_{-a}^{a} 2 sqrt(a^2 - z^2) sqrt(r^2 - z^2) dz (a < r): the
// volume of the cylinder x^2 + z^2 <= a^2 below the cylinder y^2 + z^2 = r^2
// (y >= 0). With z = a sin(theta) the integrand 2 a^2 cos^2 sqrt(r^2 - a^2 sin^2)
// is smooth and pi-periodic, so the trapezoidal rule over one period converges
// exponentially: 256 points reach rounding for a/r < 0.9.
double shoulder_inside_tube(double a, double r) {
  const int n = 256;
  double sum = 0;
  for (int k = 0; k < n; ++k) {
    const double theta = -pi / 2 + pi * k / n;
    const double s = std::sin(theta), c = std::cos(theta);
    sum += 2 * a * a * c * c * std::sqrt(r * r - a * a * s * s);
  }
  return sum * pi / n;
}

// The wall t in [lo, hi] whose volume(t) (increasing) is target_m3, or the
// limit that comes nearest, with the rule that chose it.
std::pair<double, WallRule> wall_for_volume(const std::function<double(double)>& volume, double target_m3,
                                            double lo, double hi) {
  if (volume(lo) >= target_m3) return {lo, volume(lo) > target_m3 ? WallRule::MinimumWall : WallRule::MassMet};
  if (volume(hi) < target_m3) return {hi, WallRule::MaximumWall};
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (volume(mid) < target_m3 ? lo : hi) = mid;
  }
  return {0.5 * (lo + hi), WallRule::MassMet};
}

}  // namespace

std::string_view wall_rule_name(WallRule rule) {
  switch (rule) {
    case WallRule::MassMet: return "mass met";
    case WallRule::MinimumWall: return "minimum wall (heavier than the target)";
    case WallRule::MaximumWall: return "maximum wall (lighter than the target)";
  }
  return "?";
}

std::string_view spherical_part_name(SphericalPart part) {
  switch (part) {
    case SphericalPart::Column: return "column";
    case SphericalPart::Sleeve: return "sleeve";
    case SphericalPart::Arm: return "arm";
  }
  return "?";
}

void SphericalPartSizing::validate() const {
  require_positive("spherical part sizing",
                   {{"arm_length_m", arm_length_m}, {"sleeve_length_m", sleeve_length_m},
                    {"sleeve_diameter_m", sleeve_diameter_m}, {"base_diameter_m", base_diameter_m},
                    {"height_a_m", height_a_m}, {"height_b_m", height_b_m}, {"reach_min_m", reach_min_m},
                    {"reach_max_m", reach_max_m}, {"column_mass_kg", column_mass_kg},
                    {"sleeve_mass_kg", sleeve_mass_kg}, {"arm_mass_kg", arm_mass_kg}});
  require(std::isfinite(tilt_max_rad) && tilt_max_rad >= 0 && tilt_max_rad < pi / 2,
          "spherical part sizing tilt_max_rad = {} must be in [0, pi/2)", tilt_max_rad);
  require(height_a_m < height_b_m, "spherical part sizing height_a_m = {} must be below height_b_m = {}",
          height_a_m, height_b_m);
  require(reach_min_m < reach_max_m, "spherical part sizing reach_min_m = {} must be below reach_max_m = {}",
          reach_min_m, reach_max_m);
  // The arm must reach r_Mmax with its rear end still in the sleeve.
  require(arm_length_m > reach_max_m + 0.5 * sleeve_length_m,
          "spherical part sizing arm_length_m = {} must exceed reach_max_m + sleeve_length_m/2 = {} (SPEC §5: "
          "l1 = r_Mmax + 0.5 l2 + 0.1 m)",
          arm_length_m, reach_max_m + 0.5 * sleeve_length_m);
  require(reach_min_m > 0.5 * sleeve_length_m,
          "spherical part sizing reach_min_m = {} must exceed sleeve_length_m/2 = {} (M would be inside the sleeve)",
          reach_min_m, 0.5 * sleeve_length_m);
}

void SphericalPartRules::validate() const {
  require_positive("spherical part rule",
                   {{"density_kg_m3", density_kg_m3}, {"arm_diameter_ratio", arm_diameter_ratio},
                    {"guide_length_ratio", guide_length_ratio}, {"pin_diameter_ratio", pin_diameter_ratio},
                    {"shoulder_diameter_ratio", shoulder_diameter_ratio},
                    {"shoulder_gap_ratio", shoulder_gap_ratio}, {"cheek_thickness_ratio", cheek_thickness_ratio},
                    {"lug_width_ratio", lug_width_ratio}, {"end_plate_ratio", end_plate_ratio},
                    {"flange_thickness_m", flange_thickness_m}, {"top_plate_thickness_m", top_plate_thickness_m},
                    {"seat_length_m", seat_length_m}, {"seat_collar_m", seat_collar_m},
                    {"lug_margin_m", lug_margin_m}, {"tilt_clearance_m", tilt_clearance_m},
                    {"min_wall_m", min_wall_m}, {"max_wall_fraction", max_wall_fraction},
                    {"min_relief_m", min_relief_m}});
  require(arm_diameter_ratio < 1, "spherical part rule arm_diameter_ratio = {} must be below 1", arm_diameter_ratio);
  require(max_wall_fraction <= 1, "spherical part rule max_wall_fraction = {} must not exceed 1", max_wall_fraction);
  require(shoulder_diameter_ratio > 1, "spherical part rule shoulder_diameter_ratio = {} must exceed 1",
          shoulder_diameter_ratio);
}

void SphericalColumnDimensions::validate() const {
  require_positive("spherical column dimension",
                   {{"flange_radius_m", flange_radius_m}, {"flange_thickness_m", flange_thickness_m},
                    {"outer_radius_m", outer_radius_m}, {"wall_m", wall_m}, {"top_m", top_m},
                    {"top_plate_thickness_m", top_plate_thickness_m}, {"seat_height_m", seat_height_m},
                    {"seat_length_m", seat_length_m}, {"seat_collar_m", seat_collar_m},
                    {"pin_height_m", pin_height_m}, {"pin_diameter_m", pin_diameter_m},
                    {"cheek_inner_y_m", cheek_inner_y_m}, {"cheek_thickness_m", cheek_thickness_m},
                    {"lug_width_m", lug_width_m}});
  require(wall_m < outer_radius_m, "spherical column wall_m = {} must be smaller than outer_radius_m = {}", wall_m,
          outer_radius_m);
  require(top_m - top_plate_thickness_m > flange_thickness_m,
          "spherical column top_m = {} leaves no tube between the flange and the top plate (t_f + t_top = {})", top_m,
          flange_thickness_m + top_plate_thickness_m);
  require(seat_height_m - seat_length_m / 2 > flange_thickness_m && seat_height_m + seat_length_m / 2 < top_m,
          "spherical column seat_height_m = {} must put the seat (length {}) between the flange (t_f = {}) and the "
          "top z_top = {}",
          seat_height_m, seat_length_m, flange_thickness_m, top_m);
  const double y_out = cheek_inner_y_m + cheek_thickness_m;
  require(std::hypot(y_out, lug_width_m / 2) < outer_radius_m,
          "spherical column outer_radius_m = {} must exceed the lugs' corner radius {} (the lugs stand on the top "
          "plate)",
          outer_radius_m, std::hypot(y_out, lug_width_m / 2));
  require(pin_diameter_m < lug_width_m, "spherical column pin_diameter_m = {} must be smaller than lug_width_m = {}",
          pin_diameter_m, lug_width_m);
  require(pin_height_m - top_m >= lug_width_m / 2,
          "spherical column pin_height_m = {} must be at least lug_width_m/2 above top_m = {}", pin_height_m, top_m);
  require(flange_radius_m > outer_radius_m + seat_collar_m,
          "spherical column flange_radius_m = {} must exceed outer_radius_m + seat_collar_m = {}", flange_radius_m,
          outer_radius_m + seat_collar_m);
}

double SphericalColumnDimensions::volume_m3() const {
  const double r1 = outer_radius_m, ri = r1 - wall_m, rc = r1 + seat_collar_m, w = lug_width_m;
  const double lug = cheek_thickness_m * (w * (pin_height_m - top_m) + pi * w * w / 8 -
                                          pi * pin_diameter_m * pin_diameter_m / 4);
  return pi * flange_radius_m * flange_radius_m * flange_thickness_m + pi * r1 * r1 * (top_m - flange_thickness_m) -
         pi * ri * ri * (top_m - top_plate_thickness_m - flange_thickness_m) +
         pi * (rc * rc - r1 * r1) * seat_length_m + 2 * lug;
}

void SphericalSleeveDimensions::validate() const {
  require_positive("spherical sleeve dimension",
                   {{"length_m", length_m}, {"outer_diameter_m", outer_diameter_m}, {"wall_m", wall_m},
                    {"guide_diameter_m", guide_diameter_m}, {"guide_length_m", guide_length_m},
                    {"pin_diameter_m", pin_diameter_m}, {"shoulder_diameter_m", shoulder_diameter_m},
                    {"journal_start_y_m", journal_start_y_m}, {"journal_length_m", journal_length_m}});
  const double r2 = outer_diameter_m / 2;
  require(r2 - wall_m > guide_diameter_m / 2,
          "spherical sleeve wall_m = {} must leave the relief bore wider than guide_diameter_m = {} (outer diameter "
          "{})",
          wall_m, guide_diameter_m, outer_diameter_m);
  require(2 * guide_length_m < length_m, "spherical sleeve guide_length_m = {} must be below length_m/2 = {}",
          guide_length_m, length_m / 2);
  require(pin_diameter_m < shoulder_diameter_m,
          "spherical sleeve pin_diameter_m = {} must be smaller than shoulder_diameter_m = {}", pin_diameter_m,
          shoulder_diameter_m);
  // The shoulder stands on the tube over the relief, clear of the guide lands.
  require(shoulder_diameter_m / 2 < r2 && shoulder_diameter_m / 2 < length_m / 2 - guide_length_m,
          "spherical sleeve shoulder_diameter_m = {} must be smaller than the outer diameter {} and than the relief's "
          "length {}",
          shoulder_diameter_m, outer_diameter_m, length_m - 2 * guide_length_m);
  require(journal_start_y_m > r2, "spherical sleeve journal_start_y_m = {} must be outside the tube (d2/2 = {})",
          journal_start_y_m, r2);
}

double SphericalSleeveDimensions::volume_m3() const {
  const double r2 = outer_diameter_m / 2, rg = guide_diameter_m / 2, rr = r2 - wall_m;
  const double a = shoulder_diameter_m / 2, rj = pin_diameter_m / 2;
  const double tube = pi * r2 * r2 * length_m - pi * rg * rg * 2 * guide_length_m -
                      pi * rr * rr * (length_m - 2 * guide_length_m);
  const double shoulders = 2 * (pi * a * a * journal_start_y_m - shoulder_inside_tube(a, r2));
  return tube + shoulders + 2 * pi * rj * rj * journal_length_m;
}

void SphericalArmDimensions::validate() const {
  require_positive("spherical arm dimension",
                   {{"length_m", length_m}, {"outer_diameter_m", outer_diameter_m}, {"wall_m", wall_m},
                    {"end_plate_thickness_m", end_plate_thickness_m}});
  require(wall_m < outer_diameter_m / 2, "spherical arm wall_m = {} must be smaller than outer_diameter_m/2 = {}",
          wall_m, outer_diameter_m / 2);
  require(std::isfinite(slide_from_m) && std::isfinite(slide_to_m) && -length_m < slide_from_m &&
              slide_from_m < slide_to_m && slide_to_m < -end_plate_thickness_m,
          "spherical arm slide_from_m = {}, slide_to_m = {} must satisfy -length_m = {} < slide_from_m < slide_to_m "
          "< -end_plate_thickness_m = {}",
          slide_from_m, slide_to_m, -length_m, -end_plate_thickness_m);
}

double SphericalArmDimensions::volume_m3() const {
  const double r3 = outer_diameter_m / 2, ri = r3 - wall_m;
  return pi * r3 * r3 * length_m - pi * ri * ri * (length_m - end_plate_thickness_m);
}

void SphericalPartDimensions::validate() const {
  column.validate();
  sleeve.validate();
  arm.validate();
  require(std::isfinite(density_kg_m3) && density_kg_m3 > 0, "spherical parts density_kg_m3 = {} must be positive",
          density_kg_m3);
  // Mating faces: the column's bores hold the sleeve's journals, the sleeve's
  // guide lands the arm.
  require(column.pin_diameter_m == sleeve.pin_diameter_m && column.cheek_inner_y_m == sleeve.journal_start_y_m &&
              column.cheek_thickness_m == sleeve.journal_length_m,
          "spherical parts: the column's pin bores (d {}, y {} + {}) and the sleeve's journals (d {}, y {} + {}) "
          "must match",
          column.pin_diameter_m, column.cheek_inner_y_m, column.cheek_thickness_m, sleeve.pin_diameter_m,
          sleeve.journal_start_y_m, sleeve.journal_length_m);
  require(sleeve.guide_diameter_m == arm.outer_diameter_m,
          "spherical parts: the sleeve's guide_diameter_m = {} must equal the arm's outer_diameter_m = {}",
          sleeve.guide_diameter_m, arm.outer_diameter_m);
}

double spherical_part_volume_m3(SphericalPart part, const SphericalPartDimensions& d) {
  switch (part) {
    case SphericalPart::Column: return d.column.volume_m3();
    case SphericalPart::Sleeve: return d.sleeve.volume_m3();
    case SphericalPart::Arm: return d.arm.volume_m3();
  }
  return 0.0;
}

double spherical_part_mass_kg(SphericalPart part, const SphericalPartDimensions& d) {
  return d.density_kg_m3 * spherical_part_volume_m3(part, d);
}

SphericalPartDimensions spherical_part_dimensions(const SphericalPartSizing& s, const SphericalPartRules& rules) {
  s.validate();
  rules.validate();
  SphericalPartDimensions d;
  d.density_kg_m3 = rules.density_kg_m3;
  const double rho = rules.density_kg_m3;
  const double d2 = s.sleeve_diameter_m, r2 = d2 / 2;
  const double pin = rules.pin_diameter_ratio * d2;
  const double y_in = r2 + rules.shoulder_gap_ratio * d2;
  const double t_c = rules.cheek_thickness_ratio * pin;
  const double d3 = rules.arm_diameter_ratio * d2;

  SphericalArmDimensions& arm = d.arm;
  arm.length_m = s.arm_length_m;
  arm.outer_diameter_m = d3;
  arm.end_plate_thickness_m = rules.end_plate_ratio * d3;
  // The arm's points in the sleeve: |l_BM + x| <= l2/2 for some l_BM in
  // [r_Mmin, r_Mmax].
  arm.slide_from_m = -s.reach_max_m - s.sleeve_length_m / 2;
  arm.slide_to_m = -s.reach_min_m + s.sleeve_length_m / 2;
  arm.target_mass_kg = s.arm_mass_kg;
  std::tie(arm.wall_m, arm.wall_rule) = wall_for_volume(
      [&](double t) { SphericalArmDimensions a = arm; a.wall_m = t; return a.volume_m3(); }, s.arm_mass_kg / rho,
      rules.min_wall_m, rules.max_wall_fraction * d3 / 2);

  SphericalSleeveDimensions& sleeve = d.sleeve;
  sleeve.length_m = s.sleeve_length_m;
  sleeve.outer_diameter_m = d2;
  sleeve.guide_diameter_m = d3;
  sleeve.guide_length_m = rules.guide_length_ratio * d3;
  sleeve.pin_diameter_m = pin;
  sleeve.shoulder_diameter_m = rules.shoulder_diameter_ratio * pin;
  sleeve.journal_start_y_m = y_in;
  sleeve.journal_length_m = t_c;
  sleeve.target_mass_kg = s.sleeve_mass_kg;
  const double max_sleeve_wall = r2 - d3 / 2 - rules.min_relief_m;
  require(max_sleeve_wall > rules.min_wall_m,
          "spherical parts: the sleeve's wall between min_wall_m = {} and the guide lands' {} leaves no room "
          "(arm_diameter_ratio = {} too large)",
          rules.min_wall_m, max_sleeve_wall, rules.arm_diameter_ratio);
  std::tie(sleeve.wall_m, sleeve.wall_rule) = wall_for_volume(
      [&](double t) { SphericalSleeveDimensions v = sleeve; v.wall_m = t; return v.volume_m3(); },
      s.sleeve_mass_kg / rho, rules.min_wall_m, max_sleeve_wall);

  SphericalColumnDimensions& column = d.column;
  column.flange_radius_m = s.base_diameter_m / 2;
  column.flange_thickness_m = rules.flange_thickness_m;
  column.pin_height_m = s.height_b_m;
  column.pin_diameter_m = pin;
  column.cheek_inner_y_m = y_in;
  column.cheek_thickness_m = t_c;
  column.lug_width_m = rules.lug_width_ratio * pin;
  column.outer_radius_m = std::hypot(y_in + t_c, column.lug_width_m / 2) + rules.lug_margin_m;
  // The sleeve tilted by phi2 about the pin: its lower generatrix passes
  // z = z_B - r2/cos(phi2) - |x| tan(phi2); over |x| <= R1 it must clear the top.
  column.top_m = s.height_b_m - r2 / std::cos(s.tilt_max_rad) -
                 column.outer_radius_m * std::tan(s.tilt_max_rad) - rules.tilt_clearance_m;
  require(column.top_m - 1.5 * rules.seat_length_m > rules.flange_thickness_m &&
              column.top_m - rules.top_plate_thickness_m > rules.flange_thickness_m,
          "spherical parts: the sleeve tilted by tilt_max_rad = {} ({} deg) about the pin at height_b_m = {} leaves "
          "the column's top at z_top = {} m, too low for the floor flange, the bearing seat and the top plate",
          s.tilt_max_rad, s.tilt_max_rad * 180 / pi, s.height_b_m, column.top_m);
  column.top_plate_thickness_m = rules.top_plate_thickness_m;
  column.seat_length_m = rules.seat_length_m;
  column.seat_collar_m = rules.seat_collar_m;
  column.seat_height_m = std::min(s.height_a_m, column.top_m - rules.seat_length_m);
  column.target_mass_kg = s.column_mass_kg;
  column.wall_m = rules.min_wall_m;  // for validate() of the rest
  column.validate();
  std::tie(column.wall_m, column.wall_rule) = wall_for_volume(
      [&](double t) { SphericalColumnDimensions c = column; c.wall_m = t; return c.volume_m3(); },
      s.column_mass_kg / rho, rules.min_wall_m, rules.max_wall_fraction * column.outer_radius_m);

  d.validate();
  return d;
}

fem::Mesh mesh_spherical_part(SphericalPart part, const SphericalPartDimensions& d, const MeshOptions& options) {
  d.validate();
  switch (part) {
    case SphericalPart::Column: {
      const auto& c = d.column;
      return mesh_geometry_text("spherical_column.geo", spherical_column_geometry_text(), options,
                                {{"Column/R_f", c.flange_radius_m},
                                 {"Column/t_f", c.flange_thickness_m},
                                 {"Column/R1", c.outer_radius_m},
                                 {"Column/t1", c.wall_m},
                                 {"Column/z_top", c.top_m},
                                 {"Column/t_top", c.top_plate_thickness_m},
                                 {"Column/z_seat", c.seat_height_m},
                                 {"Column/h_seat", c.seat_length_m},
                                 {"Column/h_c", c.seat_collar_m},
                                 {"Column/z_B", c.pin_height_m},
                                 {"Column/d_pin", c.pin_diameter_m},
                                 {"Column/y_in", c.cheek_inner_y_m},
                                 {"Column/t_c", c.cheek_thickness_m},
                                 {"Column/w", c.lug_width_m}});
    }
    case SphericalPart::Sleeve: {
      const auto& s = d.sleeve;
      return mesh_geometry_text("spherical_sleeve.geo", spherical_sleeve_geometry_text(), options,
                                {{"Sleeve/l2", s.length_m},
                                 {"Sleeve/d2", s.outer_diameter_m},
                                 {"Sleeve/t2", s.wall_m},
                                 {"Sleeve/D_g", s.guide_diameter_m},
                                 {"Sleeve/l_g", s.guide_length_m},
                                 {"Sleeve/d_pin", s.pin_diameter_m},
                                 {"Sleeve/d_s", s.shoulder_diameter_m},
                                 {"Sleeve/y_in", s.journal_start_y_m},
                                 {"Sleeve/t_c", s.journal_length_m}});
    }
    case SphericalPart::Arm: {
      const auto& a = d.arm;
      return mesh_geometry_text("spherical_arm.geo", spherical_arm_geometry_text(), options,
                                {{"Arm3/l1", a.length_m},
                                 {"Arm3/D3", a.outer_diameter_m},
                                 {"Arm3/t3", a.wall_m},
                                 {"Arm3/t_p", a.end_plate_thickness_m},
                                 {"Arm3/x_s0", a.slide_from_m},
                                 {"Arm3/x_s1", a.slide_to_m}});
    }
  }
  throw Error("mesh_spherical_part: unknown part");
}

}  // namespace kinetofem::meshes
