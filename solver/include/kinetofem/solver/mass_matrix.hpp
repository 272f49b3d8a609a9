#pragma once
// Consistent mass matrix of a part's FE model.
//
//   M = sum_e int_Ve rho_e N^T N dV  (x) I_3      [kg]
//
// with rho_e the density of the element's own material (ElementMaterials),
// for every element type of the library (TET4, TET10, HEX8, HEX20), with the
// DoF order of the stiffness (DoF 3 * node + c) and restricted like it to the
// free-free block of a DofMap. The pattern is the stiffness's
// (assemble_stiffness on the same mesh and DofMap builds the identical
// upper-triangle CSC structure), so K - sigma M is a combination of the two
// value arrays and one symbolic factorization serves every shift.
//
// Quadrature (exact for N^T N with an affine / trilinear geometry):
//   TET4 degree 3 (5 points), TET10 degree 5 (14 points), HEX8 2x2x2,
//   HEX20 3x3x3. Curved TET10 edges: the degree-5 rule is not exact but
//   converges with the mesh like the stiffness.
//
// The rigid-body kinetic energy 1/2 v^T M v of a velocity field
// v(x) = v_0 + omega x x equals that of the mass properties
// (rigid_body.hpp) to round-off: the isoparametric elements interpolate
// v exactly and the rules integrate rho |v|^2 exactly.
//
// A part of zero density gives M = 0; it is assembled (no error here) and the
// eigen solver rejects it (generalized_eigen.hpp).
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/sparse.hpp"

namespace kinetofem::fem {

// M_ff (kg), upper triangle. Throws Error naming the element (global index,
// type) whose Jacobian determinant is not positive at a Gauss point, or if
// the DoF map does not fit the mesh.
SymmetricUpperMatrix assemble_mass(const Mesh& mesh, const ElementMaterials& materials,
                                   const DofMap& dofs);

// Nodal velocity (or displacement) field of a rigid motion v = v_0 + omega x x
// over all DoFs (3 N): m/s (or m).
Eigen::VectorXd rigid_body_field(const Mesh& mesh, const Eigen::Vector3d& translation,
                                 const Eigen::Vector3d& rotation);

}  // namespace kinetofem::fem
