// The "gripper_study" case type (SPEC §6): the energy transmission index U_V
// of the crank-slider gripper over the crank angle phi, its operating ranges
// (|U_V| in 1 +- tol, with and without the pressure-angle limits), the
// dimensions from the offset, the jaw travel, and the search for the widest
// design. Closed form: mechanisms/crank_slider_gripper.hpp.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/crank_slider_gripper.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;

std::string ranges_text(const std::vector<mech::PhiInterval>& ranges) {
  std::string out;
  for (const auto& r : ranges) out += fmt::format("{}{:.2f}..{:.2f}", out.empty() ? "" : ", ", r.lo_rad / kDeg, r.hi_rad / kDeg);
  return out.empty() ? "none" : out;
}
}  // namespace

const std::vector<KeySpec>& gripper_study_schema() {
  static const std::vector<KeySpec> schema = [] {
    std::vector<KeySpec> s = mechanism_case_keys("gripper_study");
    s.insert(s.end(), {
      {.path = "gripper.sigma", .type = Type::Number, .default_number = 1.1, .min = 0, .min_exclusive = true, .doc = "sigma = r / l (crank over rod)"},
      {.path = "gripper.gamma", .type = Type::Number, .default_number = 0.82, .min = 0, .doc = "gamma = e / l (offset over rod); 0: central mechanism, eq. (4)"},
      {.path = "gripper.offset_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 50, .min = 0, .min_exclusive = true,
       .doc = "offset e for the dimensions (the source: e = H_max / 2 = 50 mm)"},
      {.path = "object.thickness_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .min = 0, .min_exclusive = true,
       .doc = "thickness H of an object to clamp: must lie in the jaws' range 2e - h .. 2e (open 2e apart at the top of the "
              "operating range with the pressure limits, closing by the jaw travel h); prints its clamp angle and U_V there"},
      {.path = "criterion.tolerance", .type = Type::Number, .default_number = 0.05, .min = 0, .max = 1, .min_exclusive = true, .doc = "|U_V| within 1 +- tolerance"},
      {.path = "criterion.theta12_limit_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 30, .min = 0, .max = 90, .doc = "limit of the slider-guide pressure angle (9)"},
      {.path = "criterion.theta23_limit_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 45, .min = 0, .max = 90, .doc = "limit of the rod-rocker pressure angle (10)"},
      {.path = "curve.phi_min_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 90, .min = -360, .max = 360, .doc = "start of the phi window (the source: second quadrant)"},
      {.path = "curve.phi_max_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 180, .min = -360, .max = 360, .doc = "end of the phi window"},
      {.path = "curve.samples", .type = Type::Integer, .default_number = 901, .min = 3, .max = 10000000, .doc = "samples of the U_V curve written to the results"},
      {.path = "curve.duration_s", .type = Type::Number, .unit = "s", .default_number = 1, .min = 0, .min_exclusive = true,
       .doc = "the crank sweeps phi_min..phi_max at a constant rate in this time (the time axis of the curve)"},
      {.path = "search.enabled", .type = Type::Boolean, .default_number = 1, .doc = "search sigma x gamma for the widest single operating interval (with pressure limits)"},
      {.path = "search.sigma_min", .type = Type::Number, .default_number = 0.8, .min = 0, .min_exclusive = true, .doc = "search window of sigma"},
      {.path = "search.sigma_max", .type = Type::Number, .default_number = 1.5, .min = 0, .min_exclusive = true, .doc = "search window of sigma"},
      {.path = "search.gamma_min", .type = Type::Number, .default_number = 0.6, .min = 0, .doc = "search window of gamma"},
      {.path = "search.gamma_max", .type = Type::Number, .default_number = 1.0, .min = 0, .doc = "search window of gamma"},
      {.path = "search.grid_sigma", .type = Type::Integer, .default_number = 15, .min = 3, .max = 1001, .doc = "grid points of sigma"},
      {.path = "search.grid_gamma", .type = Type::Integer, .default_number = 21, .min = 3, .max = 1001, .doc = "grid points of gamma"},
      {.path = "search.step_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 0.1, .min = 0, .max = 10, .min_exclusive = true, .doc = "phi sampling step before bisection, per design"},
      {.path = "search.refinements", .type = Type::Integer, .default_number = 3, .min = 0, .max = 20, .doc = "zooms of the grid around the best point"},
      {.path = "search.offset_within_crank", .type = Type::Boolean, .default_number = 1, .doc = "restrict to e <= r (gamma <= sigma), the source's region"},
    });
    return s;
  }();
  return schema;
}

MechanismCaseSummary run_gripper_study(const CaseFile& c, const RunOptions& options) {
  const std::string name = mechanism_case_name(c);
  const Log log = start_case_log(c, options, name, "crank-slider gripper study (SPEC §6)");
  const double sigma = c.number("gripper.sigma"), gamma = c.number("gripper.gamma");
  mech::GripperRangeOptions ro;
  ro.tolerance = c.number("criterion.tolerance");
  ro.theta12_limit_rad = c.number("criterion.theta12_limit_deg");
  ro.theta23_limit_rad = c.number("criterion.theta23_limit_deg");
  ro.phi_lo_rad = c.number("curve.phi_min_deg");
  ro.phi_hi_rad = c.number("curve.phi_max_deg");
  require(ro.phi_lo_rad < ro.phi_hi_rad, "{}: phi_min_deg must be below phi_max_deg", c.where("curve.phi_max_deg"));
  mech::GripperRangeOptions limited = ro;
  limited.pressure_limits = true;
  const auto ranges = mech::gripper_operating_ranges(sigma, gamma, ro);
  const auto ranges_limited = mech::gripper_operating_ranges(sigma, gamma, limited);
  const auto hull = mech::operating_hull(ranges), hull_limited = mech::operating_hull(ranges_limited);
  const auto central = mech::widest(mech::gripper_operating_ranges_central(sigma, ro));

  const long T = c.integer("curve.samples");
  const double duration = c.number("curve.duration_s");
  std::vector<double> times(static_cast<std::size_t>(T));
  post::FieldMatrix phi(T, 1), uv(T, 1), th12(T, 1), th23(T, 1), inside(T, 2), assembles(T, 1);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto in = [](const std::vector<mech::PhiInterval>& rs, double x) {
    for (const auto& r : rs)
      if (x >= r.lo_rad && x <= r.hi_rad) return 1.0;
    return 0.0;
  };
  const std::vector<double> grid = mech::equally_spaced_times(duration, T);
  for (long k = 0; k < T; ++k) {
    const double t = grid[std::size_t(k)];
    const double p = ro.phi_lo_rad + (ro.phi_hi_rad - ro.phi_lo_rad) * t / duration;
    times[std::size_t(k)] = t;
    phi(k, 0) = p;
    const bool ok = mech::gripper_assembles(p, sigma, gamma);
    assembles(k, 0) = ok ? 1.0 : 0.0;
    uv(k, 0) = th12(k, 0) = th23(k, 0) = nan;
    if (ok) {
      try {  // (4), (6) are singular at phi = 90 deg (tan): NaN there
        uv(k, 0) = gamma == 0 ? mech::gripper_index_central(p, sigma) : mech::gripper_index_offset(p, sigma, gamma);
        th12(k, 0) = mech::gripper_pressure_angle_slider_rad(p, sigma, gamma);
        th23(k, 0) = mech::gripper_pressure_angle_rod_rocker_rad(p, sigma, gamma);
      } catch (const Error&) {
      }
    }
    inside.row(k) << in(ranges, p), in(ranges_limited, p);
  }

  mech::GripperDesign best;
  const bool search = c.boolean("search.enabled");
  if (search) {
    mech::GripperDesignSearch s;
    s.sigma_lo = c.number("search.sigma_min");
    s.sigma_hi = c.number("search.sigma_max");
    s.gamma_lo = c.number("search.gamma_min");
    s.gamma_hi = c.number("search.gamma_max");
    require(s.sigma_lo < s.sigma_hi && s.gamma_lo < s.gamma_hi, "{}: each search window needs min < max", c.where("search.sigma_max"));
    s.n_sigma = std::size_t(c.integer("search.grid_sigma"));
    s.n_gamma = std::size_t(c.integer("search.grid_gamma"));
    s.refinements = std::size_t(c.integer("search.refinements"));
    s.offset_within_crank = c.boolean("search.offset_within_crank");
    s.range = limited;
    s.range.step_rad = c.number("search.step_deg");
    try {
      best = mech::search_widest_gripper_design(s);
    } catch (const Error& e) {
      fail("{}: [search] over sigma {:g}..{:g}, gamma {:g}..{:g}: {}", c.path().string(), s.sigma_lo, s.sigma_hi, s.gamma_lo,
           s.gamma_hi, e.what());
    }
  }
  const auto dims = mech::gripper_dimensions_from_offset(c.number("gripper.offset_mm"), sigma, gamma == 0 ? sigma : gamma);
  const double travel = hull_limited.width_rad() > 0
                            ? mech::gripper_jaw_travel_m(dims.r_m, hull_limited.lo_rad, hull_limited.hi_rad) / dims.r_m
                            : 0.0;

  // The object: its clamp angle in the operating range (the source's compact
  // design: the jaws 2e apart at its top, e = H_max / 2).
  std::optional<double> object_phi;
  if (c.has("object.thickness_mm")) {
    const double thickness = c.number("object.thickness_mm");
    require(hull_limited.width_rad() > 0, "{} = {:g} mm: this design has no operating range to clamp in",
            c.where("object.thickness_mm"), thickness / kMm);
    const mech::GripperObjectRange jaws =
        mech::gripper_object_range(2 * dims.e_m, dims.r_m, hull_limited.lo_rad, hull_limited.hi_rad);
    require(thickness <= jaws.thickness_max_m && thickness >= jaws.thickness_min_m,
            "{} = {:g} mm: {} than the jaws' range {:.2f}..{:.2f} mm (open 2e = {:g} mm at phi = {:.2f} deg, closing "
            "by the jaw travel {:.2f} mm to phi = {:.2f} deg)",
            c.where("object.thickness_mm"), thickness / kMm, thickness > jaws.thickness_max_m ? "thicker" : "thinner",
            jaws.thickness_min_m / kMm, jaws.thickness_max_m / kMm, 2 * dims.e_m / kMm, hull_limited.hi_rad / kDeg,
            (jaws.thickness_max_m - jaws.thickness_min_m) / kMm, hull_limited.lo_rad / kDeg);
    object_phi = mech::gripper_clamp_angle_rad(thickness, 2 * dims.e_m, dims.r_m, hull_limited.lo_rad, hull_limited.hi_rad);
  }

  MechanismCaseSummary summary;
  summary.results_file = mechanism_results_path(c, options, name);
  post::ResultsWriter w(summary.results_file, mechanism_provenance(c, options));
  w.set_mechanism_time(times);
  w.write_history("crank.phi", "rad", phi);
  w.write_history("assembles", "1", assembles);
  w.write_history_where_defined("U_V", "1", uv);
  w.write_history_where_defined("theta12", "rad", th12);
  w.write_history_where_defined("theta23", "rad", th23);
  w.write_history("in_operating_range", "1", inside, {"index_only", "with_pressure_limits"});
  w.commit();

  summary.values = {{"hull_lo_rad", hull.lo_rad}, {"hull_hi_rad", hull.hi_rad}, {"hull_limited_lo_rad", hull_limited.lo_rad},
                    {"hull_limited_hi_rad", hull_limited.hi_rad}, {"r_m", dims.r_m}, {"l_m", dims.l_m},
                    {"jaw_travel_over_r", travel}, {"central_widest_rad", central.width_rad()},
                    {"best_sigma", best.sigma}, {"best_gamma", best.gamma}, {"best_width_rad", best.range.width_rad()}};
  if (object_phi) {
    summary.values.push_back({"object_phi_rad", *object_phi});
    summary.values.push_back({"object_U_V", mech::gripper_index_offset(*object_phi, sigma, gamma)});
  }
  std::printf("\nSummary of '%s' (crank-slider gripper, SPEC §6: sigma = %.4g, gamma = %.4g, |U_V| in 1 +- %.3g)\n",
              name.c_str(), sigma, gamma, ro.tolerance);
  std::printf("  %-42s %-28s %s\n", "quantity", "published", "computed");
  std::printf("  %-42s %-28s %s (hull %.2f..%.2f)\n", "operating range of phi [deg]", "139..165 (sigma 1.1, gamma 0.82)",
              ranges_text(ranges).c_str(), hull.lo_rad / kDeg, hull.hi_rad / kDeg);
  std::printf("  %-42s %-28s %s (hull %.2f..%.2f)\n", "  with |theta12| <= 30, |theta23| <= 45 deg", "139..163",
              ranges_text(ranges_limited).c_str(), hull_limited.lo_rad / kDeg, hull_limited.hi_rad / kDeg);
  std::printf("  %-42s %-28s r = %.3f mm, l = %.3f mm, e = %.3f mm\n", "dimensions from the offset e", "r = 67, l = 60.98, e = 50",
              dims.r_m / kMm, dims.l_m / kMm, dims.e_m / kMm);
  std::printf("  %-42s %-28s %.5f r\n", "jaw travel 2 r (sin phi2 - sin phi1) over the hull", "0.728 r", travel);
  std::printf("  %-42s %-28s %.2f deg\n", "central mechanism (e = 0), widest range", "about 2 deg, unusable", central.width_rad() / kDeg);
  if (search)
    std::printf("  %-42s %-28s sigma %.4f, gamma %.4f: %.2f..%.2f deg (%.2f deg, %zu evaluations)\n",
                "widest design (pressure limits, e <= r)", "sigma 1.1, gamma 0.82, 24 deg", best.sigma, best.gamma,
                best.range.lo_rad / kDeg, best.range.hi_rad / kDeg, best.range.width_rad() / kDeg, best.evaluations);
  if (object_phi)
    std::printf("  %-42s %-28s phi = %.2f deg, U_V = %.4f (clamping force per jaw = U_V x drive force per rod)\n",
                fmt::format("object {:g} mm thick: clamp angle", c.number("object.thickness_mm") / kMm).c_str(), "49..100 mm",
                *object_phi / kDeg, mech::gripper_index_offset(*object_phi, sigma, gamma));
  std::printf("  (U_V by the source's printed formulas (4), (6); see docs/mechanisms_closed_form.md for its inconsistency)\n");
  std::printf("  results: %s (+ .xdmf)\n", summary.results_file.string().c_str());
  return summary;
}

}  // namespace kinetofem::app
