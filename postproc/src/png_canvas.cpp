#include "png_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "kinetofem/core/error.hpp"

namespace kinetofem::post::drawing {

Rgb turbo(double x) {
  x = std::clamp(x, 0.0, 1.0);
  auto poly = [x](double c0, double c1, double c2, double c3, double c4, double c5) {
    return std::clamp(c0 + x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5)))), 0.0, 1.0);
  };
  return {poly(0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943),
          poly(0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604),
          poly(0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973)};
}

void set_colour(cairo_t* cr, const Rgb& c, double alpha) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

// Text anchored at (x, y): ax = 0 left, 0.5 centre, 1 right; ay = 0 top, 0.5 middle, 1 baseline.
void text(cairo_t* cr, double x, double y, const std::string& s, double size, double ax,
          double ay, bool bold, double angle) {
  cairo_save(cr);
  cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_font_extents_t f;
  cairo_font_extents(cr, &f);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, angle);
  // ay measured on the font's cap height so rows of labels line up.
  cairo_move_to(cr, -e.x_advance * ax, f.ascent * 0.75 * (1.0 - ay));
  cairo_show_text(cr, s.c_str());
  cairo_restore(cr);
}

double text_width(cairo_t* cr, const std::string& s, double size) {
  cairo_save(cr);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  cairo_restore(cr);
  return e.x_advance;
}

// A 1-2-5 step giving about `target` intervals over `range`.
double nice_step(double range, int target) {
  if (!(range > 0)) return 1.0;
  const double raw = range / target, mag = std::pow(10.0, std::floor(std::log10(raw))), f = raw / mag;
  return (f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0) * mag;
}

std::vector<double> ticks_of(double lo, double hi, double step) {
  std::vector<double> t;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step)
    t.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  return t;
}

std::string tick_label(double v, double step) {
  const int decimals = std::max(0, int(-std::floor(std::log10(step) + 1e-9)));
  return fmt::format("{:.{}f}", v, decimals);
}


// The ticks of a log axis from y0 to y1 (> 0): every decade 10^k inside, and their labels.
std::vector<double> decades_of(double y0, double y1) {
  std::vector<double> t;
  for (double k = std::ceil(std::log10(y0) - 1e-9); k <= std::floor(std::log10(y1) + 1e-9); ++k)
    t.push_back(std::pow(10.0, k));
  return t;
}
std::string decade_label(double v) { return v >= 1e-3 && v < 1e5 ? fmt::format("{:g}", v) : fmt::format("1e{:.0f}", std::log10(v)); }

void clip_to(cairo_t* cr, const Axes& a) {
  cairo_rectangle(cr, a.left, a.top, a.width, a.height);
  cairo_clip(cr);
}

// Frame, grid, ticks, tick labels and axis labels of `a`.
void draw_axes(cairo_t* cr, const Axes& a, const std::string& xlabel, const std::string& ylabel,
               double font, bool grid, int target_ticks_x, int target_ticks_y) {
  const double sx = nice_step(a.x1 - a.x0, std::max(2, target_ticks_x));
  const double sy = nice_step(a.y1 - a.y0, std::max(2, target_ticks_y));
  const std::vector<double> y_ticks = a.log_y ? decades_of(a.y0, a.y1) : ticks_of(a.y0, a.y1, sy);
  cairo_save(cr);
  cairo_set_line_width(cr, 1.0);
  if (grid) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    for (double x : ticks_of(a.x0, a.x1, sx)) {
      cairo_move_to(cr, std::round(a.X(x)) + 0.5, a.top);
      cairo_line_to(cr, std::round(a.X(x)) + 0.5, a.top + a.height);
    }
    for (double y : y_ticks) {
      cairo_move_to(cr, a.left, std::round(a.Y(y)) + 0.5);
      cairo_line_to(cr, a.left + a.width, std::round(a.Y(y)) + 0.5);
    }
    cairo_stroke(cr);
    if (a.log_y) {  // fainter lines at 2 .. 9 x 10^k
      cairo_set_source_rgb(cr, 0.95, 0.95, 0.95);
      for (double k = std::floor(std::log10(a.y0)); k <= std::ceil(std::log10(a.y1)); ++k)
        for (int f = 2; f <= 9; ++f) {
          const double y = f * std::pow(10.0, k);
          if (y <= a.y0 || y >= a.y1) continue;
          cairo_move_to(cr, a.left, std::round(a.Y(y)) + 0.5);
          cairo_line_to(cr, a.left + a.width, std::round(a.Y(y)) + 0.5);
        }
      cairo_stroke(cr);
    }
  }
  cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
  cairo_rectangle(cr, std::round(a.left) + 0.5, std::round(a.top) + 0.5, std::round(a.width), std::round(a.height));
  cairo_stroke(cr);
  double widest = 0;
  for (double x : ticks_of(a.x0, a.x1, sx)) {
    const double px = std::round(a.X(x)) + 0.5;
    cairo_move_to(cr, px, a.top + a.height);
    cairo_line_to(cr, px, a.top + a.height + 5);
    text(cr, px, a.top + a.height + 8, tick_label(x, sx), font, 0.5, 0.0);
  }
  for (double y : y_ticks) {
    const double py = std::round(a.Y(y)) + 0.5;
    cairo_move_to(cr, a.left - 5, py);
    cairo_line_to(cr, a.left, py);
    const std::string label = a.log_y ? decade_label(y) : tick_label(y, sy);
    widest = std::max(widest, text_width(cr, label, font));
    text(cr, a.left - 8, py, label, font, 1.0, 0.5);
  }
  cairo_stroke(cr);
  text(cr, a.left + a.width / 2, a.top + a.height + 14 + 1.4 * font, xlabel, font, 0.5, 0.0);
  text(cr, a.left - 14 - widest, a.top + a.height / 2, ylabel, font, 0.5, 1.0, false, -std::numbers::pi / 2);
  cairo_restore(cr);
}

// Two centred lines, shrunk to fit the picture's width.
void title(cairo_t* cr, const Canvas& canvas, const std::string& line1, const std::string& line2) {
  auto fitted = [&](const std::string& s, double size, bool bold) {
    cairo_save(cr);
    cairo_select_font_face(cr, kFont, CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    const double w = text_width(cr, s, size);
    cairo_restore(cr);
    return std::max(8.0, std::min(size, size * (canvas.width() - 30) / std::max(w, 1.0)));
  };
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, canvas.width() / 2.0, 30, line1, fitted(line1, 20, true), 0.5, 1.0, true);
  if (!line2.empty()) {
    cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    text(cr, canvas.width() / 2.0, 54, line2, fitted(line2, 14, false), 0.5, 1.0);
    cairo_set_source_rgb(cr, 0, 0, 0);
  }
}

// A ring at (px, py) with a leader line and a boxed bold label. The label goes
// away from the nearer side edge (to the other side where only that one has room
// for it) and below the point near the top edge, unless dx, dy (+-1) are given.
void mark_point(cairo_t* cr, const Axes& ax, double px, double py, const std::string& label, double font, int dx,
                int dy) {
  if (dx == 0) {
    const double needed = 30 + text_width(cr, label, font) * 1.08;
    const bool right = px + needed <= ax.left + ax.width, left = px - needed >= ax.left;
    dx = right != left ? (right ? 1 : -1) : px - ax.left > ax.left + ax.width - px ? -1 : 1;
  }
  if (dy == 0) dy = py < ax.top + 40 ? 1 : -1;
  cairo_save(cr);
  cairo_new_path(cr);  // text() leaves a current point; the ring must not start from it
  cairo_set_line_width(cr, 4);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_arc(cr, px, py, 8, 0, 2 * std::numbers::pi);
  cairo_stroke(cr);
  cairo_set_line_width(cr, 2);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_arc(cr, px, py, 8, 0, 2 * std::numbers::pi);
  cairo_stroke(cr);
  cairo_move_to(cr, px + dx * 6, py + dy * 6);
  cairo_line_to(cr, px + dx * 22, py + dy * 22);
  cairo_stroke(cr);
  const double lx = px + dx * 24, ly = py + dy * 24 + (dy > 0 ? 12 : 0), tw = text_width(cr, label, font) * 1.08;
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_rectangle(cr, dx > 0 ? lx - 2 : lx - tw - 2, ly - 13, tw + 4, 17);
  cairo_fill(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, lx, ly, label, font, dx > 0 ? 0.0 : 1.0, 1.0, true);
  cairo_restore(cr);
}

// A vertical "turbo" colour bar from 0 (bottom) to vmax (display units) with its heading above.
void draw_colour_bar(cairo_t* cr, double bx, double by, double bw, double bh, double vmax, const std::string& heading,
                     const std::string& unit_label, double font) {
  for (int i = 0; i < 256; ++i) {
    set_colour(cr, turbo((i + 0.5) / 256.0));
    cairo_rectangle(cr, bx, by + bh - (i + 1) * bh / 256.0, bw, bh / 256.0 + 0.6);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, bx + 0.5, by + 0.5, bw, bh);
  cairo_stroke(cr);
  const double step = nice_step(vmax, 6);
  for (double t : ticks_of(0.0, vmax, step)) {
    const double py = std::round(by + bh - t / vmax * bh) + 0.5;
    cairo_move_to(cr, bx + bw, py);
    cairo_line_to(cr, bx + bw + 5, py);
    cairo_stroke(cr);
    if (vmax - t > 0.35 * step) text(cr, bx + bw + 8, py, tick_label(t, step), font - 1, 0.0, 0.5);
  }
  const int decimals = std::clamp(2 - int(std::floor(std::log10(vmax))), 2, 6);  // 3 significant digits below 1
  text(cr, bx + bw + 8, by + 0.5, fmt::format("{:.{}f}", vmax, decimals), font - 1, 0.0, 0.5, true);
  text(cr, bx + bw / 2, by - 24, heading, font, 0.5, 1.0, true);
  if (!unit_label.empty()) text(cr, bx + bw / 2, by - 8, "[" + unit_label + "]", font, 0.5, 1.0);
}

// A line panel with its own y range (CurveRange), a legend at its right; returns the axes drawn.
Axes draw_curves(cairo_t* cr, const Axes& frame, const std::vector<Curve>& curves, const std::string& ylabel,
                 const std::string& xlabel, const std::string& panel_title, double legend_x,
                 const CurveRange& range) {
  double lo = 0, hi = 0, x0 = curves.front().x.front(), x1 = curves.front().x.back();
  for (const auto& c : curves)
    for (size_t i = 0; i < c.y.size(); ++i) {
      lo = std::min(lo, c.y[i]), hi = std::max(hi, c.y[i]);
      x0 = std::min(x0, c.x[i]), x1 = std::max(x1, c.x[i]);
    }
  for (double y : range.also_y) lo = std::min(lo, y), hi = std::max(hi, y);
  if (x1 <= x0) x1 = x0 + 1;
  Axes ax = frame;
  ax.x0 = x0, ax.x1 = x1;
  if (range.log_floor > 0) {
    ax.log_y = true;
    ax.y0 = std::pow(10.0, std::floor(std::log10(range.log_floor) + 1e-9));
    ax.y1 = std::pow(10.0, std::ceil(std::log10(std::max(hi, 10 * ax.y0)) - 1e-9));
  } else {
    if (hi - lo <= 0) hi = lo + 1;
    hi += range.headroom * (hi - lo);
    const double step = nice_step(hi - lo, 6);
    ax.y0 = std::floor(lo / step + 1e-9) * step, ax.y1 = std::ceil(hi / step - 1e-9) * step;
  }
  const double font = 13;
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, ax.left, ax.top - 8, panel_title, font + 2, 0.0, 1.0, true);
  draw_axes(cr, ax, xlabel, ylabel, font, true);
  cairo_save(cr);
  clip_to(cr, ax);
  cairo_set_line_width(cr, 2.0);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const auto& c : curves) {
    set_colour(cr, c.colour);
    const double dash[] = {8.0, 5.0};
    cairo_set_dash(cr, dash, c.dashed ? 2 : 0, 0);
    for (size_t i = 0; i < c.x.size(); ++i)
      (i ? cairo_line_to : cairo_move_to)(cr, ax.X(c.x[i]), ax.Y(c.y[i]));
    cairo_stroke(cr);
  }
  cairo_restore(cr);
  // Legend: one row per curve, beside the panel.
  double y = ax.top + 8;
  for (const auto& c : curves) {
    cairo_save(cr);
    set_colour(cr, c.colour);
    cairo_set_line_width(cr, 3.0);
    const double dash[] = {8.0, 5.0};
    cairo_set_dash(cr, dash, c.dashed ? 2 : 0, 0);
    cairo_move_to(cr, legend_x, y);
    cairo_line_to(cr, legend_x + 34, y);
    cairo_stroke(cr);
    cairo_restore(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, legend_x + 42, y, c.label, font, 0.0, 0.5);
    y += 22;
  }
  return ax;
}

// A vertical line through the whole of `ax` at x, with a label at its top (to its right).
void vertical_line(cairo_t* cr, const Axes& ax, double x, const Rgb& colour, const std::string& label, bool dashed) {
  const double px = std::round(ax.X(x)) + 0.5;
  cairo_save(cr);
  cairo_new_path(cr);
  set_colour(cr, colour);
  cairo_set_line_width(cr, 1.5);
  const double dash[] = {6.0, 4.0};
  cairo_set_dash(cr, dash, dashed ? 2 : 0, 0);
  cairo_move_to(cr, px, ax.top);
  cairo_line_to(cr, px, ax.top + ax.height);
  cairo_stroke(cr);
  const bool right = px < ax.left + ax.width - 260;  // the label on the side with room
  const double tw = text_width(cr, label, 13) * 1.08;
  cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
  cairo_rectangle(cr, right ? px + 4 : px - tw - 8, ax.top + 6, tw + 4, 18);
  cairo_fill(cr);
  set_colour(cr, colour);
  text(cr, right ? px + 6 : px - 6, ax.top + 20, label, 13, right ? 0.0 : 1.0, 1.0, true);
  cairo_restore(cr);
}

Canvas::Canvas(int width, int height) : width_(width), height_(height) {
  require(width >= 200 && height >= 150 && width <= 10000 && height <= 10000,
          "picture size {} x {} px is outside 200 x 150 .. 10000 x 10000", width, height);
  surface_.reset(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, width, height));
  cr_.reset(cairo_create(surface_.get()));
  require(cairo_status(cr_.get()) == CAIRO_STATUS_SUCCESS, "cairo: cannot create a {} x {} image: {}",
          width, height, cairo_status_to_string(cairo_status(cr_.get())));
  cairo_set_source_rgb(cr_.get(), 1, 1, 1);
  cairo_paint(cr_.get());
  cairo_select_font_face(cr_.get(), kFont, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
}

void Canvas::save(const std::filesystem::path& path) const {
  const cairo_status_t drawn = cairo_status(cr_.get());
  require(drawn == CAIRO_STATUS_SUCCESS, "{}: drawing failed: {}", path.string(), cairo_status_to_string(drawn));
  cairo_surface_flush(surface_.get());
  const cairo_status_t status = cairo_surface_write_to_png(surface_.get(), path.string().c_str());
  require(status == CAIRO_STATUS_SUCCESS, "{}: cannot write the PNG: {}", path.string(),
          cairo_status_to_string(status));
}

}  // namespace kinetofem::post::drawing
