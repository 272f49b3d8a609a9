#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <set>
#include <string>

#include <Eigen/Geometry>
#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/hot_spots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/time_history.hpp"

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


// A rectangle of the picture (px) showing a data range; y grows upwards in data.
struct Axes {
  double left, top, width, height;  // px
  double x0, x1, y0, y1;            // data
  double X(double x) const { return left + (x - x0) / (x1 - x0) * width; }
  double Y(double y) const { return top + height - (y - y0) / (y1 - y0) * height; }
};

void clip_to(cairo_t* cr, const Axes& a) {
  cairo_rectangle(cr, a.left, a.top, a.width, a.height);
  cairo_clip(cr);
}

// Frame, grid, ticks, tick labels and axis labels of `a`.
void draw_axes(cairo_t* cr, const Axes& a, const std::string& xlabel, const std::string& ylabel,
               double font, bool grid, int target_ticks_x = 8, int target_ticks_y = 6) {
  const double sx = nice_step(a.x1 - a.x0, std::max(2, target_ticks_x));
  const double sy = nice_step(a.y1 - a.y0, std::max(2, target_ticks_y));
  cairo_save(cr);
  cairo_set_line_width(cr, 1.0);
  if (grid) {
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    for (double x : ticks_of(a.x0, a.x1, sx)) {
      cairo_move_to(cr, std::round(a.X(x)) + 0.5, a.top);
      cairo_line_to(cr, std::round(a.X(x)) + 0.5, a.top + a.height);
    }
    for (double y : ticks_of(a.y0, a.y1, sy)) {
      cairo_move_to(cr, a.left, std::round(a.Y(y)) + 0.5);
      cairo_line_to(cr, a.left + a.width, std::round(a.Y(y)) + 0.5);
    }
    cairo_stroke(cr);
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
  for (double y : ticks_of(a.y0, a.y1, sy)) {
    const double py = std::round(a.Y(y)) + 0.5;
    cairo_move_to(cr, a.left - 5, py);
    cairo_line_to(cr, a.left, py);
    const std::string label = tick_label(y, sy);
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

// ---- the stress picture --------------------------------------------------

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

double round_down_125(double x) {
  const double mag = std::pow(10.0, std::floor(std::log10(x))), f = x / mag;
  return (f >= 5 ? 5.0 : f >= 2 ? 2.0 : 1.0) * mag;
}

}  // namespace

StressPictureInfo write_stress_picture(const ResultsFile& results, const std::filesystem::path& png,
                                       const StressPictureOptions& options) {
  const std::vector<BodyEnvelope> envelopes = max_envelopes(results, options.field);
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

  const double k = options.oblique_depth, a = options.oblique_angle_deg * std::numbers::pi / 180.0;
  const Eigen::Vector3d view_dir = Eigen::Vector3d(-k * std::cos(a), -k * std::sin(a), 1.0).normalized();
  const Eigen::Vector3d light = Eigen::Vector3d(-0.2, 0.3, 1.0).normalized();
  double shown_max = 0;
  for (size_t b = 0; b < views.size(); ++b) {
    BodyView& v = views[b];
    v.deformed_mm = (v.mesh.nodes + scale * displacement[b]) * 1e3;
    v.projected.resize(v.deformed_mm.rows(), 2);
    v.projected.col(0) = v.deformed_mm.col(0) + k * std::cos(a) * v.deformed_mm.col(2);
    v.projected.col(1) = v.deformed_mm.col(1) + k * std::sin(a) * v.deformed_mm.col(2);
    v.x0 = v.projected.col(0).minCoeff(), v.x1 = v.projected.col(0).maxCoeff();
    v.y0 = v.projected.col(1).minCoeff(), v.y1 = v.projected.col(1).maxCoeff();
    const double pad = 0.06 * std::max(v.x1 - v.x0, v.y1 - v.y0);
    v.x0 -= pad, v.x1 += pad, v.y0 -= pad, v.y1 += pad;
    shown_max = std::max(shown_max, v.peak);
  }
  const double colour_max = shown_max > 0 ? shown_max : 1.0;

  Canvas canvas(options.width_px, options.height_px);
  cairo_t* cr = canvas.cr();
  const DisplayUnit du = display_unit(units);
  const std::string name = case_name(results, options);
  const std::string when = std::isnan(critical_time) ? std::string("static load case")
                                                     : fmt::format("t = {:.3f} s (time of the peak)", critical_time);
  const std::string field_name = options.field == "von_mises" ? std::string("von Mises stress") : options.field;
  title(cr, canvas,
        fmt::format("{}: {}{} {}, deformation scaled x{:g}", name, field_name,
                    std::isnan(critical_time) ? "," : " at", when, scale),
        fmt::format("oblique view of the x-y plane (z drawn at {:g}°, x{:g}); each body in its own frame; "
                    "peak {:.2f} {} on {}, node {}",
                    options.oblique_angle_deg, k, shown_max * du.factor, du.label, views[peak_env].name,
                    views[peak_env].peak_node));

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
         fmt::format("{}: max {:.2f} {}", v.name, v.peak * du.factor, du.label), font + 1,
         0.0, 1.0, true);
    draw_axes(cr, ax, "x [mm]", "y [mm]", font - 1, true, std::max(3, int(w / 70)), std::max(3, int(h / 60)));

    // Visible triangles, far to near.
    struct Tri {
      std::array<fem::Index, 3> n;
      double depth, value, shade;
    };
    std::vector<Tri> tris;
    for (const auto& face : boundary_faces(v.mesh))
      for (const auto& t : triangles_of(face)) {
        const Eigen::Vector3d p0 = v.deformed_mm.row(t[0]).transpose(), p1 = v.deformed_mm.row(t[1]).transpose(),
                              p2 = v.deformed_mm.row(t[2]).transpose();
        Eigen::Vector3d normal = (p1 - p0).cross(p2 - p0);
        const double len = normal.norm();
        if (!(len > 0) || normal.dot(view_dir) <= 0) continue;
        normal /= len;
        tris.push_back({t, (p0 + p1 + p2).dot(view_dir) / 3.0, (v.value(t[0]) + v.value(t[1]) + v.value(t[2])) / 3.0,
                        0.62 + 0.38 * std::max(0.0, normal.dot(light))});
      }
    std::sort(tris.begin(), tris.end(), [](const Tri& x, const Tri& y) { return x.depth < y.depth; });
    cairo_save(cr);
    clip_to(cr, ax);
    cairo_set_line_width(cr, 0.7);
    cairo_set_line_join(cr, CAIRO_LINE_JOIN_BEVEL);
    for (const Tri& t : tris) {
      const Rgb c = turbo(t.value / colour_max);
      cairo_set_source_rgb(cr, c.r * t.shade, c.g * t.shade, c.b * t.shade);
      cairo_move_to(cr, ax.X(v.projected(t.n[0], 0)), ax.Y(v.projected(t.n[0], 1)));
      cairo_line_to(cr, ax.X(v.projected(t.n[1], 0)), ax.Y(v.projected(t.n[1], 1)));
      cairo_line_to(cr, ax.X(v.projected(t.n[2], 0)), ax.Y(v.projected(t.n[2], 1)));
      cairo_close_path(cr);
      cairo_fill_preserve(cr);
      cairo_stroke(cr);  // the same colour: hides anti-aliasing seams between triangles
    }
    cairo_restore(cr);
    if (b == peak_env) {  // mark the peak node on top of everything
      const double px = ax.X(v.projected(v.peak_node, 0)), py = ax.Y(v.projected(v.peak_node, 1));
      cairo_set_line_width(cr, 4);
      cairo_set_source_rgb(cr, 1, 1, 1);
      cairo_arc(cr, px, py, 8, 0, 2 * std::numbers::pi);
      cairo_stroke(cr);
      cairo_set_line_width(cr, 2);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cairo_arc(cr, px, py, 8, 0, 2 * std::numbers::pi);
      cairo_stroke(cr);
      const double dx = px - ax.left > ax.left + ax.width - px ? -1 : 1, dy = py < ax.top + 40 ? 1 : -1;
      cairo_move_to(cr, px + dx * 6, py + dy * 6);
      cairo_line_to(cr, px + dx * 22, py + dy * 22);
      cairo_stroke(cr);
      const std::string label = "peak";
      const double lx = px + dx * 24, ly = py + dy * 24 + (dy > 0 ? 12 : 0), tw = text_width(cr, label, font);
      cairo_set_source_rgba(cr, 1, 1, 1, 0.85);
      cairo_rectangle(cr, dx > 0 ? lx - 2 : lx - tw - 2, ly - 13, tw + 4, 17);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      text(cr, lx, ly, label, font, dx > 0 ? 0.0 : 1.0, 1.0, true);
    }
    if (row) cursor_x += w + gap + left_margin;
    else cursor_y += h + panel_title + gap + bottom_margin;
  }

  // Colour bar.
  const double bx = canvas.width() - bar_width + 20, by = top + 40, bh = std::min(area_h - 60, 520.0), bw = 26;
  for (int i = 0; i < 256; ++i) {
    const Rgb c = turbo((i + 0.5) / 256.0);
    set_colour(cr, c);
    cairo_rectangle(cr, bx, by + bh - (i + 1) * bh / 256.0, bw, bh / 256.0 + 0.6);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, bx + 0.5, by + 0.5, bw, bh);
  cairo_stroke(cr);
  const double vmax = colour_max * du.factor, step = nice_step(vmax, 6);
  for (double t : ticks_of(0.0, vmax, step)) {
    const double py = std::round(by + bh - t / vmax * bh) + 0.5;
    cairo_move_to(cr, bx + bw, py);
    cairo_line_to(cr, bx + bw + 5, py);
    cairo_stroke(cr);
    if (vmax - t > 0.35 * step) text(cr, bx + bw + 8, py, tick_label(t, step), font - 1, 0.0, 0.5);
  }
  text(cr, bx + bw + 8, by + 0.5, fmt::format("{:.2f}", vmax), font - 1, 0.0, 0.5, true);
  text(cr, bx + bw / 2, by - 24, options.field == "von_mises" ? std::string("von Mises") : options.field, font, 0.5, 1.0,
       true);
  text(cr, bx + bw / 2, by - 8, "[" + du.label + "]", font, 0.5, 1.0);
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

// A line panel with its own y range (0 included), a legend at its right.
void draw_curves(cairo_t* cr, const Axes& frame, const std::vector<Curve>& curves, const std::string& ylabel,
                 const std::string& xlabel, const std::string& panel_title, double legend_x) {
  double lo = 0, hi = 0, x0 = curves.front().x.front(), x1 = curves.front().x.back();
  for (const auto& c : curves)
    for (size_t i = 0; i < c.y.size(); ++i) {
      lo = std::min(lo, c.y[i]), hi = std::max(hi, c.y[i]);
      x0 = std::min(x0, c.x[i]), x1 = std::max(x1, c.x[i]);
    }
  if (hi - lo <= 0) hi = lo + 1;
  const double step = nice_step(hi - lo, 6);
  lo = std::floor(lo / step + 1e-9) * step, hi = std::ceil(hi / step - 1e-9) * step;
  if (x1 <= x0) x1 = x0 + 1;
  Axes ax = frame;
  ax.x0 = x0, ax.x1 = x1, ax.y0 = lo, ax.y1 = hi;
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
