#pragma once
// The drawing primitives of the PNG pictures (png_plots.hpp): an ARGB32 image
// drawn with cairo, colours, text, axes with ticks, line panels with a legend,
// marks and a colour bar. Coordinates are picture pixels, x to the right and y
// downwards from the top left corner; an Axes maps a data range onto a
// rectangle of them (data y upwards). Nothing here reads a results file.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <cairo.h>

namespace kinetofem::post::drawing {

inline constexpr const char* kFont = "DejaVu Sans";

struct Rgb {
  double r, g, b;
};

// Distinct line colours (the Tableau 10 palette).
inline constexpr std::array<Rgb, 10> kPalette = {{{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055},
                                                  {0.173, 0.627, 0.173}, {0.839, 0.153, 0.157},
                                                  {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294},
                                                  {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498},
                                                  {0.737, 0.741, 0.133}, {0.090, 0.745, 0.812}}};

// "Turbo" colour map (Mikhailov 2019), its published polynomial fit; x in [0, 1] (clamped).
Rgb turbo(double x);

// An ARGB32 image, white, and its cairo context; save() writes the PNG or
// throws Error naming the file. Owns both cairo objects.
class Canvas {
 public:
  // Throws Error if the size is outside 200 x 150 .. 10000 x 10000 px.
  Canvas(int width, int height);
  cairo_t* cr() const { return cr_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  void save(const std::filesystem::path& path) const;

 private:
  struct SurfaceDeleter {
    void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
  };
  struct ContextDeleter {
    void operator()(cairo_t* c) const { cairo_destroy(c); }
  };
  int width_, height_;
  std::unique_ptr<cairo_surface_t, SurfaceDeleter> surface_;
  std::unique_ptr<cairo_t, ContextDeleter> cr_;
};

void set_colour(cairo_t* cr, const Rgb& c, double alpha = 1.0);

// Text anchored at (x, y): ax = 0 left, 0.5 centre, 1 right; ay = 0 top, 0.5 middle, 1 baseline.
void text(cairo_t* cr, double x, double y, const std::string& s, double size, double ax = 0.0,
          double ay = 1.0, bool bold = false, double angle = 0.0);
double text_width(cairo_t* cr, const std::string& s, double size);

// A 1-2-5 step giving about `target` intervals over `range`.
double nice_step(double range, int target);
// The multiples of step from lo to hi (round-off tolerant).
std::vector<double> ticks_of(double lo, double hi, double step);
std::string tick_label(double v, double step);

// A rectangle of the picture (px) showing a data range; y grows upwards in data. With log_y
// (0 < y0 < y1) y is drawn on a log scale, and values at or below y0 at the bottom edge.
struct Axes {
  double left, top, width, height;  // px
  double x0, x1, y0, y1;            // data
  bool log_y = false;
  double X(double x) const { return left + (x - x0) / (x1 - x0) * width; }
  double Y(double y) const {
    const double share = log_y ? std::log10(std::max(y, y0) / y0) / std::log10(y1 / y0) : (y - y0) / (y1 - y0);
    return top + height - share * height;
  }
};

// The ticks of a log axis from y0 to y1 (> 0): every decade 10^k inside, and their labels.
std::vector<double> decades_of(double y0, double y1);
std::string decade_label(double v);

void clip_to(cairo_t* cr, const Axes& a);

// Frame, grid, ticks, tick labels and axis labels of `a`.
void draw_axes(cairo_t* cr, const Axes& a, const std::string& xlabel, const std::string& ylabel,
               double font, bool grid, int target_ticks_x = 8, int target_ticks_y = 6);

// Two centred lines at the top, shrunk to fit the picture's width.
void title(cairo_t* cr, const Canvas& canvas, const std::string& line1, const std::string& line2);

// A ring at (px, py) with a leader line and a boxed bold label. The label goes
// away from the nearer side edge (to the other side where only that one has room
// for it) and below the point near the top edge, unless dx, dy (+-1) are given.
void mark_point(cairo_t* cr, const Axes& ax, double px, double py, const std::string& label, double font, int dx = 0,
                int dy = 0);

// A vertical "turbo" colour bar from 0 (bottom) to vmax (display units) with its heading above.
void draw_colour_bar(cairo_t* cr, double bx, double by, double bw, double bh, double vmax, const std::string& heading,
                     const std::string& unit_label, double font);

struct Curve {
  std::string label;
  std::vector<double> x, y;
  Rgb colour;
  bool dashed = false;
};

// How draw_curves chooses its y range.
struct CurveRange {
  double headroom = 0.0;       // a share of the data's range free above the curves (for a label)
  std::vector<double> also_y;  // values the range must cover too (marks the caller draws)
  // Log scale from the decade at or below `log_floor` (> 0) to the one at or above the largest
  // value; values below the floor are drawn at the bottom edge. 0: linear, 0 included.
  double log_floor = 0.0;
};

// A line panel with its own y range (CurveRange), a legend at its right; returns the axes drawn.
// `curves` must not be empty.
Axes draw_curves(cairo_t* cr, const Axes& frame, const std::vector<Curve>& curves, const std::string& ylabel,
                 const std::string& xlabel, const std::string& panel_title, double legend_x,
                 const CurveRange& range = {});

// A vertical line through the whole of `ax` at x, with a label at its top (to its right).
void vertical_line(cairo_t* cr, const Axes& ax, double x, const Rgb& colour, const std::string& label, bool dashed);

}  // namespace kinetofem::post::drawing
