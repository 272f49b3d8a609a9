// The point vibration picture (png_plots.hpp, 7.): a tracked point's |u| during and after the stroke.
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/vibration_results.hpp"
#include "png_canvas.hpp"
#include "png_common.hpp"

namespace kinetofem::post {

using namespace drawing;

PointVibrationPictureInfo write_point_vibration_picture(const ResultsFile& results, const std::filesystem::path& png,
                                                        const std::string& point, const PictureOptions& options) {
  const PointVibrationData p = read_point_vibration(results, point);
  const PointVibrationPictureInfo info{p.peak_dynamic_m, p.peak_quasi_static_m, p.dynamic_amplification,
                                       p.settling_time_s};
  const Eigen::VectorXd dynamic_mm = p.dynamic_m.rowwise().norm() * 1e3, quasi_mm = p.quasi_static_m.rowwise().norm() * 1e3;
  // After the stop: the deviation from the rest position (the quasi-static u at the end).
  const Eigen::RowVector3d rest = p.quasi_static_m.row(p.quasi_static_m.rows() - 1);
  std::vector<double> after_t, deviation_mm;
  for (size_t k = 0; k < p.time_s.size(); ++k)
    if (p.time_s[k] >= p.stop_time_s - 1e-9) {
      after_t.push_back(p.time_s[k]);
      deviation_mm.push_back((p.dynamic_m.row(Eigen::Index(k)) - rest).norm() * 1e3);
    }
  const double tolerance_mm = p.settling_tolerance_m * 1e3;

  const std::string damping = std::isnan(p.damping_ratio) ? std::string("")
                                                          : fmt::format("modal damping {:.1f} %, ", 100 * p.damping_ratio);
  const std::string settling = std::isfinite(p.settling_time_s)
                                   ? fmt::format("settles within {} {:.3f} s after the stop", mm_text(p.settling_tolerance_m),
                                                 p.settling_time_s)
                                   : fmt::format("does not settle within {}", mm_text(p.settling_tolerance_m));
  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  title(cr, canvas,
        fmt::format("{}: vibration of point {}, dynamic amplification {:.3f}", case_name(results, options), point,
                    p.dynamic_amplification),
        fmt::format("{}peak |u| {} with vibration, {} quasi-static over the stroke (0 .. {:.2f} s); {}", damping,
                    mm_text(p.peak_dynamic_m), mm_text(p.peak_quasi_static_m), p.stop_time_s, settling));
  const double left = 100, legend_w = 300, top = 100, bottom = 70, gap = 90;
  const double width = canvas.width() - left - legend_w - 30, legend_x = left + width + 25;
  const double panel_h = (canvas.height() - top - bottom - gap) / 2;
  const std::vector<Curve> magnitudes = {
      {"|u| with vibration", p.time_s, as_vector(dynamic_mm), kPalette[0], false},
      {"|u| quasi-static", p.time_s, as_vector(quasi_mm), kPalette[1], true}};
  const Axes ax = draw_curves(cr, Axes{left, top, width, panel_h, 0, 1, 0, 1}, magnitudes, "|u| [mm]", "time [s]",
                              fmt::format("Elastic displacement of {} over the motion and after the stop", point), legend_x,
                              {.headroom = 0.25});
  vertical_line(cr, ax, p.stop_time_s, {0.3, 0.3, 0.3}, fmt::format("stop, t = {:.3f} s", p.stop_time_s), true);
  mark_point(cr, ax, ax.X(p.peak_dynamic_time_s), ax.Y(p.peak_dynamic_m * 1e3),
             fmt::format("peak {} at t = {:.3f} s", mm_text(p.peak_dynamic_m), p.peak_dynamic_time_s), 13, 0, -1);

  if (after_t.size() >= 2) {
    // Log scale from a decade below the tolerance (or below the largest deviation, if smaller): the
    // decay and the tolerance stay readable; the dips of |u - u_rest| at its zero crossings are cut there.
    const double largest = *std::max_element(deviation_mm.begin(), deviation_mm.end());
    const double floor_mm = 0.1 * (largest > 0 ? std::min(tolerance_mm, largest) : tolerance_mm);
    const std::vector<Curve> after = {
        {"|u(t) - u_rest| with vibration", after_t, deviation_mm, kPalette[0], false},
        {fmt::format("settling tolerance {}", mm_text(p.settling_tolerance_m)),
         {after_t.front(), after_t.back()}, {tolerance_mm, tolerance_mm}, kPalette[3], true}};
    const Axes ax2 = draw_curves(cr, Axes{left, top + panel_h + gap, width, panel_h, 0, 1, 0, 1}, after,
                                 "|u - u_rest| [mm] (log)", "time [s]",
                                 "After the stop: deviation from the rest position u_rest (quasi-static u at the end)",
                                 legend_x, {.log_floor = floor_mm});
    const double settled_at = p.stop_time_s + p.settling_time_s;
    if (!std::isfinite(p.settling_time_s))
      vertical_line(cr, ax2, after_t.back(), kPalette[2], "does not settle", false);
    else if (settled_at <= after_t.back() + 1e-12)
      vertical_line(cr, ax2, settled_at, kPalette[2], fmt::format("settled {:.3f} s after the stop", p.settling_time_s),
                    false);
    else
      vertical_line(cr, ax2, after_t.back(),  kPalette[2],
                    fmt::format("settles {:.3f} s after the stop, beyond the window", p.settling_time_s), false);
  }
  canvas.save(png);
  return info;
}

}  // namespace kinetofem::post
