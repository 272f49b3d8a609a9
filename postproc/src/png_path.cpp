// The path picture (png_plots.hpp, 3.): a point's x-y path over the motion.
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/time_history.hpp"
#include "png_canvas.hpp"
#include "png_common.hpp"

namespace kinetofem::post {

using namespace drawing;

void write_path_picture(const ResultsFile& results, const std::filesystem::path& png, const std::string& history,
                        const PictureOptions& options) {
  const TimeHistory h = mechanism_history(results, history);
  require(h.values.cols() >= 2 && h.units == "m", "mechanism history '{}' is not an x-y path in m (units '{}', {} columns)",
          history, h.units, h.values.cols());
  require(h.values.rows() >= 2, "mechanism history '{}' has {} points; a path needs 2", history, h.values.rows());
  const Eigen::VectorXd x = h.values.col(0) * 1e3, y = h.values.col(1) * 1e3;

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  const std::string point = history.rfind("gripper_point_", 0) == 0 ? "gripper point " + history.substr(14)
                            : history.rfind("point.", 0) == 0      ? "point " + history.substr(6)
                                                                  : history;
  title(cr, canvas, fmt::format("{}: path of the {} over the motion", case_name(results, options), point),
        fmt::format("x-y plane of the mechanism, equal scales; {:.2f} .. {:.2f} s, dots every tenth of the motion time",
                    h.time_s.front(), h.time_s.back()));
  // Equal aspect: one px/mm for both axes, the range padded to fill the frame.
  const double left = 110, top = 90, right = 40, bottom = 80;
  const double fw = canvas.width() - left - right, fh = canvas.height() - top - bottom;
  double x0 = x.minCoeff(), x1 = x.maxCoeff(), y0 = y.minCoeff(), y1 = y.maxCoeff();
  const double span = std::max({x1 - x0, y1 - y0, 1e-6});
  x0 -= 0.08 * span, x1 += 0.08 * span, y0 -= 0.08 * span, y1 += 0.08 * span;
  const double s = std::min(fw / (x1 - x0), fh / (y1 - y0));
  const double cx = (x0 + x1) / 2, cy = (y0 + y1) / 2;
  Axes ax{left, top, fw, fh, cx - fw / s / 2, cx + fw / s / 2, cy - fh / s / 2, cy + fh / s / 2};
  draw_axes(cr, ax, "x [mm]", "y [mm]", 13, true, int(fw / 100), int(fh / 90));

  cairo_save(cr);
  clip_to(cr, ax);
  set_colour(cr, kPalette[0]);
  cairo_set_line_width(cr, 2.5);
  for (long i = 0; i < x.size(); ++i) (i ? cairo_line_to : cairo_move_to)(cr, ax.X(x(i)), ax.Y(y(i)));
  cairo_stroke(cr);
  // Dots at tenths of the motion time (nearest output time).
  const double t0 = h.time_s.front(), t1 = h.time_s.back();
  for (int j = 1; j < 10; ++j) {
    const double tj = t0 + j * (t1 - t0) / 10;
    size_t best = 0;
    for (size_t i = 1; i < h.time_s.size(); ++i)
      if (std::abs(h.time_s[i] - tj) < std::abs(h.time_s[best] - tj)) best = i;
    cairo_arc(cr, ax.X(x(long(best))), ax.Y(y(long(best))), 4, 0, 2 * std::numbers::pi);
    cairo_fill(cr);
  }
  auto marker = [&](long i, const Rgb& c, const std::string& label) {
    const double px = ax.X(x(i)), py = ax.Y(y(i));
    set_colour(cr, c);
    cairo_new_path(cr);  // the previous label's text left a current point
    cairo_arc(cr, px, py, 8, 0, 2 * std::numbers::pi);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_set_line_width(cr, 1.5);
    cairo_arc(cr, px, py, 8, 0, 2 * std::numbers::pi);
    cairo_stroke(cr);
    const bool right_side = px < ax.left + ax.width - 200;
    text(cr, px + (right_side ? 14 : -14), py - 12, label, 14, right_side ? 0.0 : 1.0, 1.0, true);
  };
  marker(0, kPalette[2], fmt::format("start, t = {:.2f} s ({:.1f}, {:.1f}) mm", t0, x(0), y(0)));
  const long last = x.size() - 1;
  marker(last, kPalette[3], fmt::format("end, t = {:.2f} s ({:.1f}, {:.1f}) mm", t1, x(last), y(last)));
  cairo_restore(cr);
  canvas.save(png);
}

}  // namespace kinetofem::post
