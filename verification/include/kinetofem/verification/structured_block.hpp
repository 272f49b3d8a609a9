#pragma once
// StructuredBlock — a structured hexahedral block of elements: the image of
// the parameter cube (u, v, w) in [0,1]^3 under a mapping, cut into
// nu x nv x nw cells. Each cell becomes one HEX8 / HEX20 or six TET4 / TET10
// (the Kuhn split: the six tetrahedra around the cell diagonal from its
// (0,0,0) corner to its (1,1,1) corner; every cell is split the same way, so
// the face diagonals of neighbouring cells match and the mesh is conforming).
//
// Nodes sit on a lattice in parameter space with one point per cell corner
// (linear elements) or also one per cell-edge midpoint, face centre and cell
// centre (quadratic elements; face and cell centres are the midpoints of the
// tetrahedra's diagonal edges). Only lattice points used by an element become
// mesh nodes. Every node is the mapping's image of its lattice point, so
// mid-edge nodes lie on the exact mapped geometry (e.g. on an arc).
//
// Grading: along each parameter direction the cell sizes form a geometric
// series whose last / first size is grading_ratio[d]; the mid-edge lattice
// point of a cell is the mean of its two end parameters (a straight edge keeps
// its mid node at the midpoint).
//
// Distortion: with random_perturbation = f > 0, each cell corner moves by a
// uniform random amount in [-f, f] times the local cell size along each
// parameter direction in which it is not on the block's boundary, before the
// mapping (a pseudo-random sequence fixed by `seed`): interior nodes move
// freely, face nodes slide within their face, edge nodes along their edge,
// block corners stay. The mid-edge points of quadratic elements follow the
// mean shift of their edge's two ends (edges stay straight in parameter
// space) plus, with mid_node_perturbation = g > 0, an own random shift of up
// to g times half the cell size (curved edges). f <= 0.2 and g <= 0.1 keep
// every element valid.
//
// Named sets created (names from face_names, in the order u=0, u=1, v=0,
// v=1, w=0, w=1):
//   face_sets[name]   the boundary faces on that parameter face (QUAD4, QUAD8,
//                     TRI3 or TRI6), numbered so that the normal by the
//                     right-hand rule points out of the block (for a mapping
//                     with positive Jacobian);
//   node_sets[name]   every node on that parameter face (mid-edge nodes too);
//   node_sets["boundary"]  every node on the block's boundary.
// One element block of `type`. Units are those of the mapping (m).
#include <array>
#include <cstdint>
#include <functional>
#include <string>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

// Parameter point (u, v, w) in [0,1]^3 -> physical point (m). Must have a
// positive Jacobian determinant for the elements to be valid.
using BlockMapping = std::function<Eigen::Vector3d(const Eigen::Vector3d& uvw)>;

struct StructuredBlock {
  BlockMapping mapping;
  std::array<int, 3> divisions = {1, 1, 1};  // cells along u, v, w (>= 1)
  fem::ElementType type = fem::ElementType::Hex8;
  std::array<std::string, 6> face_names = {"u0", "u1", "v0", "v1", "w0", "w1"};
  std::array<double, 3> grading_ratio = {1.0, 1.0, 1.0};  // last / first cell size, > 0
  double random_perturbation = 0.0;    // corners: fraction of the cell size, 0 <= f < 0.5
  double mid_node_perturbation = 0.0;  // quadratic mid nodes: fraction of half a cell, 0 <= g < 0.5
  std::uint64_t seed = 1;
};

// Builds the mesh; throws kinetofem::Error on a missing mapping, divisions
// below 1, a non-positive grading ratio or a perturbation outside [0, 0.5).
fem::Mesh structured_block_mesh(const StructuredBlock& block);

}  // namespace kinetofem::verification
