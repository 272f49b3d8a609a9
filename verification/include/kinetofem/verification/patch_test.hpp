#pragma once
// Displacement patch test of the solid elements on distorted meshes.
//
// Reference (the patch test, Irons; e.g. Zienkiewicz, Taylor & Zhu, The
// Finite Element Method: Its Basis and Fundamentals, ch. 10): a linear field
// u = A x + b lies in the span of every isoparametric element's shape
// functions (sum N_i = 1, sum N_i x_i = x), so a conforming, consistent
// element reproduces it exactly: with u prescribed on the boundary the
// interior nodes take u(x) and every Gauss point carries the constant stress
// sigma = D eps(A). "Exactly" means to round-off: 1e-10 relative (the
// systems here have condition numbers ~1e4-1e6).
#include <Eigen/Core>

#include "kinetofem/solver/material.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

inline constexpr double kPatchTolerance = 1e-10;

// The box 1.0 x 0.8 x 0.6 m.
Eigen::Vector3d patch_box_length();
// Steel, E = 210 GPa, nu = 0.3.
fem::IsotropicMaterial patch_material();

// The box cut into 3 x 3 x 3 cells of `type` (box_mesh.hpp), corners moved
// at random by up to 20 % of a cell (seed 7); `curved` adds mid-node shifts
// (10 % of half a cell, curved edges) and a smooth sine warp (amplitude
// 0.05). The one-argument form curves every type but TET10, whose 4-point
// rule (degree 2) integrates int dN/dx dV exactly only on affine elements.
fem::Mesh distorted_box(fem::ElementType type, bool curved);
fem::Mesh distorted_box(fem::ElementType type);

// The field u = A x + b of the test, and its Voigt strain (xx, yy, zz, xy,
// yz, zx; engineering shear).
Eigen::Matrix3d patch_field_gradient();
Eigen::Vector3d patch_field_offset();
fem::Vector6d voigt_strain(const Eigen::Matrix3d& gradient);

// u = A x + b prescribed on the node set "boundary" of `mesh` (patch
// material), solved; the errors, each relative: max |u - u_exact| at the
// interior nodes over max |u_exact|, max |sigma - D eps(A)| at the Gauss
// points and at the recovered nodal stresses over |D eps(A)|. Checks the
// element Jacobians first (Error on an inverted element).
struct PatchErrors {
  double displacement = 0.0, gauss_stress = 0.0, nodal_stress = 0.0;
  int interior_nodes = 0;
};
PatchErrors displacement_patch_test(const fem::Mesh& mesh);

}  // namespace kinetofem::verification
