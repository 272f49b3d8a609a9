// The mechanism loads picture (png_plots.hpp, 2.): joint reactions, chain tension, drive efforts and
// transmission moments over time.
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/time_history.hpp"
#include "png_canvas.hpp"
#include "png_common.hpp"

namespace kinetofem::post {

using namespace drawing;

namespace {

// The legend label of a mechanism history to plot, or "" to leave it out.
// Files of kinetofem >= 0.2 name histories joint.<j>.on_<b>.force_world,
// chain.<c>.tension, drive.<d>.effort (pipeline/histories.hpp); one side of
// each joint is enough (the other carries the same magnitude). Older files:
// reaction_<j>_on_<b>, chain_tension, drive_torque.
std::string legend_label(const std::string& name, bool magnitude, std::set<std::string>& joints_seen) {
  auto field = [&](int k) {
    std::size_t start = 0;
    for (int i = 0; i < k; ++i) start = name.find('.', start) + 1;
    return name.substr(start, name.find('.', start) - start);
  };
  if (name.rfind("joint.", 0) == 0) {
    if (name.size() < 12 || name.compare(name.size() - 12, 12, ".force_world") != 0) return "";
    if (!joints_seen.insert(field(1)).second) return "";
    return "|R| joint " + field(1);
  }
  if (name.rfind("chain.", 0) == 0)
    return name.size() > 8 && name.compare(name.size() - 8, 8, ".tension") == 0 ? "chain " + field(1) + " tension" : "";
  if (name.rfind("drive.", 0) == 0)
    return name.size() > 7 && name.compare(name.size() - 7, 7, ".effort") == 0 ? "drive " + field(1) : "";
  if (name.rfind("transmission.", 0) == 0)  // its moment on the output's body_j; the pull is that over the radius
    return name.size() > 14 && name.compare(name.size() - 14, 14, ".moment_output") == 0
               ? "transmission " + field(1) + " (output)"
               : "";
  if (name.find('.') != std::string::npos) return "";  // body., energy., check., point.: not loads
  std::string s = name;
  if (s.rfind("reaction_", 0) == 0) s = "R " + s.substr(9);
  for (auto pos = s.find('_'); pos != std::string::npos; pos = s.find('_')) s[pos] = ' ';
  if (magnitude) s = s.rfind("R ", 0) == 0 ? "|R| " + s.substr(2) : "|" + s + "|";
  return s;
}

}  // namespace

void write_mechanism_loads_picture(const ResultsFile& results, const std::filesystem::path& png,
                                   const PictureOptions& options) {
  std::vector<Curve> forces, torques;
  std::set<std::string> joints_seen;
  for (const auto& name : results.histories()) {
    const TimeHistory h = mechanism_history(results, name);
    if (h.units != "N" && h.units != "N*m") continue;
    const bool magnitude = h.values.cols() > 1;
    const std::string label = legend_label(name, magnitude, joints_seen);
    if (label.empty()) continue;
    const Eigen::VectorXd y = magnitude ? h.magnitude() : Eigen::VectorXd(h.values.col(0));
    Curve c{label, h.time_s, std::vector<double>(y.data(), y.data() + y.size()), {}, false};
    (h.units == "N" ? forces : torques).push_back(std::move(c));
  }
  require(!forces.empty() || !torques.empty(), "'{}' has no mechanism history in N or N*m to plot",
          results.path().string());
  // Joint reactions solid, other forces (chain tension) dashed and drawn last:
  // the chain tension equals |R| of the chain on the arm and must stay visible.
  std::stable_partition(forces.begin(), forces.end(), [](const Curve& c) { return c.label.rfind("|R|", 0) == 0; });
  size_t colour = 0;
  for (auto* group : {&forces, &torques})
    for (auto& c : *group) {
      c.colour = kPalette[colour++ % kPalette.size()];
      c.dashed = c.label.rfind("|R|", 0) != 0 && group == &forces;
    }

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  const double t_end = forces.empty() ? torques.front().x.back() : forces.front().x.back();
  title(cr, canvas,
        fmt::format("{}: joint forces, chain tension, drive efforts and transmission moments over the motion",
                    case_name(results, options)),
        fmt::format("mechanism histories, 0 .. {:.2f} s; |R|: magnitude of the force a joint transmits", t_end));
  const double left = 100, legend_w = 250, top = 100, bottom = 70, gap = 90;
  const double width = canvas.width() - left - legend_w - 30;
  const int panels = int(!forces.empty()) + int(!torques.empty());
  const double total_h = canvas.height() - top - bottom - (panels - 1) * gap;
  const double force_h = panels == 2 ? total_h * 0.6 : total_h;
  double y = top;
  if (!forces.empty()) {
    draw_curves(cr, Axes{left, y, width, force_h, 0, 1, 0, 1}, forces, "force [N]", "time [s]",
                "Joint reaction magnitudes, chain tension, linear drives' forces", left + width + 25);
    y += force_h + gap;
  }
  if (!torques.empty())
    draw_curves(cr, Axes{left, y, width, total_h - (panels == 2 ? force_h : 0), 0, 1, 0, 1}, torques,
                "torque [N·m]", "time [s]", "Drive torques, transmission moments", left + width + 25);
  canvas.save(png);
}

}  // namespace kinetofem::post
