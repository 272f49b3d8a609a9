// The frequency picture (png_plots.hpp, 6.): the lowest natural frequencies over the motion.
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

FrequencyPictureInfo write_frequency_picture(const ResultsFile& results, const std::filesystem::path& png,
                                             const PictureOptions& options) {
  const NaturalFrequencies f = read_natural_frequencies(results);
  const FrequencyPictureInfo info{f.lowest_first_hz, f.lowest_first_time_s, f.highest_first_hz, f.modes(),
                                  f.static_hz.empty() ? kNaN : f.static_hz.front()};
  std::vector<Curve> modes;
  for (int k = 0; k < f.modes(); ++k)
    modes.push_back({fmt::format("mode {}", k + 1), f.time_s, as_vector(f.hz.col(k)), kPalette[size_t(k) % kPalette.size()],
                     false});

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  title(cr, canvas, fmt::format("{}: natural frequencies of the manipulator over the motion", case_name(results, options)),
        fmt::format("the {} lowest modes of the elastic assembly in each pose, {:.2f} .. {:.2f} s; mode 1 from {:.2f} to "
                    "{:.2f} Hz{}",
                    f.modes(), f.time_s.front(), f.time_s.back(), f.lowest_first_hz, f.highest_first_hz,
                    f.static_hz.empty() ? std::string("") : fmt::format("; static pose {:.2f} Hz", f.static_hz.front())));
  const double left = 100, ticks_w = f.static_hz.empty() ? 0.0 : 50.0, legend_w = 210, top = 100, bottom = 70;
  const double width = canvas.width() - left - ticks_w - legend_w - 30;
  const double legend_x = left + width + ticks_w + 25;
  const Axes ax = draw_curves(cr, Axes{left, top, width, canvas.height() - top - bottom, 0, 1, 0, 1}, modes,
                              "frequency [Hz]", "time [s]", "Natural frequencies (mode k: the k-th lowest)", legend_x,
                              {.headroom = 0.08, .also_y = f.static_hz});
  if (!f.static_hz.empty()) {
    // Ticks just right of the frame, one per mode, and their label along them.
    const double x = ax.left + ax.width;
    cairo_save(cr);
    cairo_set_line_width(cr, 3.0);
    double y_lo = ax.top + ax.height, y_hi = ax.top;
    for (size_t k = 0; k < f.static_hz.size(); ++k) {
      const double py = ax.Y(f.static_hz[k]);
      y_lo = std::min(y_lo, py), y_hi = std::max(y_hi, py);
      set_colour(cr, kPalette[k % kPalette.size()]);
      cairo_move_to(cr, x + 3, py);
      cairo_line_to(cr, x + 21, py);
      cairo_stroke(cr);
    }
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    text(cr, x + 38, (y_lo + y_hi) / 2, "static pose", 13, 0.5, 0.5, false, -std::numbers::pi / 2);
    // The legend's row for them, under the modes'.
    const double ly = ax.top + 8 + 22.0 * double(modes.size()) + 6;
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_move_to(cr, legend_x + 8, ly);
    cairo_line_to(cr, legend_x + 26, ly);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, legend_x + 42, ly, "static pose (ticks)", 13, 0.0, 0.5);
    cairo_restore(cr);
  }
  mark_point(cr, ax, ax.X(info.lowest_first_time_s), ax.Y(info.lowest_first_hz),
             fmt::format("lowest mode 1: {:.2f} Hz at t = {:.3f} s", info.lowest_first_hz, info.lowest_first_time_s), 13, 0,
             0);  // above the line unless at the top: mode 1 lies near the time axis and its labels
  canvas.save(png);
  return info;
}

}  // namespace kinetofem::post
