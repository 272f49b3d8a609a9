// The stress picture (png_plots.hpp, 1.): a scalar field on the deformed boundary of every link body.
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/hot_spots.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/vibration_results.hpp"
#include "png_canvas.hpp"
#include "png_common.hpp"
#include "png_surface.hpp"

namespace kinetofem::post {

using namespace drawing;

namespace {

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

}  // namespace kinetofem::post
