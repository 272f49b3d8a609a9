// The assembly picture (png_plots.hpp, 4.): the manipulator as one elastic structure in world axes.
#include "kinetofem/postproc/png_plots.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <cairo.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/postproc/results_file.hpp"
#include "kinetofem/postproc/time_history.hpp"
#include "png_canvas.hpp"
#include "png_common.hpp"
#include "png_surface.hpp"

namespace kinetofem::post {

using namespace drawing;

namespace {

// One assembly body at the step drawn: rigid position and elastic displacement in world axes.
struct AssemblyBody {
  std::string name;
  fem::Mesh mesh;
  std::vector<BoundaryFace> faces;
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
  const std::string prefix = layout::kAssemblyPointPrefix, suffix = ".displacement";
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

}  // namespace kinetofem::post
