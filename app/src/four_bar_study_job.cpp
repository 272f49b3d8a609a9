// The "four_bar_study" case type (SPEC §2): the lever-chain manipulator and
// its equivalent hinged four-bar side by side over the same lever motion
// (range of motion, limits of assembly, straightness of H's path,
// transmission angle). Closed form: mechanisms/four_bar.hpp
// compare_lever_chain_with_four_bar.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/four_bar.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
}  // namespace

const std::vector<KeySpec>& four_bar_study_schema() {
  static const std::vector<KeySpec> schema = [] {
    std::vector<KeySpec> s = mechanism_case_keys("four_bar_study");
    for (auto&& k : lever_chain_dimension_keys("geometry.")) s.push_back(std::move(k));
    s.insert(s.end(), {
      {.path = "study.dphi_min_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = -73, .min = -180, .max = 180, .doc = "start of the lever motion"},
      {.path = "study.dphi_max_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 90, .min = -180, .max = 180, .doc = "end of the lever motion"},
      {.path = "study.samples", .type = Type::Integer, .default_number = 1631, .min = 3, .max = 10000000, .doc = "samples (output times) of the motion"},
      {.path = "study.duration_s", .type = Type::Number, .unit = "s", .default_number = 2, .min = 0, .min_exclusive = true,
       .doc = "the lever turns at a constant rate from dphi_min to dphi_max in this time (the time axis of the histories)"},
      {.path = "study.straightness_length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 300, .min = 0, .min_exclusive = true,
       .doc = "horizontal length of the stretch of H's path whose band is compared"},
    });
    return s;
  }();
  return schema;
}

MechanismCaseSummary run_four_bar_study(const CaseFile& c, const RunOptions& options) {
  const std::string name = mechanism_case_name(c);
  const Log log = start_case_log(c, options, name, "lever-chain vs four-bar study (SPEC §2)");
  const mech::LeverChainGeometry g = read_lever_chain_geometry(c, "geometry.");
  const double lo = c.number("study.dphi_min_deg"), hi = c.number("study.dphi_max_deg");
  require(lo < hi, "{}: dphi_min_deg must be below dphi_max_deg", c.where("study.dphi_max_deg"));
  const std::size_t n = std::size_t(c.integer("study.samples"));
  const double window = c.number("study.straightness_length_mm");
  mech::LeverVsFourBarStudy s;
  try {
    s = mech::compare_lever_chain_with_four_bar(g, lo, hi, n, window);
  } catch (const Error& e) {
    fail("{}: [study]: {}", c.path().string(), e.what());
  }
  const mech::FourBar fb = mech::make_equivalent_four_bar(g);

  const double duration = c.number("study.duration_s");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> times(n);
  const std::vector<double> grid = mech::equally_spaced_times(duration, long(n));
  post::FieldMatrix dphi(n, 1), h_chain(n, 2), h_four(n, 2), assembled(n, 1), mu_chain(n, 1), mu_four(n, 1);
  for (std::size_t k = 0; k < n; ++k) {
    const auto& sample = s.samples[k];
    times[k] = grid[k];
    dphi(k, 0) = sample.dphi_rad;
    h_chain.row(k) = sample.h_lever_chain_m.transpose();
    assembled(k, 0) = sample.four_bar_assembles ? 1.0 : 0.0;
    h_four.row(k) = sample.four_bar_assembles ? sample.h_four_bar_m.transpose() : Eigen::RowVector2d(nan, nan);
    mu_four(k, 0) = sample.four_bar_assembles ? sample.transmission_angle_four_bar_rad : nan;
    mu_chain(k, 0) = sample.transmission_angle_lever_chain_rad;
  }
  MechanismCaseSummary summary;
  summary.results_file = mechanism_results_path(c, options, name);
  post::ResultsWriter w(summary.results_file, mechanism_provenance(c, options));
  w.set_mechanism_time(times);
  w.write_history("lever.dphi", "rad", dphi);
  w.write_history("lever_chain.H.position", "m", h_chain, {"x", "y"});
  w.write_history("lever_chain.transmission_angle", "rad", mu_chain);
  w.write_history("four_bar.assembles", "1", assembled);
  w.write_history_where_defined("four_bar.H.position", "m", h_four, {"x", "y"});
  w.write_history_where_defined("four_bar.transmission_angle", "rad", mu_four);
  w.commit();

  const auto& range = s.four_bar_range_dphi;
  summary.values = {{"four_bar_lo_rad", range.lo_rad}, {"four_bar_hi_rad", range.hi_rad},
                    {"h_extent_lever_chain_m", s.h_extent_lever_chain_m}, {"h_extent_four_bar_m", s.h_extent_four_bar_m},
                    {"min_transmission_four_bar_rad", s.min_transmission_angle_four_bar_rad},
                    {"max_transmission_four_bar_rad", s.max_transmission_angle_four_bar_rad},
                    {"band_h_lever_chain_m", s.h_lever_chain.band_height_m}, {"band_h_four_bar_m", s.h_four_bar.band_height_m}};
  std::printf("\nSummary of '%s' (lever-chain vs equivalent four-bar, SPEC §2)\n", name.c_str());
  std::printf("  four-bar A0A = %.3f, AB = %.3f, BB0 = %.3f, A0B0 = %.3f mm: %s (SPEC §2: non-Grashof, 500+75 > 411.8+115.8)\n",
              fb.crank_length_m() / kMm, fb.coupler_length_m() / kMm, fb.rocker_length_m() / kMm, fb.ground_length_m() / kMm,
              std::string(mech::to_string(fb.grashof())).c_str());
  std::printf("  lever motion dphi %.1f .. %.1f deg at a constant rate over %.3g s, %zu samples\n", lo / kDeg, hi / kDeg,
              duration, n);
  std::printf("  %-46s %16s %16s\n", "quantity", "lever-chain", "four-bar");
  std::printf("  %-46s %16s %7.3f..%-8.3f\n", "range of dphi that assembles [deg]", "unlimited", range.lo_rad / kDeg, range.hi_rad / kDeg);
  std::printf("  %-46s %16.1f %16.1f\n", "horizontal extent of H [mm]", s.h_extent_lever_chain_m / kMm, s.h_extent_four_bar_m / kMm);
  std::printf("  %-46s %16.3f %16.3f\n", fmt::format("H band over the narrowest {:.0f} mm [mm]", window / kMm).c_str(),
              s.h_lever_chain.band_height_m / kMm, s.h_four_bar.band_height_m / kMm);
  std::printf("  %-46s %16.3f %16.3f\n", "  its max deviation from the tangent y = a + h [mm]",
              s.h_lever_chain.max_deviation_m / kMm, s.h_four_bar.max_deviation_m / kMm);
  std::printf("  %-46s %16s %7.1f..%-8.1f\n", "transmission angle [deg] (SPEC §2: chain 90)", "90 (constant)",
              s.min_transmission_angle_four_bar_rad / kDeg, s.max_transmission_angle_four_bar_rad / kDeg);
  std::printf("  results: %s (+ .xdmf); four-bar values are NaN where it does not assemble\n",
              summary.results_file.string().c_str());
  return summary;
}

}  // namespace kinetofem::app
