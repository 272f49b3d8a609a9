#pragma once
// Lever 1 (A0-A) of the lever-chain manipulator (SPEC §1): a flat steel plate
// joining two bored bosses (hubs) that carry the pins at A0 and A.
//
// Frame (metres): origin at the centre of bore A0; the lever axis along +Y
// (its design position in SPEC §1), so bore A is centred at (0, length_m, 0);
// pin axes along Z; the part is symmetric about z = 0 and about x = 0.
//
//   plate      |x| <= width/2,     0 <= y <= length,   |z| <= thickness/2
//   bosses     cylinders of diameter boss_diameter and length boss_length
//              (|z| <= boss_length/2) about the two pin axes
//   bores      diameter bore_diameter through both bosses
//
// The geometry is meshes/geometry/lever.geo (OpenCASCADE), compiled into the
// library (lever_geometry_text(), geometry_text.hpp); mesh_lever passes
// these dimensions to it as the ONELAB parameters "Lever/a", "Lever/w",
// "Lever/t", "Lever/d_bore", "Lever/D_boss", "Lever/L_boss". The default
// values and the design reasons for them are in meshes/geometry/README.md.
//
// Sets of the mesh (physical groups of lever.geo):
//   element set + node set "lever"          the whole part
//   face set + node set "bore_A0", "bore_A" the cylindrical bore surfaces
//   face set + node set "boss_ends_A0", "boss_ends_A"
//                                           the two flat annular ends of each boss
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

struct LeverDimensions {
  double length_m = 0.500;         // a = |A0A| between the bore centres (SPEC §1 example)
  double width_m = 0.080;          // plate width
  double thickness_m = 0.025;      // plate thickness
  double bore_diameter_m = 0.040;  // pin bore diameter (both pins)
  double boss_diameter_m = 0.090;  // boss outer diameter
  double boss_length_m = 0.050;    // boss length along the pin axis

  // Throws Error naming the dimension unless bore < width < boss diameter,
  // thickness <= boss length and length > boss diameter (the bosses must
  // not overlap), all positive.
  void validate() const;

  // Exact volume of the solid, m^3:
  //   V = w a t + 2 pi R^2 L - t S - 2 pi r^2 L,
  // R = D_boss/2, r = d_bore/2, L = boss length; S is the area of the disc of
  // radius R within the strip |x| <= c = w/2 (half of it lies in the plate at
  // each end, so t S is the plate volume counted twice):
  //   S = 2 (c sqrt(R^2 - c^2) + R^2 asin(c/R)).
  double volume_m3() const;
};

// Meshes the lever; throws Error for invalid dimensions or options, or if
// Gmsh fails.
fem::Mesh mesh_lever(const LeverDimensions& dimensions, const MeshOptions& options);

}  // namespace kinetofem::meshes
