// The "lever_chain_kinematics" case type (SPEC §1): synthesis of the
// lever-chain manipulator (from a, c, h, r or from H0, Hf, phi_of), the paths
// of C and H over a lever range with their horizontal extents and
// straightness, and the speeds and accelerations of C and H for a motion law
// of the lever. Closed form: mechanisms/lever_chain.hpp.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "kinetofem/app/common_keys.hpp"
#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/app/motion_keys.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/path_straightness.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
}  // namespace

const std::vector<KeySpec>& lever_chain_kinematics_schema() {
  static const std::vector<KeySpec> schema = [] {
    std::vector<KeySpec> s = mechanism_case_keys("lever_chain_kinematics");
    for (auto&& k : lever_chain_dimension_keys("geometry.")) s.push_back(std::move(k));
    s.insert(s.end(), {
      {.path = "geometry.input", .type = Type::String, .default_text = "dimensions", .allowed = {"dimensions", "synthesis"},
       .doc = "dimensions: a, c, h, r given; synthesis: a, c, h from H0, Hf and phi_of (SPEC §1, fig. 2), r given"},
      {.path = "geometry.h0_mm", .type = Type::Array, .unit = "mm", .doc = "synthesis: design position H0 = [x, y] of H (frame: origin A0, Y along the machine axis)"},
      {.path = "geometry.hf_mm", .type = Type::Array, .unit = "mm", .doc = "synthesis: final position Hf = [x, y] of H"},
      {.path = "geometry.phi_of_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .min = -180, .max = 180, .doc = "synthesis: lever rotation from H0 to Hf"},
      {.path = "path.dphi_min_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = -73, .min = -180, .max = 180, .doc = "lower end of the lever range of the paths (published drawing: -73)"},
      {.path = "path.dphi_max_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 90, .min = -180, .max = 180, .doc = "upper end of the lever range (published drawing: +90)"},
      {.path = "path.samples", .type = Type::Integer, .default_number = 16301, .min = 3, .max = 10000000, .doc = "samples of the lever range for extents and straightness"},
      {.path = "path.straightness_length_mm", .type = Type::Number, .unit = "mm", .to_si = kMm, .default_number = 800, .min = 0, .min_exclusive = true,
       .doc = "horizontal length of the stretch whose band is measured (SPEC §1: almost 800 mm)"},
      {.path = "motion.start_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 0, .min = -180, .max = 180, .doc = "lever angle dphi at t = 0"},
      {.path = "motion.output_times", .type = Type::Integer, .default_number = 101, .min = 2, .max = 1000000, .doc = "output times over the motion, both ends included"},
    });
    add_motion_law_keys(s, "motion.", "law",
                        {.default_law = "polynomial345", .default_stroke_deg = 80.0, .default_duration_s = 2.0, .angles_only = true});
    return s;
  }();
  return schema;
}

MechanismCaseSummary run_lever_chain_kinematics(const CaseFile& c, const RunOptions& options) {
  const std::string name = mechanism_case_name(c);
  const Log log = start_case_log(c, options, name, "lever-chain kinematics (SPEC §1)");
  mech::LeverChainGeometry g;
  try {
    if (c.text_value("geometry.input") == "synthesis") {
      for (const char* key : {"geometry.h0_mm", "geometry.hf_mm", "geometry.phi_of_deg"})
        require(c.has(key), "{}: geometry.input = \"synthesis\" needs '{}'", c.where("geometry.input"), key);
      const mech::PrimaryChainSynthesis syn = mech::synthesize_primary_chain(
          read_vector2(c, "geometry.h0_mm", 0, kMm), read_vector2(c, "geometry.hf_mm", 0, kMm), c.number("geometry.phi_of_deg"));
      log.info("  synthesis: Hf1 = ({:.3f}, {:.3f}) mm, M = ({:.3f}, {:.3f}) mm", syn.hf_in_lever_frame_m.x() / kMm,
               syn.hf_in_lever_frame_m.y() / kMm, syn.midpoint_m.x() / kMm, syn.midpoint_m.y() / kMm);
      g = mech::make_lever_chain_geometry(syn.a_m, syn.c_m, syn.h_m, c.number("geometry.r_mm"));
    } else {
      g = mech::make_lever_chain_geometry(c.number("geometry.a_mm"), c.number("geometry.c_mm"), c.number("geometry.h_mm"),
                                          c.number("geometry.r_mm"));
    }
  } catch (const Error& e) {
    fail("{}: [geometry]: {}", c.path().string(), e.what());
  }
  const mech::LeverChain lc(g);

  // ---- paths over the lever range -------------------------------------------
  const double lo = c.number("path.dphi_min_deg"), hi = c.number("path.dphi_max_deg");
  require(lo < hi, "{}: dphi_min_deg must be below dphi_max_deg", c.where("path.dphi_max_deg"));
  mech::LeverChainPath path;
  try {
    path = mech::sample_lever_chain_path(lc, lo, hi, std::size_t(c.integer("path.samples")));
  } catch (const Error& e) {
    fail("{}: [path]: {}", c.path().string(), e.what());
  }
  const double window = c.number("path.straightness_length_mm");
  const double ext_c = mech::horizontal_extent(path.c_m), ext_h = mech::horizontal_extent(path.h_m);
  const auto st_c = mech::horizontal_straightness(path.c_m, window, g.a_m);
  const auto st_h = mech::horizontal_straightness(path.h_m, window, g.a_m + g.h_m);

  // ---- motion ---------------------------------------------------------------
  const std::shared_ptr<const mech::MotionLaw> law = read_motion_law(c, "motion.", "law", /*angle=*/true);
  const double duration = law->duration();
  const std::vector<double> times_grid = mech::equally_spaced_times(duration, c.integer("motion.output_times"));
  const double start = c.number("motion.start_deg");
  const long T = c.integer("motion.output_times");
  std::vector<double> times(std::size_t(T), 0.0);
  post::FieldMatrix dphi(T, 3), dpsi(T, 1), theta(T, 1), chain_b(T, 1);
  post::FieldMatrix cp(T, 2), cv(T, 2), ca(T, 2), cs(T, 2), hp(T, 2), hv(T, 2), ha(T, 2), hs(T, 2);
  double peak_speed_h = 0, peak_accel_h = 0;
  for (long k = 0; k < T; ++k) {
    const double t = times_grid[std::size_t(k)];
    times[std::size_t(k)] = t;
    const mech::MotionState m = law->at(t);
    mech::LeverChainPose p;
    try {
      p = lc.pose(start + m.s);
    } catch (const Error& e) {
      fail("{}: [motion] at t = {:.6g} s: {}", c.path().string(), t, e.what());
    }
    dphi.row(k) << start + m.s, m.s_dot, m.s_ddot;
    dpsi(k, 0) = p.ctm.dpsi_rad;
    theta(k, 0) = p.theta_rad;
    chain_b(k, 0) = p.ctm.b_m;
    const mech::PointMotion mc = mech::point_motion(p.c, m.s_dot, m.s_ddot);
    const mech::PointMotion mh = mech::point_motion(p.h, m.s_dot, m.s_ddot);
    cp.row(k) = p.c.p.transpose();
    cv.row(k) = mc.velocity_mps.transpose();
    ca.row(k) = mc.acceleration_mps2.transpose();
    cs.row(k) << mc.speed_mps, mc.tangential_acceleration_mps2;
    hp.row(k) = p.h.p.transpose();
    hv.row(k) = mh.velocity_mps.transpose();
    ha.row(k) = mh.acceleration_mps2.transpose();
    hs.row(k) << mh.speed_mps, mh.tangential_acceleration_mps2;
    peak_speed_h = std::max(peak_speed_h, std::abs(mh.speed_mps));
    peak_accel_h = std::max(peak_accel_h, mh.acceleration_mps2.norm());
  }

  MechanismCaseSummary summary;
  summary.results_file = mechanism_results_path(c, options, name);
  post::ResultsWriter w(summary.results_file, mechanism_provenance(c, options));
  w.set_mechanism_time(times);
  const std::vector<std::string> xy = {"x", "y"};
  w.write_history("lever.dphi", "rad", dphi.col(0));
  w.write_history("lever.dphi_dot", "rad/s", dphi.col(1));
  w.write_history("lever.dphi_ddot", "rad/s^2", dphi.col(2));
  w.write_history("arm.dpsi", "rad", dpsi);
  w.write_history("arm.theta", "rad", theta);
  w.write_history("chain.free_length", "m", chain_b);
  w.write_history("C.position", "m", cp, xy);
  w.write_history("C.velocity", "m/s", cv, xy);
  w.write_history("C.acceleration", "m/s^2", ca, xy);
  w.write_history("C.speed", "m/s", cs.col(0));
  w.write_history("C.tangential_acceleration", "m/s^2", cs.col(1));
  w.write_history("H.position", "m", hp, xy);
  w.write_history("H.velocity", "m/s", hv, xy);
  w.write_history("H.acceleration", "m/s^2", ha, xy);
  w.write_history("H.speed", "m/s", hs.col(0));
  w.write_history("H.tangential_acceleration", "m/s^2", hs.col(1));
  w.commit();

  const double d1_0 = lc.ctm(0.0).dpsi_d1, d1_20 = lc.ctm(20 * kDeg).dpsi_d1;
  summary.values = {{"b0_m", g.b0_m}, {"l0_m", g.l0_m}, {"alpha0_rad", g.alpha0_rad}, {"dpsi_d1_at_0", d1_0},
                    {"dpsi_d1_at_20deg", d1_20}, {"extent_c_m", ext_c}, {"extent_h_m", ext_h},
                    {"above_c_m", st_c.max_above_m}, {"above_h_m", st_h.max_above_m},
                    {"peak_speed_h_mps", peak_speed_h}, {"peak_accel_h_mps2", peak_accel_h}};

  std::printf("\nSummary of '%s' (lever-chain kinematics, SPEC §1)\n", name.c_str());
  std::printf("  a = %.3f, c = %.3f, h = %.3f, r = %.3f mm\n", g.a_m / kMm, g.c_m / kMm, g.h_m / kMm, g.r_m / kMm);
  std::printf("  %-44s %-26s %14s\n", "quantity", "published (a,c,h,r = 500,350,100,75)", "computed");
  std::printf("  %-44s %-26s %14.3f\n", "b0 [mm] (1)", "411.765", g.b0_m / kMm);
  std::printf("  %-44s %-26s %14.3f\n", "l0 [mm] (2)", "115.804", g.l0_m / kMm);
  std::printf("  %-44s %-26s %14.3f\n", "alpha0 [deg] (3)", "49.635", g.alpha0_rad / kDeg);
  std::printf("  %-44s %-26s %14.5f\n", "d(dpsi)/d(dphi) at 0", "-1.0000", d1_0);
  std::printf("  %-44s %-26s %14.5f\n", "d(dpsi)/d(dphi) at 20 deg", "-1.38380", d1_20);
  std::printf("  %-44s %-26s %14.1f\n", "horizontal extent of C's path [mm]", "about 1230", ext_c / kMm);
  std::printf("  %-44s %-26s %14.1f\n", "horizontal extent of H's path [mm]", "about 1270", ext_h / kMm);
  std::printf("  %-44s %-26s %8.2f / %.2f\n", fmt::format("C: deviation above / below over {:.0f} mm", window / kMm).c_str(),
              "about 45, one direction", st_c.max_above_m / kMm, st_c.max_below_m / kMm);
  std::printf("  %-44s %-26s %8.2f / %.2f\n", fmt::format("H: deviation above / below over {:.0f} mm", window / kMm).c_str(),
              "about 20, one direction", st_h.max_above_m / kMm, st_h.max_below_m / kMm);
  std::printf("  (paths over dphi in [%.1f, %.1f] deg, %ld samples; deviations from the design tangent y = a, a + h)\n",
              lo / kDeg, hi / kDeg, long(c.integer("path.samples")));
  std::printf("  motion: %s from dphi = %.1f deg, %zu output times: H peak speed %.4f m/s, peak |acceleration| %.4f m/s^2\n",
              law->describe().c_str(), start / kDeg, times.size(), peak_speed_h, peak_accel_h);
  std::printf("  results: %s (+ .xdmf)\n", summary.results_file.string().c_str());
  return summary;
}

}  // namespace kinetofem::app
