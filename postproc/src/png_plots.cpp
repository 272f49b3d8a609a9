#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <numeric>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>
#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/hot_spots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/time_history.hpp"
#include "kinetofem/postproc/vibration_results.hpp"

namespace kinetofem::post {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr const char* kFont = "DejaVu Sans";

struct Rgb {
  double r, g, b;
};

// Distinct line colours (the Tableau 10 palette).
constexpr std::array<Rgb, 10> kPalette = {{{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055},
                                           {0.173, 0.627, 0.173}, {0.839, 0.153, 0.157},
                                           {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294},
                                           {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498},
                                           {0.737, 0.741, 0.133}, {0.090, 0.745, 0.812}}};

// "Turbo" colour map (Mikhailov 2019), its published polynomial fit; x in [0, 1].
Rgb turbo(double x) {
  x = std::clamp(x, 0.0, 1.0);
  auto poly = [x](double c0, double c1, double c2, double c3, double c4, double c5) {
    return std::clamp(c0 + x * (c1 + x * (c2 + x * (c3 + x * (c4 + x * c5)))), 0.0, 1.0);
  };
  return {poly(0.13572138, 4.61539260, -42.66032258, 132.13108234, -152.94239396, 59.28637943),
          poly(0.09140261, 2.19418839, 4.84296658, -14.18503333, 4.27729857, 2.82956604),
          poly(0.10667330, 12.64194608, -60.58204836, 110.36276771, -89.90310912, 27.34824973)};
}

// An ARGB32 image and its cairo context; save() writes the PNG or throws.
class Canvas {
 public:
  Canvas(int width, int height) : width_(width), height_(height) {
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
  cairo_t* cr() const { return cr_.get(); }
  int width() const { return width_; }
  int height() const { return height_; }
  void save(const std::filesystem::path& path) const {
    const cairo_status_t drawn = cairo_status(cr_.get());
    require(drawn == CAIRO_STATUS_SUCCESS, "{}: drawing failed: {}", path.string(), cairo_status_to_string(drawn));
    cairo_surface_flush(surface_.get());
    const cairo_status_t status = cairo_surface_write_to_png(surface_.get(), path.string().c_str());
    require(status == CAIRO_STATUS_SUCCESS, "{}: cannot write the PNG: {}", path.string(),
            cairo_status_to_string(status));
  }

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

void set_colour(cairo_t* cr, const Rgb& c, double alpha = 1.0) { cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha); }

// Text anchored at (x, y): ax = 0 left, 0.5 centre, 1 right; ay = 0 top, 0.5 middle, 1 baseline.
void text(cairo_t* cr, double x, double y, const std::string& s, double size, double ax = 0.0,
          double ay = 1.0, bool bold = false, double angle = 0.0) {
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
               double font, bool grid, int target_ticks_x = 8, int target_ticks_y = 6) {
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

std::string case_name(const ResultsFile& results, const PictureOptions& options) {
  return options.title_name.empty() ? results.path().stem().string() : options.title_name;
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

// ---- boundary surfaces (the stress and the assembly pictures) -------------

// Boundary faces of a mesh: the element faces that belong to one element only,
// as the face's node lists (outward normal, Gmsh face node order).
std::vector<std::vector<fem::Index>> boundary_faces(const fem::Mesh& mesh) {
  using Key = std::array<fem::Index, 4>;  // sorted corner nodes, -1 padded
  std::vector<std::vector<fem::Index>> faces;
  std::vector<std::pair<Key, size_t>> keys;
  for (const auto& block : mesh.blocks) {
    const int nf = fem::faces_per_element(block.type);
    const fem::FaceType type = fem::face_type_of(block.type);
    const long corners = type == fem::FaceType::Tri3 || type == fem::FaceType::Tri6 ? 3 : 4;
    std::vector<std::vector<int>> local;
    for (int f = 0; f < nf; ++f) local.push_back(fem::element_face_nodes(block.type, f));
    for (fem::Index e = 0; e < block.size(); ++e) {
      const auto element = block.element(e);
      for (const auto& l : local) {
        std::vector<fem::Index> nodes;
        for (int i : l) nodes.push_back(element[size_t(i)]);
        Key key = {-1, -1, -1, -1};
        std::copy_n(nodes.begin(), corners, key.begin());
        for (long a = 1; a < corners; ++a)  // insertion sort of 3 or 4 corners
          for (long b = a; b > 0 && key[size_t(b - 1)] > key[size_t(b)]; --b) std::swap(key[size_t(b - 1)], key[size_t(b)]);
        keys.emplace_back(key, faces.size());
        faces.push_back(std::move(nodes));
      }
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::vector<fem::Index>> out;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].first == keys[i].first) ++j;
    if (j - i == 1) out.push_back(std::move(faces[keys[i].second]));
    i = j;
  }
  return out;
}

// Corners of a boundary face: 3 (TRI3, TRI6) or 4 (QUAD4, QUAD8); the mid-edge
// node of edge (i, i+1) of a quadratic face is node corners + i.
size_t corners_of(const std::vector<fem::Index>& face) { return face.size() == 3 || face.size() == 6 ? 3 : 4; }

// Flat triangles of a face: linear faces as they are, quadratic ones split at
// their mid-edge nodes so curved bores stay round.
std::vector<std::array<fem::Index, 3>> triangles_of(const std::vector<fem::Index>& n) {
  switch (n.size()) {
    case 3: return {{n[0], n[1], n[2]}};
    case 6: return {{n[0], n[3], n[5]}, {n[3], n[1], n[4]}, {n[5], n[4], n[2]}, {n[3], n[4], n[5]}};
    case 4: return {{n[0], n[1], n[2]}, {n[0], n[2], n[3]}};
    case 8:
      return {{n[0], n[4], n[7]}, {n[4], n[1], n[5]}, {n[5], n[2], n[6]},
              {n[6], n[3], n[7]}, {n[4], n[5], n[6]}, {n[4], n[6], n[7]}};
    default: fail("boundary face with {} nodes", n.size());
  }
}

// The oblique view of the x-y plane (png_plots.hpp): X = x + k z cos a, Y = y + k z sin a,
// seen from +z along the projection direction.
struct ObliqueView {
  double k, a;                      // depth factor, angle (rad)
  Eigen::Vector3d towards_viewer;   // unit; a face is seen if its outward normal points this way
  ObliqueView(double depth, double angle_deg)
      : k(depth),
        a(angle_deg * std::numbers::pi / 180.0),
        towards_viewer(Eigen::Vector3d(-k * std::cos(a), -k * std::sin(a), 1.0).normalized()) {}
  Eigen::MatrixX2d project(const fem::NodeCoordinates& p) const {
    Eigen::MatrixX2d out(p.rows(), 2);
    out.col(0) = p.col(0) + k * std::cos(a) * p.col(2);
    out.col(1) = p.col(1) + k * std::sin(a) * p.col(2);
    return out;
  }
  std::string description() const {
    return k == 0 ? std::string("x-y plane seen from +z")
                  : fmt::format("oblique view of the x-y plane (z drawn at {:g}°, x{:g})", a * 180.0 / std::numbers::pi, k);
  }
};

// One flat triangle of the boundary surface as it is painted.
struct DrawnTriangle {
  std::array<Eigen::Vector2d, 3> corner;  // projected, mm
  double depth;                           // along towards_viewer: the larger, the nearer
  double value;                           // mean of the corner values, field units
  double shade;                           // 0.62 .. 1, lit from the upper left
  int layer = 0;                          // painted in layer order first, then far to near
};

// The triangles of `faces` that face the viewer, appended to `out`. deformed_mm:
// node positions as drawn (3-D), projected: the same through the view.
void add_visible_triangles(const std::vector<std::vector<fem::Index>>& faces, const fem::NodeCoordinates& deformed_mm,
                           const Eigen::MatrixX2d& projected, const Eigen::VectorXd& value, const ObliqueView& view,
                           std::vector<DrawnTriangle>& out, int layer = 0) {
  const Eigen::Vector3d light = Eigen::Vector3d(-0.2, 0.3, 1.0).normalized();
  for (const auto& face : faces)
    for (const auto& t : triangles_of(face)) {
      const Eigen::Vector3d p0 = deformed_mm.row(t[0]).transpose(), p1 = deformed_mm.row(t[1]).transpose(),
                            p2 = deformed_mm.row(t[2]).transpose();
      Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0);
      const double len = normal.norm();
      if (!(len > 0) || normal.dot(view.towards_viewer) <= 0) continue;
      normal /= len;
      out.push_back({{projected.row(t[0]).transpose(), projected.row(t[1]).transpose(), projected.row(t[2]).transpose()},
                     (p0 + p1 + p2).dot(view.towards_viewer) / 3.0,
                     (value(t[0]) + value(t[1]) + value(t[2])) / 3.0,
                     0.62 + 0.38 * std::max(0.0, normal.dot(light)), layer});
    }
}

// Paints the triangles layer by layer, each far to near (painter's algorithm), coloured by value / colour_max.
void paint_triangles(cairo_t* cr, const Axes& ax, std::vector<DrawnTriangle>& tris, double colour_max) {
  std::sort(tris.begin(), tris.end(), [](const DrawnTriangle& x, const DrawnTriangle& y) {
    return x.layer != y.layer ? x.layer < y.layer : x.depth < y.depth;
  });
  cairo_save(cr);
  clip_to(cr, ax);
  cairo_set_line_width(cr, 0.7);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_BEVEL);
  for (const DrawnTriangle& t : tris) {
    const Rgb c = turbo(t.value / colour_max);
    cairo_set_source_rgb(cr, c.r * t.shade, c.g * t.shade, c.b * t.shade);
    cairo_move_to(cr, ax.X(t.corner[0].x()), ax.Y(t.corner[0].y()));
    cairo_line_to(cr, ax.X(t.corner[1].x()), ax.Y(t.corner[1].y()));
    cairo_line_to(cr, ax.X(t.corner[2].x()), ax.Y(t.corner[2].y()));
    cairo_close_path(cr);
    cairo_fill_preserve(cr);
    cairo_stroke(cr);  // the same colour: hides anti-aliasing seams between triangles
  }
  cairo_restore(cr);
}

// The outline of a closed boundary surface as seen: silhouette edges (between a
// face seen and one facing away), crease edges between two seen faces meeting
// at more than ~25°, and open edges of a seen face; each a node path, through
// the mid-edge node of a quadratic face.
std::vector<std::vector<fem::Index>> outline_edges(const std::vector<std::vector<fem::Index>>& faces,
                                                   const fem::NodeCoordinates& xyz, const ObliqueView& view) {
  struct Side {
    std::vector<fem::Index> path;
    Eigen::Vector3d normal;  // unit, outward
  };
  std::vector<std::pair<std::pair<fem::Index, fem::Index>, Side>> sides;
  for (const auto& face : faces) {
    const size_t nc = corners_of(face);
    Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // Newell's method over the corners
    for (size_t i = 0; i < nc; ++i)
      normal += Eigen::Vector3d(xyz.row(face[i]).transpose()).cross(Eigen::Vector3d(xyz.row(face[(i + 1) % nc]).transpose()));
    if (!(normal.norm() > 0)) continue;
    normal.normalize();
    for (size_t i = 0; i < nc; ++i) {
      const fem::Index p = face[i], q = face[(i + 1) % nc];
      std::vector<fem::Index> path = face.size() > nc ? std::vector<fem::Index>{p, face[nc + i], q} : std::vector<fem::Index>{p, q};
      sides.push_back({{std::min(p, q), std::max(p, q)}, {std::move(path), normal}});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::vector<fem::Index>> out;
  for (size_t i = 0; i < sides.size();) {
    size_t j = i + 1;
    while (j < sides.size() && sides[j].first == sides[i].first) ++j;
    const Side& s = sides[i].second;
    const bool seen = s.normal.dot(view.towards_viewer) > 0;
    if (j - i == 1) {
      if (seen) out.push_back(s.path);
    } else {
      const Side& o = sides[i + 1].second;
      const bool other_seen = o.normal.dot(view.towards_viewer) > 0;
      if (seen != other_seen || (seen && s.normal.dot(o.normal) < std::cos(25.0 * std::numbers::pi / 180.0)))
        out.push_back(s.path);
    }
    i = j;
  }
  return out;
}

void stroke_paths(cairo_t* cr, const Axes& ax, const std::vector<std::vector<fem::Index>>& paths,
                  const Eigen::MatrixX2d& projected) {
  for (const auto& path : paths)
    for (size_t i = 0; i < path.size(); ++i)
      (i ? cairo_line_to : cairo_move_to)(cr, ax.X(projected(path[i], 0)), ax.Y(projected(path[i], 1)));
  cairo_stroke(cr);
}

// A ring at (px, py) with a leader line and a boxed bold label. The label goes
// away from the nearer side edge (to the other side where only that one has room
// for it) and below the point near the top edge, unless dx, dy (+-1) are given.
void mark_point(cairo_t* cr, const Axes& ax, double px, double py, const std::string& label, double font, int dx = 0,
                int dy = 0) {
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

double round_down_125(double x) {
  const double mag = std::pow(10.0, std::floor(std::log10(x))), f = x / mag;
  return (f >= 5 ? 5.0 : f >= 2 ? 2.0 : 1.0) * mag;
}

// The 1/2/5 x 10^k value nearest to x on a log scale.
double nearest_125(double x) {
  const double mag = std::pow(10.0, std::floor(std::log10(x))), f = x / mag;
  return (f < std::sqrt(2.0) ? 1.0 : f < std::sqrt(10.0) ? 2.0 : f < std::sqrt(50.0) ? 5.0 : 10.0) * mag;
}

// Bodies of the elastic assembly ("assembly.<b>"): world-axes displacement, drawn by write_assembly_picture.
constexpr std::string_view kAssemblyBodyPrefix = layout::kAssemblyBodyPrefix;
bool is_assembly_body(const std::string& body) { return body.rfind(kAssemblyBodyPrefix, 0) == 0; }

// A shown value: 2 decimals, or 3 significant digits for small ones (e.g. a
// fatigue damage per cycle of 1e-5).
std::string value_text(double v) {
  return v == 0.0 || std::abs(v) >= 0.01 ? fmt::format("{:.2f}", v) : fmt::format("{:.3e}", v);
}

struct BodyView {
  std::string name;
  fem::Mesh mesh;
  Eigen::VectorXd value;        // N, field units
  fem::NodeCoordinates deformed_mm;
  Eigen::MatrixX2d projected;   // N x 2, mm
  double peak = 0;
  Eigen::Index peak_node = 0;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;  // projected bounding box, mm
};

}  // namespace

StressPictureInfo write_stress_picture(const ResultsFile& results, const std::filesystem::path& png,
                                       const StressPictureOptions& options) {
  std::vector<BodyEnvelope> envelopes = max_envelopes(results, options.field);
  std::erase_if(envelopes, [](const BodyEnvelope& e) { return is_assembly_body(e.body) || is_vibration_body(e.body); });
  require(!envelopes.empty(), "'{}': no body has a field '{}' to draw", results.path().string(), options.field);
  size_t peak_env = 0;
  for (size_t b = 1; b < envelopes.size(); ++b)
    if (envelopes[b].peak_value() > envelopes[peak_env].peak_value()) peak_env = b;
  const double critical_time = envelopes[peak_env].time_of(envelopes[peak_env].peak_node());
  const std::string units = envelopes[peak_env].units;

  // Field and displacement of every body at the critical time (static: the static fields).
  std::vector<BodyView> views;
  double extent_mm = 0, max_u_m = 0;
  std::vector<fem::NodeCoordinates> displacement;
  for (const BodyEnvelope& env : envelopes) {
    BodyView v;
    v.name = env.body;
    v.mesh = results.read_mesh(env.body);
    fem::NodeCoordinates u = fem::NodeCoordinates::Zero(v.mesh.node_count(), 3);
    if (env.source == BodyEnvelope::Source::Static) {
      v.value = results.read_static(env.body, options.field).values.col(0);
      const auto statics = results.static_fields(env.body);
      if (std::find(statics.begin(), statics.end(), options.displacement_field) != statics.end())
        u = results.read_static(env.body, options.displacement_field).values;
    } else {
      const std::vector<double>& t = env.times_s;
      size_t k = 0;
      if (!std::isnan(critical_time))
        for (size_t i = 1; i < t.size(); ++i)
          if (std::abs(t[i] - critical_time) < std::abs(t[k] - critical_time)) k = i;
      v.value = results.read_step(env.body, options.field, fem::Index(k)).values.col(0);
      const auto series = results.series_fields(env.body);
      if (std::find(series.begin(), series.end(), options.displacement_field) != series.end())
        u = results.read_step(env.body, options.displacement_field, fem::Index(k)).values;
    }
    require(u.rows() == v.mesh.node_count() && u.cols() == 3, "body '{}': '{}' is not an N x 3 field",
            env.body, options.displacement_field);
    const Eigen::RowVector3d lo = v.mesh.nodes.colwise().minCoeff(), hi = v.mesh.nodes.colwise().maxCoeff();
    extent_mm = std::max(extent_mm, (hi - lo).maxCoeff() * 1e3);
    max_u_m = std::max(max_u_m, u.rowwise().norm().maxCoeff());
    v.peak = v.value.maxCoeff(&v.peak_node);
    displacement.push_back(std::move(u));
    views.push_back(std::move(v));
  }
  double scale = options.deformation_scale;
  if (scale <= 0) scale = max_u_m > 0 ? round_down_125(0.05 * extent_mm / (max_u_m * 1e3)) : 0.0;

  const ObliqueView view(options.oblique_depth, options.oblique_angle_deg);
  double shown_max = 0;
  for (size_t b = 0; b < views.size(); ++b) {
    BodyView& v = views[b];
    v.deformed_mm = (v.mesh.nodes + scale * displacement[b]) * 1e3;
    v.projected = view.project(v.deformed_mm);
    v.x0 = v.projected.col(0).minCoeff(), v.x1 = v.projected.col(0).maxCoeff();
    v.y0 = v.projected.col(1).minCoeff(), v.y1 = v.projected.col(1).maxCoeff();
    const double pad = 0.06 * std::max(v.x1 - v.x0, v.y1 - v.y0);
    v.x0 -= pad, v.x1 += pad, v.y0 -= pad, v.y1 += pad;
    shown_max = std::max(shown_max, v.peak);
  }
  const double colour_max = shown_max > 0 ? shown_max : 1.0;

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  DisplayUnit du = display_unit(units);
  if (du.label == layout::kDimensionless) du.label = "";  // a ratio: no unit after the numbers
  const std::string name = case_name(results, options);
  const std::string when = !options.caption.empty()     ? options.caption
                           : std::isnan(critical_time) ? std::string("static load case")
                                                       : fmt::format("t = {:.3f} s (time of the peak)", critical_time);
  const std::string field_name = options.field == "von_mises" ? std::string("von Mises stress") : options.field;
  title(cr, canvas,
        fmt::format("{}: {}{} {}{}", name, field_name, std::isnan(critical_time) || !options.caption.empty() ? "," : " at",
                    when, max_u_m > 0 ? fmt::format(", deformation scaled x{:g}", scale) : std::string(", undeformed")),
        fmt::format("{}; each body in its own frame; peak {} {} on {}, node {}", view.description(),
                    value_text(shown_max * du.factor), du.label, views[peak_env].name, views[peak_env].peak_node));

  // Layout: panels side by side or stacked, whichever draws larger; one mm scale for all.
  const double font = 13, top = 80, bottom_margin = 60, left_margin = 80, bar_width = 150, gap = 40;
  const double area_w = canvas.width() - left_margin - bar_width - 20, area_h = canvas.height() - top - bottom_margin;
  const double n = double(views.size()), panel_title = 24;
  double sum_w = 0, sum_h = 0, max_w = 0, max_h = 0;
  for (const auto& v : views) {
    sum_w += v.x1 - v.x0, sum_h += v.y1 - v.y0;
    max_w = std::max(max_w, v.x1 - v.x0), max_h = std::max(max_h, v.y1 - v.y0);
  }
  const double row_scale = std::min((area_w - (n - 1) * (gap + left_margin)) / sum_w, (area_h - panel_title) / max_h);
  const double column_scale =
      std::min(area_w / max_w, (area_h - n * panel_title - (n - 1) * (gap + bottom_margin)) / sum_h);
  const bool row = row_scale >= column_scale;
  const double px_per_mm = std::max(row ? row_scale : column_scale, 1e-6);

  // Centre the panels in the free area.
  double cursor_x = left_margin, cursor_y = top;
  if (row) cursor_x += std::max(0.0, (area_w - (n - 1) * (gap + left_margin) - sum_w * px_per_mm) / 2);
  else cursor_y += std::max(0.0, (area_h - n * panel_title - (n - 1) * (gap + bottom_margin) - sum_h * px_per_mm) / 2);
  for (size_t b = 0; b < views.size(); ++b) {
    const BodyView& v = views[b];
    const double w = (v.x1 - v.x0) * px_per_mm, h = (v.y1 - v.y0) * px_per_mm;
    Axes ax{cursor_x, cursor_y + panel_title, w, h, v.x0, v.x1, v.y0, v.y1};
    if (row) ax.top += (area_h - panel_title - h) / 2;
    else ax.left += (area_w - w) / 2;
    cairo_set_source_rgb(cr, 0, 0, 0);
    text(cr, ax.left, ax.top - 8,
         fmt::format("{}: max {} {}", v.name, value_text(v.peak * du.factor), du.label), font + 1,
         0.0, 1.0, true);
    draw_axes(cr, ax, "x [mm]", "y [mm]", font - 1, true, std::max(3, int(w / 70)), std::max(3, int(h / 60)));

    std::vector<DrawnTriangle> tris;
    add_visible_triangles(boundary_faces(v.mesh), v.deformed_mm, v.projected, v.value, view, tris);
    paint_triangles(cr, ax, tris, colour_max);
    if (b == peak_env)  // the peak on top of everything
      mark_point(cr, ax, ax.X(v.projected(v.peak_node, 0)), ax.Y(v.projected(v.peak_node, 1)), "peak", font);
    if (row) cursor_x += w + gap + left_margin;
    else cursor_y += h + panel_title + gap + bottom_margin;
  }

  draw_colour_bar(cr, canvas.width() - bar_width + 20, top + 40, 26, std::min(area_h - 60, 520.0), colour_max * du.factor,
                  options.field == "von_mises" ? std::string("von Mises") : options.field, du.label, font);
  canvas.save(png);
  return {critical_time, scale, shown_max, views[peak_env].name, views[peak_env].peak_node};
}

namespace {

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
Axes draw_curves(cairo_t* cr, const Axes& frame, const std::vector<Curve>& curves, const std::string& ylabel,
                 const std::string& xlabel, const std::string& panel_title, double legend_x,
                 const CurveRange& range = {}) {
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
  title(cr, canvas, fmt::format("{}: joint forces, chain tension and drive torque over the motion", case_name(results, options)),
        fmt::format("mechanism histories, 0 .. {:.2f} s; |R|: magnitude of the force a joint transmits", t_end));
  const double left = 100, legend_w = 250, top = 100, bottom = 70, gap = 90;
  const double width = canvas.width() - left - legend_w - 30;
  const int panels = int(!forces.empty()) + int(!torques.empty());
  const double total_h = canvas.height() - top - bottom - (panels - 1) * gap;
  const double force_h = panels == 2 ? total_h * 0.6 : total_h;
  double y = top;
  if (!forces.empty()) {
    draw_curves(cr, Axes{left, y, width, force_h, 0, 1, 0, 1}, forces, "force [N]", "time [s]",
                "Joint reaction magnitudes and chain tension", left + width + 25);
    y += force_h + gap;
  }
  if (!torques.empty())
    draw_curves(cr, Axes{left, y, width, total_h - (panels == 2 ? force_h : 0), 0, 1, 0, 1}, torques,
                "torque [N·m]", "time [s]", "Drive torque", left + width + 25);
  canvas.save(png);
}

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

// ---- the elastic assembly -------------------------------------------------

namespace {

// Names the pipeline's assembly stage writes (docs/results.md, "The elastic assembly").
constexpr const char* kPointPrefix = layout::kAssemblyPointPrefix;
constexpr const char* kMaxDisplacement = layout::kAssemblyMaxDisplacement;
std::string point_history(const std::string& point, const std::string& what) { return kPointPrefix + point + "." + what; }

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? std::string("none") : s;
}

// A length in mm with three significant digits (at least two decimals): 1.00, 0.0300, 12.30.
std::string mm_text(double metres) {
  const double mm = metres * 1e3;
  const int decimals = mm > 0 ? std::clamp(2 - int(std::floor(std::log10(mm))), 2, 6) : 2;
  return fmt::format("{:.{}f} mm", mm, decimals);
}

size_t nearest_index(const std::vector<double>& times, double t) {
  size_t k = 0;
  for (size_t i = 1; i < times.size(); ++i)
    if (std::abs(times[i] - t) < std::abs(times[k] - t)) k = i;
  return k;
}

// The index of the largest value (first on a tie).
size_t argmax(const Eigen::VectorXd& v) {
  Eigen::Index i = 0;
  v.maxCoeff(&i);
  return size_t(i);
}

// |u| of a tracked point over the mechanism times: its magnitude history, else the norm of its displacement.
std::optional<TimeHistory> point_magnitude(const ResultsFile& results, const std::string& point) {
  const auto histories = results.histories();
  if (has(histories, point_history(point, "displacement_magnitude")))
    return mechanism_history(results, point_history(point, "displacement_magnitude"));
  if (!has(histories, point_history(point, "displacement"))) return std::nullopt;
  TimeHistory h = mechanism_history(results, point_history(point, "displacement"));
  h.values = FieldMatrix(h.magnitude());
  return h;
}

// One assembly body at the step drawn: rigid position and elastic displacement in world axes.
struct AssemblyBody {
  std::string name;
  fem::Mesh mesh;
  std::vector<std::vector<fem::Index>> faces;
  fem::NodeCoordinates position_m, displacement_m;
  Eigen::VectorXd magnitude_m;
};

// The step to draw and why.
struct Pose {
  fem::Index step = -1;  // -1: static
  double time_s = kNaN;
  std::string chosen_by;
};

Pose choose_pose(const ResultsFile& results, const AssemblyContents& contents, const AssemblyPictureOptions& o) {
  const std::string file = results.path().string();
  if (o.pose == AssemblyPictureOptions::Pose::Static) {
    require(contents.has_static,
            "'{}' has no static pose study of the elastic assembly (static_position, static_displacement, "
            "static_displacement_magnitude on every body {})",
            file, joined(contents.bodies));
    return {-1, kNaN, "static pose study"};
  }
  const std::vector<double> times = results.series_times(contents.bodies.front());
  require(!times.empty(), "'{}': assembly body '{}' has no time series", file, contents.bodies.front());
  if (o.pose == AssemblyPictureOptions::Pose::Step) {
    require(o.step >= 0 && size_t(o.step) < times.size(), "'{}': step {} is outside the {} output times (0 .. {})", file,
            o.step, times.size(), times.size() - 1);
    return {o.step, times[size_t(o.step)], fmt::format("step {}", o.step)};
  }
  auto at_peak_of = [&](const TimeHistory& h, const std::string& why) {
    const size_t k = nearest_index(times, h.time_s[argmax(h.values.col(0))]);
    return Pose{fem::Index(k), times[k], why};
  };
  if (auto h = point_magnitude(results, o.point)) return at_peak_of(*h, "largest |u| of " + o.point);
  if (has(results.histories(), kMaxDisplacement))
    return at_peak_of(mechanism_history(results, kMaxDisplacement), "largest assembly.max_displacement");
  // No histories: the step of the largest displacement_magnitude over the bodies' series.
  Eigen::VectorXd largest = Eigen::VectorXd::Zero(fem::Index(times.size()));
  for (const auto& body : contents.bodies)
    for (size_t k = 0; k < times.size(); ++k)
      largest(fem::Index(k)) = std::max(
          largest(fem::Index(k)), results.read_step(body, "displacement_magnitude", fem::Index(k)).values.maxCoeff());
  const size_t k = argmax(largest);
  return {fem::Index(k), times[k], "largest |u| of the series"};
}

AssemblyBody read_assembly_body(const ResultsFile& results, const std::string& body, const Pose& pose) {
  AssemblyBody b;
  b.name = body;
  b.mesh = results.read_mesh(body);
  b.faces = boundary_faces(b.mesh);
  auto read = [&](const std::string& field, long columns) {
    const std::string name = pose.step < 0 ? "static_" + field : field;
    const FieldData d = pose.step < 0 ? results.read_static(body, name) : results.read_step(body, name, pose.step);
    require(d.values.rows() == b.mesh.node_count() && d.values.cols() == columns,
            "'{}': body '{}': field '{}' is {} x {}, expected {} x {} (nodes x components)", results.path().string(), body,
            name, d.values.rows(), d.values.cols(), b.mesh.node_count(), columns);
    return d.values;
  };
  b.position_m = read("position", 3);
  b.displacement_m = read("displacement", 3);
  b.magnitude_m = read("displacement_magnitude", 1).col(0);
  return b;
}

// Where the tracked point is drawn: its rigid position from point.<body>.<P> (x, y; z = 0
// unless a third column is there) and its elastic displacement, at the mechanism time nearest t.
struct TrackedPoint {
  Eigen::Vector3d rigid_m, displacement_m;
};

std::optional<TrackedPoint> tracked_point(const ResultsFile& results, const std::string& point, double t) {
  if (std::isnan(t)) return std::nullopt;
  const auto histories = results.histories();
  if (!has(histories, point_history(point, "displacement"))) return std::nullopt;
  const std::string suffix = "." + point;
  for (const auto& name : histories) {
    if (name.rfind("point.", 0) != 0 || name.size() <= suffix.size() ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const TimeHistory path = mechanism_history(results, name);
    if (path.units != "m" || path.values.cols() < 2 || path.time_s.empty()) continue;
    const TimeHistory u = mechanism_history(results, point_history(point, "displacement"));
    const fem::Index i = fem::Index(nearest_index(path.time_s, t)), j = fem::Index(nearest_index(u.time_s, t));
    TrackedPoint p;
    p.rigid_m << path.values(i, 0), path.values(i, 1), path.values.cols() > 2 ? path.values(i, 2) : 0.0;
    p.displacement_m = u.values.row(j).transpose().head<3>();
    return p;
  }
  return std::nullopt;
}

}  // namespace

AssemblyContents assembly_contents(const ResultsFile& results) {
  AssemblyContents c;
  for (const auto& body : results.bodies())
    if (is_assembly_body(body)) c.bodies.push_back(body);
  c.has_static = !c.bodies.empty();
  for (const auto& body : c.bodies) {
    const auto statics = results.static_fields(body);
    for (const char* field : {"static_position", "static_displacement", "static_displacement_magnitude"})
      c.has_static = c.has_static && has(statics, field);
  }
  const std::string prefix = kPointPrefix, suffix = ".displacement";
  for (const auto& name : results.histories())
    if (name.size() > prefix.size() + suffix.size() && name.rfind(prefix, 0) == 0 &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const std::string point = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
      if (point.find(".from.") == std::string::npos) c.points.push_back(point);
    }
  return c;
}

AssemblyPictureInfo write_assembly_picture(const ResultsFile& results, const std::filesystem::path& png,
                                           const AssemblyPictureOptions& options) {
  const AssemblyContents contents = assembly_contents(results);
  require(!contents.bodies.empty(), "'{}' has no elastic assembly (no body named assembly.<part>; bodies: {})",
          results.path().string(), joined(results.bodies()));
  const Pose pose = choose_pose(results, contents, options);
  std::vector<AssemblyBody> bodies;
  for (const auto& name : contents.bodies) bodies.push_back(read_assembly_body(results, name, pose));

  // The largest |u| (coloured and drawn) and the size of the undeformed drawing.
  const ObliqueView view(options.oblique_depth, options.oblique_angle_deg);
  AssemblyPictureInfo info{pose.time_s, pose.step, pose.chosen_by, 0.0, -1.0, "", -1};
  double max_u_m = 0;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const AssemblyBody& b : bodies) {
    Eigen::Index node = 0;
    const double peak = b.magnitude_m.maxCoeff(&node);
    if (peak > info.max_value) info.max_value = peak, info.max_body = b.name, info.max_node = node;
    max_u_m = std::max(max_u_m, b.displacement_m.rowwise().norm().maxCoeff());
    const Eigen::MatrixX2d p = view.project(b.position_m * 1e3);
    lo = lo.cwiseMin(p.colwise().minCoeff().transpose()), hi = hi.cwiseMax(p.colwise().maxCoeff().transpose());
  }
  const double extent_mm = (hi - lo).maxCoeff();
  info.deformation_scale = options.deformation_scale > 0 ? options.deformation_scale
                           : max_u_m > 0 ? std::max(1.0, nearest_125(0.08 * extent_mm / (max_u_m * 1e3)))
                                         : 1.0;
  const double scale = info.deformation_scale;

  // Projected rigid and deflected node positions; the panel's range covers both.
  std::vector<Eigen::MatrixX2d> rigid, deflected;
  std::vector<fem::NodeCoordinates> deflected_mm;
  for (const AssemblyBody& b : bodies) {
    rigid.push_back(view.project(b.position_m * 1e3));
    deflected_mm.push_back((b.position_m + scale * b.displacement_m) * 1e3);
    deflected.push_back(view.project(deflected_mm.back()));
    lo = lo.cwiseMin(deflected.back().colwise().minCoeff().transpose());
    hi = hi.cwiseMax(deflected.back().colwise().maxCoeff().transpose());
  }
  const std::optional<TrackedPoint> point = tracked_point(results, options.point, pose.time_s);
  Eigen::Vector2d point_rigid, point_deflected;
  if (point) {
    auto project = [&](const Eigen::Vector3d& p_m) {
      fem::NodeCoordinates row(1, 3);
      row.row(0) = p_m.transpose() * 1e3;
      return Eigen::Vector2d(view.project(row).row(0).transpose());
    };
    point_rigid = project(point->rigid_m);
    point_deflected = project(point->rigid_m + scale * point->displacement_m);
    lo = lo.cwiseMin(point_rigid).cwiseMin(point_deflected), hi = hi.cwiseMax(point_rigid).cwiseMax(point_deflected);
  }
  const double pad = 0.06 * std::max((hi - lo).maxCoeff(), 1e-3);
  lo.array() -= pad, hi.array() += pad;

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  const std::string when = pose.step < 0 ? std::string("static pose study")
                                         : fmt::format("t = {:.3f} s ({})", pose.time_s, pose.chosen_by);
  title(cr, canvas,
        fmt::format("{}: elastic deflection of the assembly, {}, deformation scaled x{:g}", case_name(results, options),
                    when, scale),
        fmt::format("{}, world axes; grey: rigid configuration; max |u| {} on {}, node {}", view.description(),
                    mm_text(info.max_value), info.max_body, info.max_node));

  // One panel, equal scales, centred in the area left of the colour bar.
  const double font = 13, top = 80, bottom_margin = 60, left_margin = 90, bar_width = 190;
  const double area_w = canvas.width() - left_margin - bar_width - 20, area_h = canvas.height() - top - bottom_margin;
  const double px_per_mm = std::max(std::min(area_w / (hi.x() - lo.x()), area_h / (hi.y() - lo.y())), 1e-6);
  const double w = (hi.x() - lo.x()) * px_per_mm, h = (hi.y() - lo.y()) * px_per_mm;
  const Axes ax{left_margin + (area_w - w) / 2, top + (area_h - h) / 2, w, h, lo.x(), hi.x(), lo.y(), hi.y()};
  draw_axes(cr, ax, "x [mm]", "y [mm]", font - 1, true, std::max(3, int(w / 80)), std::max(3, int(h / 60)));

  cairo_save(cr);
  clip_to(cr, ax);
  cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
  cairo_set_line_width(cr, 1.0);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (size_t i = 0; i < bodies.size(); ++i)
    stroke_paths(cr, ax, outline_edges(bodies[i].faces, bodies[i].position_m, view), rigid[i]);
  cairo_restore(cr);
  // Links overlap at their joints, where their bosses may even share the same space (the FE
  // model couples them there). One painter's order over both interleaves their triangles
  // into a speckle, so each body is a layer, painted whole, in the order of its mean z
  // (the planar mechanism's links are stacked along z; the higher one is in front).
  std::vector<size_t> order(bodies.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](size_t i, size_t j) {
    return deflected_mm[i].col(2).mean() < deflected_mm[j].col(2).mean();
  });
  std::vector<DrawnTriangle> tris;
  for (size_t layer = 0; layer < order.size(); ++layer) {
    const size_t i = order[layer];
    add_visible_triangles(bodies[i].faces, deflected_mm[i], deflected[i], bodies[i].magnitude_m, view, tris, int(layer));
  }
  const double colour_max = info.max_value > 0 ? info.max_value : 1e-3;  // no deflection at all: a 0 .. 1 mm bar
  paint_triangles(cr, ax, tris, colour_max);

  // The node of the largest |u|, and the tracked point (labels apart where the two are close).
  size_t max_body = 0;
  while (bodies[max_body].name != info.max_body) ++max_body;
  const double mx = ax.X(deflected[max_body](info.max_node, 0)), my = ax.Y(deflected[max_body](info.max_node, 1));
  int max_dy = 0;
  if (point) {
    const double rx = ax.X(point_rigid.x()), ry = ax.Y(point_rigid.y());
    const double px = ax.X(point_deflected.x()), py = ax.Y(point_deflected.y());
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.2);
    cairo_new_path(cr);
    cairo_move_to(cr, rx, ry);
    cairo_line_to(cr, px, py);
    cairo_stroke(cr);
    cairo_arc(cr, rx, ry, 5, 0, 2 * std::numbers::pi);
    cairo_stroke(cr);
    int dy = 0;  // close marks: one label above, the other below
    if (std::abs(px - mx) < 250 && std::abs(py - my) < 60) dy = py >= my ? 1 : -1, max_dy = -dy;
    mark_point(cr, ax, px, py, fmt::format("{}: |u| {}", options.point, mm_text(point->displacement_m.norm())), font, 0,
               dy);
  }
  mark_point(cr, ax, mx, my, "max |u| " + mm_text(info.max_value), font, 0, max_dy);

  const double bx = canvas.width() - bar_width + 20, by = top + 40, bh = std::min(area_h - 160, 480.0);
  draw_colour_bar(cr, bx, by, 26, bh, colour_max * 1e3, "|u|", "mm", font);
  // Legend of the lines and marks, under the colour bar.
  double ly = by + bh + 45;
  cairo_set_source_rgb(cr, 0.55, 0.55, 0.55);
  cairo_set_line_width(cr, 1.0);
  cairo_move_to(cr, bx - 10, ly);
  cairo_line_to(cr, bx + 16, ly);
  cairo_stroke(cr);
  cairo_set_source_rgb(cr, 0, 0, 0);
  text(cr, bx + 24, ly, "rigid configuration", font - 1, 0.0, 0.5);
  if (point) {
    ly += 24;
    cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
    cairo_set_line_width(cr, 1.2);
    cairo_new_path(cr);
    cairo_arc(cr, bx + 3, ly, 5, 0, 2 * std::numbers::pi);
    cairo_stroke(cr);
    text(cr, bx + 24, ly, options.point + " rigid", font - 1, 0.0, 0.5);
    ly += 24;
    cairo_set_line_width(cr, 2);
    cairo_new_path(cr);
    cairo_arc(cr, bx + 3, ly, 8, 0, 2 * std::numbers::pi);
    cairo_stroke(cr);
    text(cr, bx + 24, ly, options.point + " deflected", font - 1, 0.0, 0.5);
  }
  canvas.save(png);
  return info;
}

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

// ---- the vibration over the motion ----------------------------------------

namespace {

std::vector<double> as_vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

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

}  // namespace

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
