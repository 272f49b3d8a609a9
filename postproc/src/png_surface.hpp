#pragma once
// Boundary surfaces of a mesh as the stress and the assembly pictures
// (png_plots.hpp, 1. and 4.) draw them: the faces that belong to one element
// only, seen in an oblique view of the x-y plane, split into flat triangles,
// culled (faces pointing away from the viewer) and painted far to near
// (painter's algorithm), with an outline of silhouette and crease edges.
// Positions are in mm, in the frame the caller gives (body frame or world).
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <cairo.h>

#include "kinetofem/solver/element_traits.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "png_canvas.hpp"

namespace kinetofem::post::drawing {

// An element face on the boundary: its face type and nodes (mesh node
// indices) in the face type's local order (corners counter-clockwise seen from
// outside, then the mid-edge node of edge (i, i+1) at corners + i).
struct BoundaryFace {
  fem::FaceType type;
  std::vector<fem::Index> nodes;
};

// The element faces of `mesh` that belong to one element only.
std::vector<BoundaryFace> boundary_faces(const fem::Mesh& mesh);

// Flat triangles of a face: linear faces as they are, quadratic ones split at
// their mid-edge nodes so curved bores stay round. Every face type has its own
// split (a switch without default: a new face type is a -Wswitch warning here).
std::vector<std::array<fem::Index, 3>> triangles_of(const BoundaryFace& face);

// The oblique view of the x-y plane (png_plots.hpp): X = x + k z cos a, Y = y + k z sin a,
// seen from +z along the projection direction.
struct ObliqueView {
  double k, a;                      // depth factor, angle (rad)
  Eigen::Vector3d towards_viewer;   // unit; a face is seen if its outward normal points this way
  ObliqueView(double depth, double angle_deg)
      : k(depth),
        a(angle_deg * std::numbers::pi / 180.0),
        towards_viewer(Eigen::Vector3d(-k * std::cos(a), -k * std::sin(a), 1.0).normalized()) {}
  // N x 3 positions -> N x 2 projected, same units.
  Eigen::MatrixX2d project(const fem::NodeCoordinates& p) const;
  std::string description() const;  // for a picture's subtitle
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
void add_visible_triangles(const std::vector<BoundaryFace>& faces, const fem::NodeCoordinates& deformed_mm,
                           const Eigen::MatrixX2d& projected, const Eigen::VectorXd& value, const ObliqueView& view,
                           std::vector<DrawnTriangle>& out, int layer = 0);

// Paints the triangles layer by layer, each far to near (painter's algorithm), coloured by
// value / colour_max on the "turbo" map; sorts `tris`.
void paint_triangles(cairo_t* cr, const Axes& ax, std::vector<DrawnTriangle>& tris, double colour_max);

// The outline of a closed boundary surface as seen: silhouette edges (between a
// face seen and one facing away), crease edges between two seen faces meeting
// at more than ~25°, and open edges of a seen face; each a node path, through
// the mid-edge node of a quadratic face.
std::vector<std::vector<fem::Index>> outline_edges(const std::vector<BoundaryFace>& faces,
                                                   const fem::NodeCoordinates& xyz, const ObliqueView& view);

// Strokes node paths (outline_edges) through their projected positions.
void stroke_paths(cairo_t* cr, const Axes& ax, const std::vector<std::vector<fem::Index>>& paths,
                  const Eigen::MatrixX2d& projected);

}  // namespace kinetofem::post::drawing
