#include "png_surface.hpp"

#include <algorithm>
#include <utility>

#include <Eigen/Geometry>

#include "kinetofem/core/error.hpp"

namespace kinetofem::post::drawing {

std::vector<BoundaryFace> boundary_faces(const fem::Mesh& mesh) {
  using Key = std::array<fem::Index, 4>;  // sorted corner nodes, -1 padded
  std::vector<BoundaryFace> faces;
  std::vector<std::pair<Key, size_t>> keys;
  for (const auto& block : mesh.blocks) {
    const fem::ElementFacts& facts = fem::element_facts(block.type);
    const fem::FaceType type = facts.face_type;
    const long corners = fem::face_facts(type).corners;
    for (fem::Index e = 0; e < block.size(); ++e) {
      const auto element = block.element(e);
      for (int f = 0; f < facts.face_count; ++f) {
        std::vector<fem::Index> nodes;
        for (int i : facts.face(f)) nodes.push_back(element[size_t(i)]);
        Key key = {-1, -1, -1, -1};
        std::copy_n(nodes.begin(), corners, key.begin());
        for (long a = 1; a < corners; ++a)  // insertion sort of 3 or 4 corners
          for (long b = a; b > 0 && key[size_t(b - 1)] > key[size_t(b)]; --b) std::swap(key[size_t(b - 1)], key[size_t(b)]);
        keys.emplace_back(key, faces.size());
        faces.push_back({type, std::move(nodes)});
      }
    }
  }
  std::sort(keys.begin(), keys.end());
  std::vector<BoundaryFace> out;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i + 1;
    while (j < keys.size() && keys[j].first == keys[i].first) ++j;
    if (j - i == 1) out.push_back(std::move(faces[keys[i].second]));
    i = j;
  }
  return out;
}

std::vector<std::array<fem::Index, 3>> triangles_of(const BoundaryFace& face) {
  const std::vector<fem::Index>& n = face.nodes;
  const fem::FaceFacts& facts = fem::face_facts(face.type);
  require(n.size() == size_t(facts.nodes), "boundary face {} with {} nodes", facts.name, n.size());
  switch (face.type) {
    case fem::FaceType::Tri3: return {{n[0], n[1], n[2]}};
    case fem::FaceType::Tri6: return {{n[0], n[3], n[5]}, {n[3], n[1], n[4]}, {n[5], n[4], n[2]}, {n[3], n[4], n[5]}};
    case fem::FaceType::Quad4: return {{n[0], n[1], n[2]}, {n[0], n[2], n[3]}};
    case fem::FaceType::Quad8:
      return {{n[0], n[4], n[7]}, {n[4], n[1], n[5]}, {n[5], n[2], n[6]},
              {n[6], n[3], n[7]}, {n[4], n[5], n[6]}, {n[4], n[6], n[7]}};
  }
  fail("face type {} is not a known face type", int(face.type));
}

// The triangles of `faces` that face the viewer, appended to `out`. deformed_mm:
// node positions as drawn (3-D), projected: the same through the view.
void add_visible_triangles(const std::vector<BoundaryFace>& faces, const fem::NodeCoordinates& deformed_mm,
                           const Eigen::MatrixX2d& projected, const Eigen::VectorXd& value, const ObliqueView& view,
                           std::vector<DrawnTriangle>& out, int layer) {
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
std::vector<std::vector<fem::Index>> outline_edges(const std::vector<BoundaryFace>& faces,
                                                   const fem::NodeCoordinates& xyz, const ObliqueView& view) {
  struct Side {
    std::vector<fem::Index> path;
    Eigen::Vector3d normal;  // unit, outward
  };
  std::vector<std::pair<std::pair<fem::Index, fem::Index>, Side>> sides;
  for (const auto& boundary_face : faces) {
    const std::vector<fem::Index>& face = boundary_face.nodes;
    const size_t nc = size_t(fem::face_facts(boundary_face.type).corners);
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

Eigen::MatrixX2d ObliqueView::project(const fem::NodeCoordinates& p) const {
  Eigen::MatrixX2d out(p.rows(), 2);
  out.col(0) = p.col(0) + k * std::cos(a) * p.col(2);
  out.col(1) = p.col(1) + k * std::sin(a) * p.col(2);
  return out;
}

std::string ObliqueView::description() const {
  return k == 0 ? std::string("x-y plane seen from +z")
                : fmt::format("oblique view of the x-y plane (z drawn at {:g}°, x{:g})", a * 180.0 / std::numbers::pi, k);
}

}  // namespace kinetofem::post::drawing
