#pragma once
// Mapped meshes of curved verification geometries (structured blocks,
// structured_block.hpp). HEX8 or HEX20 (TET4 / TET10 also work); the nodes of
// HEX20 on a circular edge, mid-edge nodes included, lie on the exact arc.
#include <cstdint>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

// Quarter of a thick-walled cylinder (tube): inner radius a, outer radius b,
// polar angle 0..90 deg in the x-y plane, axis z from 0 to length.
//   x = r cos(theta), y = r sin(theta), z;
//   radial_divisions cells from r = a to b, graded so that the outermost cell
//   is radial_grading times as thick as the one at the bore;
//   circumferential_divisions cells over 90 deg, axial_divisions along z.
// Face sets / node sets:
//   "bore"  r = a          "outer"  r = b
//   "y0"    theta = 0 (the plane y = 0, outward normal -y)
//   "x0"    theta = 90 deg (the plane x = 0, outward normal -x)
//   "z0", "z1"  the end faces z = 0 and z = length
//   node set "boundary": all boundary nodes.
struct QuarterAnnulusOptions {
  double inner_radius_m = 0.1;
  double outer_radius_m = 0.2;
  double length_m = 0.01;
  int radial_divisions = 4;
  int circumferential_divisions = 8;
  int axial_divisions = 1;
  double radial_grading = 1.0;  // outer / inner cell thickness
  fem::ElementType type = fem::ElementType::Hex20;
};
fem::Mesh quarter_annulus_mesh(const QuarterAnnulusOptions& options);

// Quarter of a rectangular plate [-W,W] x [-H,H] with a central circular hole
// of radius a, thickness t along z (0..t): the part x >= 0, y >= 0, made of
// two mapped blocks split along the line from the hole at angle
// theta_c = atan2(H, W) to the plate corner (W, H). In each block the nodes
// lie on rays from the hole (angle theta, uniform along the arc of each block)
// to the outer edge (x = W for theta <= theta_c, y = H above), graded so that
// the outermost cell is radial_grading times as long as the one at the hole.
// Face sets / node sets:
//   "hole"   r = a (the bore)
//   "x1"     the outer edge x = W        "y1"  the outer edge y = H
//   "outer"  x1 and y1 together
//   "y0"     the symmetry plane y = 0    "x0"  the symmetry plane x = 0
//   "z0", "z1"  the faces z = 0 and z = t
//   node set "boundary": all boundary nodes.
struct QuarterPlateWithHoleOptions {
  double hole_radius_m = 0.01;
  double half_width_m = 0.05;   // W, along x
  double half_height_m = 0.05;  // H, along y
  double thickness_m = 0.001;
  int radial_divisions = 8;
  int arc_divisions_per_block = 4;  // cells along the hole in each of the two blocks
  int thickness_divisions = 1;
  double radial_grading = 4.0;  // outer / hole-side cell length
  fem::ElementType type = fem::ElementType::Hex20;
};
fem::Mesh quarter_plate_with_hole_mesh(const QuarterPlateWithHoleOptions& options);

}  // namespace kinetofem::verification
