// The point deflection picture (png_plots.hpp, 5.): a tracked point's elastic displacement and its contributions.
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <cmath>
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

PointDeflectionInfo write_point_deflection_picture(const ResultsFile& results, const std::filesystem::path& png,
                                                   const std::string& point, const PictureOptions& options) {
  const std::string total_name = point_history(point, "displacement");
  require(has(results.histories(), total_name),
          "'{}' has no history {} (tracked points of the elastic assembly: {})", results.path().string(), total_name,
          joined(assembly_contents(results).points));
  const TimeHistory total = mechanism_history(results, total_name);
  require(total.values.cols() == 3 && total.units == "m" && total.time_s.size() >= 2,
          "'{}': history {} is not a displacement in m over 2 or more times (units '{}', {} x {})",
          results.path().string(), total_name, total.units, total.values.rows(), total.values.cols());
  const TimeHistory magnitude = *point_magnitude(results, point);
  const Eigen::VectorXd u_abs = magnitude.values.col(0);

  PointDeflectionInfo info;
  const size_t peak = argmax(u_abs);
  info.max_m = u_abs(fem::Index(peak));
  info.time_s = magnitude.time_s[peak];

  auto mm = [](const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
  const std::vector<std::string> axes = {"x", "y", "z"};
  std::vector<Curve> components;
  for (long c = 0; c < 3; ++c)
    components.push_back({axes[size_t(c)], total.time_s, mm(total.values.col(c) * 1e3), kPalette[size_t(c)], false});
  components.push_back({"|u|", magnitude.time_s, mm(u_abs * 1e3), {0.1, 0.1, 0.1}, false});

  // Contributions: their component along the total's direction, c_i . u / |u|.
  const std::string prefix = point_history(point, "from.");
  std::vector<Curve> contributions;
  for (const auto& name : results.histories()) {
    if (name.rfind(prefix, 0) != 0) continue;
    const TimeHistory c = mechanism_history(results, name);
    require(c.values.cols() == 3 && c.values.rows() == total.values.rows(),
            "'{}': history {} is {} x {}, expected {} x 3 like {}", results.path().string(), name, c.values.rows(),
            c.values.cols(), total.values.rows(), total_name);
    info.contributors.push_back(name.substr(prefix.size()));
    std::vector<double> along(c.time_s.size());
    for (long k = 0; k < c.values.rows(); ++k) {
      const Eigen::Vector3d u = total.values.row(k).transpose(), ci = c.values.row(k).transpose();
      along[size_t(k)] = u.norm() > 0 ? ci.dot(u) / u.norm() * 1e3 : 0.0;
    }
    std::string label = info.contributors.back();
    if (const size_t dot = label.find('.'); dot != std::string::npos) label[dot] = ' ';
    contributions.push_back({label, c.time_s, std::move(along), kPalette[contributions.size() % kPalette.size()], false});
  }

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  title(cr, canvas,
        fmt::format("{}: elastic deflection of point {} over the motion", case_name(results, options), point),
        fmt::format("elastic assembly, world axes; max |u| = {} at t = {:.3f} s; {:.2f} .. {:.2f} s",
                    mm_text(info.max_m), info.time_s, total.time_s.front(), total.time_s.back()));
  const double left = 100, legend_w = 250, top = 100, bottom = 70, gap = 90;
  const double width = canvas.width() - left - legend_w - 30;
  const double panel_h = contributions.empty() ? canvas.height() - top - bottom
                                               : (canvas.height() - top - bottom - gap) / 2;
  const Axes ax = draw_curves(cr, Axes{left, top, width, panel_h, 0, 1, 0, 1}, components, "displacement [mm]",
                              "time [s]", fmt::format("Elastic displacement of {} (world axes)", point),
                              left + width + 25, {.headroom = 0.2});
  mark_point(cr, ax, ax.X(info.time_s), ax.Y(info.max_m * 1e3),
             fmt::format("max {} at t = {:.3f} s", mm_text(info.max_m), info.time_s), 13, 0, -1);
  if (!contributions.empty()) {
    contributions.push_back({"total |u|", magnitude.time_s, mm(u_abs * 1e3), {0.1, 0.1, 0.1}, true});
    draw_curves(cr, Axes{left, top + panel_h + gap, width, panel_h, 0, 1, 0, 1}, contributions, "along u [mm]",
                "time [s]", "Contributions, component along u (they add up to |u|)",
                left + width + 25);
  }
  canvas.save(png);
  return info;
}

}  // namespace kinetofem::post
