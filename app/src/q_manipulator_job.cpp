// The "q_manipulator" case type (SPEC §4): an n-link primary chain coupled by
// constant-ratio control mechanisms; the path of H over a lever-angle sweep,
// its cusps, and (two links) the isokinematic equivalent that traces the same
// path. Closed form: mechanisms/q_manipulator.hpp.
#include <cmath>
#include <cstdio>
#include <numbers>

#include "kinetofem/app/mechanism_cases.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/mechanisms/path_straightness.hpp"
#include "kinetofem/mechanisms/q_manipulator.hpp"
#include "kinetofem/mechanisms/time_grid.hpp"
#include "kinetofem/postproc/results_writer.hpp"

namespace kinetofem::app {

namespace {
using Type = KeySpec::Type;
using units::kDeg;
using units::kMm;
}  // namespace

const std::vector<KeySpec>& q_manipulator_schema() {
  static const std::vector<KeySpec> schema = [] {
    std::vector<KeySpec> s = mechanism_case_keys("q_manipulator");
    s.insert(s.end(), {
      {.path = "manipulator.lengths_mm", .type = Type::Array, .unit = "mm", .doc = "link lengths l_1..l_n (n >= 1)", .required = true},
      {.path = "manipulator.ratios", .type = Type::Array, .doc = "CTM ratios i_1..i_{n-1}: phi_{k+1,k} = -i_k phi_{k,k-1} (SPEC §4 sign convention)"},
      {.path = "manipulator.initial_angles_deg", .type = Type::Array, .unit = "deg", .doc = "initial relative angles alpha_{1,0}..alpha_{n,n-1}; default all 0"},
      {.path = "sweep.p_min_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 0, .doc = "start of the lever angle P"},
      {.path = "sweep.p_max_deg", .type = Type::Number, .unit = "deg", .to_si = kDeg, .default_number = 360, .doc = "end of the lever angle P"},
      {.path = "sweep.output_times", .type = Type::Integer, .default_number = 721, .min = 3, .max = 10000000, .doc = "samples (output times) of the sweep"},
      {.path = "sweep.duration_s", .type = Type::Number, .unit = "s", .default_number = 2, .min = 0, .min_exclusive = true,
       .doc = "the lever turns at a constant rate from p_min to p_max in this time (velocities of H follow from it)"},
    });
    return s;
  }();
  return schema;
}

MechanismCaseSummary run_q_manipulator(const CaseFile& c, const RunOptions& options) {
  const std::string name = mechanism_case_name(c);
  const Log log = start_case_log(c, options, name, "Q-manipulator (SPEC §4)");
  const std::vector<double> lengths = read_numbers(c, "manipulator.lengths_mm", 0, kMm);
  const std::vector<double> ratios = read_numbers(c, "manipulator.ratios", 0, 1.0);
  const std::vector<double> angles = read_numbers(c, "manipulator.initial_angles_deg", 0, kDeg);
  require(!lengths.empty(), "{}: give at least one link length", c.where("manipulator.lengths_mm"));
  require(ratios.size() + 1 == lengths.size(), "{}: {} link(s) need {} ratio(s), got {}", c.where("manipulator.ratios"),
          lengths.size(), lengths.size() - 1, ratios.size());
  require(angles.empty() || angles.size() == lengths.size(), "{}: {} link(s) need {} initial angle(s), got {}",
          c.where("manipulator.initial_angles_deg"), lengths.size(), lengths.size(), angles.size());
  std::unique_ptr<mech::QManipulator> q;
  try {
    q = std::make_unique<mech::QManipulator>(lengths, ratios, angles);
  } catch (const Error& e) {
    fail("{}: [manipulator]: {}", c.path().string(), e.what());
  }
  const double lo = c.number("sweep.p_min_deg"), hi = c.number("sweep.p_max_deg");
  require(lo < hi, "{}: p_min_deg must be below p_max_deg", c.where("sweep.p_max_deg"));
  const long T = c.integer("sweep.output_times");
  const double duration = c.number("sweep.duration_s"), rate = (hi - lo) / duration;
  const std::vector<double> cusps = q->find_cusps(lo, hi);

  std::unique_ptr<mech::IsokinematicEquivalent> iso;
  if (lengths.size() == 2 && ratios[0] != 1.0) iso = std::make_unique<mech::IsokinematicEquivalent>(mech::isokinematic_equivalent(*q));

  std::vector<double> times(static_cast<std::size_t>(T));
  std::vector<Eigen::Vector2d> path;
  post::FieldMatrix p(T, 1), hp(T, 2), hv(T, 2), ha(T, 2), links(T, Eigen::Index(lengths.size())), hiso(T, 2);
  double max_iso_deviation = 0.0, peak_speed = 0.0;
  const std::vector<double> grid = mech::equally_spaced_times(duration, T);
  for (long k = 0; k < T; ++k) {
    const double t = grid[std::size_t(k)], angle = lo + rate * t;
    times[std::size_t(k)] = t;
    const mech::PointKinematics h = q->point_h(angle);
    p(k, 0) = angle;
    hp.row(k) = h.p.transpose();
    hv.row(k) = (rate * h.d1).transpose();
    ha.row(k) = (rate * rate * h.d2).transpose();
    peak_speed = std::max(peak_speed, rate * h.d1.norm());
    path.push_back(h.p);
    for (std::size_t j = 0; j < lengths.size(); ++j) links(k, Eigen::Index(j)) = q->link_angle_rad(j + 1, angle);
    if (iso) {
      const Eigen::Vector2d e = iso->manipulator.point_h(iso->lever_angle_scale * angle).p;
      hiso.row(k) = e.transpose();
      max_iso_deviation = std::max(max_iso_deviation, (e - h.p).norm());
    }
  }
  MechanismCaseSummary summary;
  summary.results_file = mechanism_results_path(c, options, name);
  post::ResultsWriter w(summary.results_file, mechanism_provenance(c, options));
  w.set_mechanism_time(times);
  w.write_history("lever.P", "rad", p);
  w.write_history("link_angles", "rad", links);
  w.write_history("H.position", "m", hp, {"x", "y"});
  w.write_history("H.velocity", "m/s", hv, {"x", "y"});
  w.write_history("H.acceleration", "m/s^2", ha, {"x", "y"});
  if (iso) w.write_history("isokinematic.H.position", "m", hiso, {"x", "y"});
  w.commit();

  summary.values = {{"cusps", double(cusps.size())}, {"isokinematic_deviation_m", max_iso_deviation},
                    {"extent_x_m", mech::horizontal_extent(path)}, {"peak_speed_mps", peak_speed}};
  std::printf("\nSummary of '%s' (Q-manipulator, SPEC §4, %zu links)\n", name.c_str(), lengths.size());
  std::printf("  angle rates K_k = dTheta_k/dP:");
  for (double k : q->angle_rates()) std::printf(" %.6g", k);
  std::printf("\n");
  if (lengths.size() == 2) {
    const double l1 = lengths[0], l2 = lengths[1], i = ratios[0];
    std::printf("  SPEC §4 cusp condition l1 = |l2 (1 - i)|: %.3f mm vs %.3f mm -> %s\n", l1 / kMm,
                std::abs(l2 * (1 - i)) / kMm, mech::two_link_has_cusps(l1, l2, i, 1e-9) ? "cusps" : "no cusps");
  }
  std::printf("  cusps found over P in [%.1f, %.1f] deg: %zu", lo / kDeg, hi / kDeg, cusps.size());
  for (std::size_t k = 0; k < cusps.size() && k < 12; ++k) std::printf("%s%.3f", k == 0 ? " at " : ", ", cusps[k] / kDeg);
  std::printf("%s\n", cusps.empty() ? "" : " deg");
  if (iso) {
    const auto& e = iso->manipulator;
    std::printf("  isokinematic equivalent (SPEC §4: l1' = l2, l2' = l1, 1 - i' = 1/(1 - i)): l1' = %.3f mm, l2' = %.3f mm, "
                "i' = %.6g; P' = %.6g P; max |H'(P') - H(P)| = %.3g m over the sweep\n",
                e.lengths_m()[0] / kMm, e.lengths_m()[1] / kMm, e.ratios()[0], iso->lever_angle_scale, max_iso_deviation);
  }
  std::printf("  H: horizontal extent %.3f mm; peak speed %.4f m/s at a lever rate of %.4g rad/s\n",
              mech::horizontal_extent(path) / kMm, peak_speed, rate);
  std::printf("  results: %s (+ .xdmf)\n", summary.results_file.string().c_str());
  return summary;
}

}  // namespace kinetofem::app
