#include "kinetofem/pipeline/part_fatigue.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/units.hpp"
#include "kinetofem/fatigue/mean_stress.hpp"
#include "kinetofem/fatigue/miner.hpp"

namespace kinetofem::pipeline {

namespace {

using fatigue::MeanStressTreatment;
constexpr double kInfinity = std::numeric_limits<double>::infinity();

std::string joined_keys(const auto& map) {
  std::string out;
  for (const auto& [name, value] : map) out += (out.empty() ? "" : ", ") + name;
  return out.empty() ? std::string("none") : out;
}

const Part* part_of(const std::vector<Part>& parts, const std::string& body) {
  for (const auto& p : parts)
    if (p.body() == body) return &p;
  return nullptr;
}

// The nodes of an element set (global element indices, blocks in order) or a face set.
std::vector<fem::Index> nodes_of_set(const fem::Mesh& mesh, const std::string& set) {
  if (const auto it = mesh.element_sets.find(set); it != mesh.element_sets.end()) {
    std::vector<fem::Index> first_of_block;
    fem::Index first = 0;
    for (const auto& b : mesh.blocks) first_of_block.push_back(first), first += b.size();
    std::vector<fem::Index> nodes;
    for (fem::Index e : it->second) {
      const auto block = size_t(std::upper_bound(first_of_block.begin(), first_of_block.end(), e) -
                                first_of_block.begin()) - 1;
      for (fem::Index n : mesh.blocks[block].element(e - first_of_block[block])) nodes.push_back(n);
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    return nodes;
  }
  return fem::nodes_of_faces(mesh.face_set(set));
}

// One detail of the part: its curve, mean stress treatment and name.
struct Detail {
  fatigue::SnCurve curve;
  MeanStressTreatment mean_stress;
  std::string name;
};

fatigue::SnCurve curve_of(double category_mpa, const FatigueSettings& s, const std::string& what) {
  try {
    return fatigue::SnCurve({.detail_category_mpa = category_mpa, .gamma_ff = s.gamma_ff, .gamma_mf = s.gamma_mf});
  } catch (const Error& e) {
    fail("{}: {}", what, e.what());
  }
}

}  // namespace

double fatigue_utilization(std::span<const fatigue::Cycle> cycles, const fatigue::SnCurve& curve,
                           MeanStressTreatment mean_stress, double design_cycles) {
  const std::vector<fatigue::Cycle> effective = fatigue::apply_mean_stress(cycles, mean_stress);
  double largest = 0.0;
  for (const auto& c : effective) largest = std::max(largest, c.range_pa);
  if (largest <= 0.0) return 0.0;
  // g(s): design damage of the ranges times s; non-decreasing in s, may jump (the cut-off).
  const auto g = [&](double s) {
    double d = 0.0;
    for (const auto& c : effective) d += c.count / curve.endurance(s * c.range_pa);
    return design_cycles * d;
  };
  double hi = 1.0;
  while (g(hi) < 1.0) hi *= 2.0;
  double lo = hi;
  while (lo > 1e-300 && g(lo) >= 1.0) lo *= 0.5;
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) >= 1.0 ? hi : lo) = mid;
  }
  return 1.0 / hi;
}

void check_fatigue_details(const FatigueSettings& settings, const std::vector<Part>& parts) {
  for (const auto& d : settings.details) {
    const Part* part = part_of(parts, d.body);
    if (!part) {
      std::string bodies;
      for (const auto& p : parts) bodies += (bodies.empty() ? "" : ", ") + p.body();
      fail("{} = \"{}\": no part on that body (parts: {})", d.source, d.body, bodies.empty() ? "none" : bodies);
    }
    const fem::Mesh& mesh = part->model.mesh;
    require(mesh.element_sets.contains(d.set) || mesh.face_sets.contains(d.set),
            "{} = \"{}\": part '{}' has no element set or face set of that name (element sets: {}; face sets: {})",
            d.source, d.set, d.body, joined_keys(mesh.element_sets), joined_keys(mesh.face_sets));
  }
}

PartFatigue assess_part_fatigue(const Part& part, const PartStressHistory& history, const FatigueSettings& settings,
                                const Log& log) {
  Stopwatch clock;
  const fem::Mesh& mesh = part.model.mesh;
  const fem::Index nodes = mesh.node_count();
  require(!history.empty(), "{}: fatigue: no stress history over the motion", part.label);
  require(history.nodes() == nodes, "{}: fatigue: the stress history has {} nodes, the mesh {}", part.label,
          history.nodes(), nodes);
  require(std::isfinite(settings.design_cycles) && settings.design_cycles >= 1.0,
          "{}: fatigue: the service life is {} work cycles, less than one", part.label, settings.design_cycles);
  require(std::isfinite(settings.cycle_rate_per_s) && settings.cycle_rate_per_s > 0.0,
          "{}: fatigue: the cycle rate {} 1/s must be positive", part.label, settings.cycle_rate_per_s);

  // The details: 0 is the part default, then the sets of this part in order.
  std::vector<Detail> details;
  details.push_back({curve_of(settings.detail_category_mpa, settings, part.label + ": fatigue: the part default"),
                     settings.mean_stress, "part default"});
  std::vector<int> detail_of(size_t(nodes), 0);
  for (const auto& d : settings.details) {
    if (d.body != part.body()) continue;
    details.push_back({curve_of(d.detail_category_mpa, settings, d.source), d.mean_stress, d.set});
    const int k = int(details.size()) - 1;
    for (fem::Index n : nodes_of_set(mesh, d.set)) {
      int& current = detail_of[size_t(n)];
      if (d.detail_category_mpa < details[size_t(current)].curve.spec().detail_category_mpa) current = k;
    }
  }

  fatigue::FatigueOptions options;
  options.measure = settings.measure;
  options.residue = fatigue::Residue::Periodic;  // one period of the repeated work cycle
  options.plane_spacing_deg = settings.plane_spacing_deg;
  const fatigue::CandidatePlanes planes = settings.measure == fatigue::StressMeasure::CriticalPlane
                                              ? fatigue::hemisphere_planes(settings.plane_spacing_deg)
                                              : fatigue::CandidatePlanes{};
  const auto options_of = [&](int detail) {
    fatigue::FatigueOptions o = options;
    o.mean_stress = details[size_t(detail)].mean_stress;
    return o;
  };

  PartFatigue r;
  r.body = part.body();
  r.design_cycles = settings.design_cycles;
  r.cycle_rate_per_s = settings.cycle_rate_per_s;
  r.superposed = history.superposed();
  r.stress_source = history.source;
  r.planes_searched = int(planes.normals.rows());
  r.damage_per_cycle.resize(nodes);
  r.life_cycles.resize(nodes);
  r.life_s.resize(nodes);
  r.utilization.resize(nodes);
  r.detail_category_pa.resize(nodes);
  r.max_range_pa.resize(nodes);
  r.plane_normal.resize(nodes, 3);

  // Nodes in chunks (a progress line between them), each chunk in parallel;
  // an Error inside the parallel loop is kept and thrown after it.
  const Eigen::Index times = history.times();
  const fem::Index chunk = 4096;
  Progress progress(log, fmt::format("part '{}' fatigue nodes", part.body()), long(nodes));
  std::optional<std::string> error;
  for (fem::Index first = 0; first < nodes && !error; first += chunk) {
    const fem::Index last = std::min(nodes, first + chunk);
#pragma omp parallel
    {
      fatigue::StressHistory s(6, times);
#pragma omp for schedule(dynamic, 64)
      for (fem::Index i = first; i < last; ++i) {
        try {
          history.node_history(i, s);
          const int detail = detail_of[size_t(i)];
          const Detail& d = details[size_t(detail)];
          const fatigue::NodeFatigue nf = fatigue::assess_node(s, d.curve, options_of(detail), planes);
          r.damage_per_cycle[i] = nf.damage;
          r.life_cycles[i] = nf.damage > 0.0 ? 1.0 / nf.damage : kInfinity;
          r.life_s[i] = r.life_cycles[i] / settings.cycle_rate_per_s;
          r.utilization[i] = fatigue_utilization(nf.cycles, d.curve, d.mean_stress, settings.design_cycles);
          r.detail_category_pa[i] = d.curve.spec().detail_category_mpa * units::kMpa;
          r.max_range_pa[i] = nf.max_range_pa;
          r.plane_normal.row(i) = nf.normal.transpose();
        } catch (const Error& e) {
#pragma omp critical(kinetofem_part_fatigue_error)
          if (!error) error = fmt::format("{}: fatigue at node {}: {}", part.label, i, e.what());
        }
      }
    }
    progress.advance(long(last));
  }
  progress.finish();
  if (error) fail("{}", *error);

  // The critical node: the largest damage; where none has damage, the largest utilization.
  Eigen::Index critical = 0;
  r.max_damage_per_cycle = r.damage_per_cycle.maxCoeff(&critical);
  if (r.max_damage_per_cycle <= 0.0) r.utilization.maxCoeff(&critical);
  r.max_utilization = r.utilization.maxCoeff();
  r.critical_node = long(critical);
  r.critical_at_m = mesh.nodes.row(critical).transpose();
  r.min_life_cycles = r.life_cycles.minCoeff();
  r.min_life_s = r.life_s.minCoeff();
  const int critical_detail = detail_of[size_t(critical)];
  r.critical_detail = details[size_t(critical_detail)].name;
  fatigue::StressHistory s(6, times);
  history.node_history(critical, s);
  r.critical = fatigue::assess_node(s, details[size_t(critical_detail)].curve, options_of(critical_detail), planes);
  r.seconds = clock.seconds();

  const Eigen::Vector3d at = r.critical_at_m / units::kMm;
  log.info("  {}: fatigue over {:.3g} work cycles ({}, {} output times{}): critical node {} ({:.1f}, {:.1f}, {:.1f}) mm, "
           "detail {} ({:g} MPa), damage {:.3e} per cycle, life {}, utilization {:.3f}; {:.2f} s",
           r.body, r.design_cycles,
           settings.measure == fatigue::StressMeasure::CriticalPlane
               ? fmt::format("critical plane of {}", r.planes_searched)
               : (settings.measure == fatigue::StressMeasure::MaxPrincipal ? std::string("max principal")
                                                                           : std::string("signed von Mises")),
           times, r.superposed ? ", superposition" : ", step by step", r.critical_node, at[0], at[1], at[2],
           r.critical_detail, r.detail_category_pa[critical] / units::kMpa, r.max_damage_per_cycle,
           std::isinf(r.min_life_cycles) ? std::string("infinite (all ranges below the cut-off)")
                                         : fmt::format("{:.3e} cycles = {:.3e} h", r.min_life_cycles,
                                                       r.min_life_s / units::kHour),
           r.max_utilization, r.seconds);
  return r;
}

void write_part_fatigue(post::BodyWriter& body, const PartFatigue& r) {
  namespace layout = post::layout;
  body.write_static(layout::kFatigueDamage, layout::kDimensionless, r.damage_per_cycle);
  body.write_static(layout::kFatigueLifeCycles, "cycles", r.life_cycles);
  const Eigen::VectorXd life_h = r.life_s / units::kHour;
  body.write_static(layout::kFatigueLifeHours, "h", life_h);
  body.write_static(layout::kFatigueUtilization, layout::kDimensionless, r.utilization);
  body.write_static(layout::kFatigueDetailCategory, "Pa", r.detail_category_pa);
  body.write_static(layout::kFatigueMaxRange, "Pa", r.max_range_pa);
  body.write_static(layout::kFatiguePlaneNormal, layout::kDimensionless, r.plane_normal, post::kVectorComponents);
}

namespace {

std::string life_text(double cycles, double seconds) {
  if (std::isinf(cycles)) return "infinite";
  return fmt::format("{:.3e} cycles, {:.3e} h", cycles, seconds / units::kHour);
}

}  // namespace

std::string format_fatigue_table(const std::vector<PartFatigue>& parts) {
  if (parts.empty()) return {};
  std::string out = fmt::format("\n  Fatigue over the service life (EN 1993-1-9; {:.4g} work cycles, {:.4g} cycles/h)\n",
                                parts.front().design_cycles, parts.front().cycle_rate_per_s * units::kHour);
  out += fmt::format("  {:<8} {:>7} {:>24} {:<18} {:>8} {:>11} {:>36} {:>8} {:>10}\n", "part", "node", "at [mm]",
                     "detail", "cat MPa", "D/cycle", "life", "u", "D service");
  for (const auto& p : parts) {
    const Eigen::Vector3d at = p.critical_at_m / units::kMm;
    out += fmt::format("  {:<8} {:>7} {:>24} {:<18} {:>8g} {:>11.3e} {:>36} {:>8.3f} {:>10.3e}\n", p.body,
                       p.critical_node, fmt::format("({:.1f}, {:.1f}, {:.1f})", at[0], at[1], at[2]), p.critical_detail,
                       p.detail_category_pa[p.critical_node] / units::kMpa, p.max_damage_per_cycle,
                       life_text(p.min_life_cycles, p.min_life_s), p.max_utilization,
                       p.design_cycles * p.max_damage_per_cycle);
  }
  out += fmt::format("  stress: {}\n", describe(parts.front().stress_source));
  out += "  u: utilization (the stress ranges divided by u give a damage of 1 over the service life); critical node: "
         "largest damage, or largest u where no range reaches the cut-off limit\n";
  for (const auto& p : parts) {
    out += fmt::format("  {} node {}: counted ranges of one work cycle (rainflow, one period)", p.body, p.critical_node);
    if (p.critical.plane >= 0)
      out += fmt::format(", critical plane n = ({:.3f}, {:.3f}, {:.3f})", p.critical.normal[0], p.critical.normal[1],
                         p.critical.normal[2]);
    out += ":\n   ";
    const auto ranges = fatigue::merge_ranges(p.critical.cycles, 1e-9 * std::max(p.critical.max_range_pa, 1.0));
    int shown = 0;
    for (auto it = ranges.rbegin(); it != ranges.rend() && shown < 12; ++it, ++shown)
      out += fmt::format(" {:.3f} MPa x {:g};", it->range_pa / units::kMpa, it->count);
    if (ranges.size() > 12) out += fmt::format(" ... ({} ranges in all, the CSV has them)", ranges.size());
    if (ranges.empty()) out += " none";
    out += "\n";
  }
  return out;
}

std::string fatigue_critical_csv(const std::vector<PartFatigue>& parts) {
  std::string out =
      "part,node,x_mm,y_mm,z_mm,detail,detail_category_mpa,damage_per_cycle,life_cycles,life_h,utilization,"
      "range_mpa,count\n";
  for (const auto& p : parts) {
    const Eigen::Vector3d at = p.critical_at_m / units::kMm;
    const double category_mpa = p.detail_category_pa[p.critical_node] / units::kMpa;
    const auto ranges = fatigue::merge_ranges(p.critical.cycles, 1e-9 * std::max(p.critical.max_range_pa, 1.0));
    const auto row = [&](double range_pa, double count) {
      out += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{},{:g},{:.9g},{:.9g},{:.9g},{:.6g},{:.9g},{:g}\n", p.body,
                         p.critical_node, at[0], at[1], at[2], p.critical_detail, category_mpa, p.max_damage_per_cycle,
                         p.min_life_cycles, p.min_life_s / units::kHour, p.max_utilization, range_pa / units::kMpa,
                         count);
    };
    for (auto it = ranges.rbegin(); it != ranges.rend(); ++it) row(it->range_pa, it->count);
    if (ranges.empty()) row(0.0, 0.0);
  }
  return out;
}

}  // namespace kinetofem::pipeline
