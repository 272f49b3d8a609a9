#pragma once
// Assembly of the linear-elastic stiffness and of the load vectors.
//
// K = sum_e int_Ve B^T D B dV (Gauss quadrature of the element's rule). The
// free-free block K_ff is assembled straight into compressed sparse storage
// (upper triangle, pattern built once from the connectivity), in parallel over
// elements (OpenMP). Prescribed DoFs are eliminated: the right-hand side of a
// load case is f_f - K_fp u_p.
//
// Elements whose Jacobian determinant is not positive at a Gauss point
// (inverted or degenerate) are rejected with the element's index.
//
// Each element takes its own material (ElementMaterials: D in the stiffness
// and internal forces, the density in the body loads); a single
// IsotropicMaterial converts to one for every element.
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/sparse.hpp"

namespace kinetofem::fem {

using DisplacementField = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;  // N x 3, m

struct AssembledStiffness {
  SymmetricUpperMatrix free_free;  // K_ff, N/m
  // K_fp u_p for the DoF map's prescribed values (n_free), N: subtract from f_f.
  Eigen::VectorXd prescribed_coupling_force;
};

// Throws Error naming the element (global index, block type) if its Jacobian
// is not positive at a Gauss point.
AssembledStiffness assemble_stiffness(const Mesh& mesh, const ElementMaterials& materials,
                                      const DofMap& dofs);

// External nodal force vectors of the load cases, one column per case over
// all DoFs (3 * N, N): nodal forces + consistent surface and body loads
// (gravity and the acceleration field times each element's density).
Eigen::MatrixXd assemble_external_forces(const Mesh& mesh, const ElementMaterials& materials,
                                         const std::vector<LoadCase>& load_cases);

// Internal force K u of a full displacement field, element by element (3 * N).
// Reactions at supports are (K u - f_ext) on the prescribed DoFs.
Eigen::VectorXd internal_forces(const Mesh& mesh, const ElementMaterials& materials,
                                const DisplacementField& displacement);

// K u restricted to the given nodes (3 per node, in their order), from the
// elements touching them only.
Eigen::VectorXd internal_forces_at(const Mesh& mesh, const ElementMaterials& materials,
                                   const DisplacementField& displacement,
                                   const std::vector<Index>& nodes);

// Volume of the mesh (m^3), by the elements' Gauss rules.
double mesh_volume(const Mesh& mesh);

// Area of a set of faces (m^2), by the faces' Gauss rules.
double surface_area(const Mesh& mesh, const std::vector<FaceBlock>& faces);

// Throws Error naming the first element whose Jacobian determinant is not
// positive at a Gauss point or at a node (inverted or degenerate element).
void check_element_jacobians(const Mesh& mesh);

}  // namespace kinetofem::fem
