#pragma once
// Box mesh — the box [0,Lx] x [0,Ly] x [0,Lz] (m) cut into nx x ny x nz cells
// of HEX8, HEX20, TET4 (six per cell, conforming) or TET10 (mid-edge nodes
// shared between elements), Gmsh node ordering (mesh.hpp). A structured block
// (structured_block.hpp) with the identity-like mapping x = (Lx u, Ly v, Lz w).
//
// Named sets: face sets and node sets "x0", "x1", "y0", "y1", "z0", "z1" (the
// faces x = 0, x = Lx, y = 0, ...; outward-numbered faces), node set
// "boundary" (all boundary nodes).
//
// Distortion, both optional:
//   random_perturbation, mid_node_perturbation
//                        nodes moved at random (see StructuredBlock);
//                        boundary nodes slide within their faces, so the six
//                        faces stay plane;
//   smooth_map           applied to every node after the box is built (e.g. a
//                        sine warp); the caller keeps it orientation-preserving.
#include <array>
#include <cstdint>
#include <functional>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

struct BoxMeshOptions {
  Eigen::Vector3d length_m = Eigen::Vector3d::Ones();
  std::array<int, 3> divisions = {1, 1, 1};
  fem::ElementType type = fem::ElementType::Hex8;
  std::array<double, 3> grading_ratio = {1.0, 1.0, 1.0};
  double random_perturbation = 0.0;    // see StructuredBlock
  double mid_node_perturbation = 0.0;  // see StructuredBlock (curves quadratic edges)
  std::uint64_t seed = 1;
  std::function<Eigen::Vector3d(const Eigen::Vector3d& x)> smooth_map;  // optional
};

fem::Mesh box_mesh(const BoxMeshOptions& options);

// A smooth, orientation-preserving warp of the box that keeps its six faces
// plane and in place: x_i += amplitude * L_i * prod_j sin(pi x_j / L_j).
// |amplitude| < 0.1 keeps linear and quadratic elements valid.
std::function<Eigen::Vector3d(const Eigen::Vector3d&)> sine_warp(const Eigen::Vector3d& length_m,
                                                                 double amplitude);

// Node count of an nx x ny x nz box of `type` (for choosing sizes from DoF
// targets without building the mesh).
std::int64_t box_node_count(fem::ElementType type, const std::array<int, 3>& divisions);

}  // namespace kinetofem::verification
