#include "kinetofem/pipeline/run_report.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "kinetofem/core/units.hpp"
#include "kinetofem/pipeline/histories.hpp"

namespace kinetofem::pipeline {

using units::kMm;
using units::kMpa;

MechanismExtremes mechanism_extremes(const mech::MultibodyModel& m, const mech::Results& res) {
  MechanismExtremes out;
  if (res.frames.empty()) return out;
  const std::size_t n_drives = res.frames.front().drives.size();
  for (std::size_t d = 0; d < n_drives; ++d) {
    double lo = 1e300, hi = -1e300, t_lo = 0, t_hi = 0, p_max = 0;
    for (const auto& f : res.frames) {
      const double e = f.drives[d].effort;
      if (e < lo) lo = e, t_lo = f.t;
      if (e > hi) hi = e, t_hi = f.t;
      p_max = std::max(p_max, std::abs(f.drives[d].power_W));
    }
    out.max_abs_drive_effort = std::max({out.max_abs_drive_effort, std::abs(lo), std::abs(hi)});
    const std::string unit = drive_effort_unit(m, d);
    out.text += fmt::format("  drive {:<16} {}: effort {:.4g} {} (t = {:.4g} s) .. {:.4g} {} (t = {:.4g} s); peak |power| {:.4g} W\n",
                            res.frames.front().drives[d].name, d < m.motion_drives.size() ? "(motion)" : "(force) ", lo,
                            unit, t_lo, hi, unit, t_hi, p_max);
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    double peak = 0, t_peak = 0, moment = 0;
    for (const auto& f : res.frames) {
      if (f.joints[j].on_j.force_world.norm() > peak) peak = f.joints[j].on_j.force_world.norm(), t_peak = f.t;
      moment = std::max(moment, std::abs(f.joints[j].on_j.moment_Nm));
    }
    out.text += fmt::format("  joint {:<16} max |reaction| {:.4g} N (t = {:.4g} s){}\n", m.joints[j].name, peak, t_peak,
                            moment > 0 && mech::joint_facts(m.joints[j].type).reaction_moment
                                ? fmt::format("; max |moment| on {} {:.4g} N m", m.joints[j].body_j, moment)
                                : "");
  }
  for (std::size_t k = 0; k < res.frames.front().transmissions.size(); ++k) {
    double moment = 0, force = 0, t_peak = 0;
    for (const auto& f : res.frames)
      if (std::abs(f.transmissions[k].moment_output_Nm) > moment)
        moment = std::abs(f.transmissions[k].moment_output_Nm), force = std::abs(f.transmissions[k].force_N), t_peak = f.t;
    const mech::Transmission& tr = m.transmissions[k];
    out.text += fmt::format("  transmission {:<9} ratio {:g}: max |moment| on {} {:.4g} N m, {} {:.4g} N (t = {:.4g} s)\n",
                            tr.name, tr.ratio, tr.output.body_j, moment,
                            mech::transmission_force_name(tr.kind), force, t_peak);
  }
  const std::size_t n_chains = res.frames.front().chains.size();
  for (std::size_t ch = 0; ch < n_chains; ++ch) {
    double lo = 1e300, hi = -1e300, t_lo = 0;
    for (const auto& f : res.frames) {
      if (f.chains[ch].tension_N < lo) lo = f.chains[ch].tension_N, t_lo = f.t;
      hi = std::max(hi, f.chains[ch].tension_N);
    }
    if (ch == 0) out.min_chain_tension_n = lo, out.max_chain_tension_n = hi;
    out.min_chain_tension_n = std::min(out.min_chain_tension_n, lo);
    out.max_chain_tension_n = std::max(out.max_chain_tension_n, hi);
    out.text += fmt::format("  chain {:<16} tension {:.4g} N (min, t = {:.4g} s) .. {:.4g} N{}\n",
                            res.frames.front().chains[ch].name, lo, t_lo, hi,
                            lo <= 0 ? "  SLACK: the chain cannot push" : "");
  }
  return out;
}

PartExtremes part_extremes(const std::vector<PartSummary>& parts) {
  PartExtremes e;
  for (const auto& p : parts) {
    e.max_von_mises_pa = std::max(e.max_von_mises_pa, p.peak_von_mises_pa);
    e.max_displacement_m = std::max(e.max_displacement_m, p.peak_displacement_m);
    e.static_max_von_mises_pa = std::max(e.static_max_von_mises_pa, p.static_von_mises_pa);
    e.static_max_displacement_m = std::max(e.static_max_displacement_m, p.static_displacement_m);
  }
  return e;
}

std::string format_part_table(const std::vector<PartSummary>& parts, bool several_planes) {
  std::size_t width = 8;  // the longest part name
  for (const auto& p : parts) width = std::max(width, p.body.size());
  std::string out = fmt::format("  {:<{}} {:>9} {:>14} {:>10} {:>14} {:>10} {:>12} {:>12}\n", "part", width, "DoFs",
                                "max vM [MPa]", "at t [s]", "max |u| [mm]", "at t [s]", "static vM", "static |u|");
  for (const auto& p : parts)
    out += fmt::format("  {:<{}} {:>9} {:>14.3f} {:>10.4f} {:>14.5f} {:>10.4f} {:>12} {:>12}\n", p.body, width, p.dofs,
                       p.peak_von_mises_pa / kMpa, p.peak_von_mises_time_s, p.peak_displacement_m / kMm,
                       p.peak_displacement_time_s,
                       p.has_static_study ? fmt::format("{:.3f}", p.static_von_mises_pa / kMpa) : "-",
                       p.has_static_study ? fmt::format("{:.5f}", p.static_displacement_m / kMm) : "-");
  for (const auto& p : parts) out += fmt::format("  {:<{}} solver: {}\n", p.body, width, p.solver_summary);
  if (several_planes)
    out += "  (each part alone under the planar multibody reactions; the parts sit in several planes, so the moments "
           "between the planes are in the elastic assembly's stress only, below)\n";
  return out;
}

}  // namespace kinetofem::pipeline
