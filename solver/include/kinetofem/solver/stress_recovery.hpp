#pragma once
// Stress recovery from a displacement field.
//
// Gauss-point stresses sigma = D_e B u_e (D_e of the element's own material,
// ElementMaterials); nodal values by extrapolation from the
// Gauss points to the corner nodes (least-squares fit of a linear (tets) or
// trilinear (hexes) field in reference coordinates), mid-edge nodes taking the
// mean of their two corners, then the unweighted average over the elements
// sharing a node. Voigt order (xx, yy, zz, xy, yz, zx), Pa.
//
// At a node shared by elements of two materials (the seam of two solids of a
// welded part) the average mixes both sides, although the stress components
// along the seam jump across it; the Gauss-point stresses are each element's
// own.
#include <Eigen/Core>

#include "kinetofem/solver/assembly.hpp"

namespace kinetofem::fem {

using StressField = Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>;  // Pa
using Vector6d = Eigen::Matrix<double, 6, 1>;

struct GaussPointStress {
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points_m;  // one row per Gauss point
  StressField stress_pa;                                               // same rows
  std::vector<Index> first_point_of_element;  // size elements + 1
};

struct NodalStress {
  StressField stress_pa;                                                // N x 6
  Eigen::VectorXd von_mises_pa;                                         // N
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> principal_pa;  // N x 3, descending
};

GaussPointStress gauss_point_stress(const Mesh& mesh, const ElementMaterials& materials,
                                    const DisplacementField& displacement);
NodalStress recover_nodal_stress(const Mesh& mesh, const ElementMaterials& materials,
                                 const DisplacementField& displacement);

double von_mises(const Vector6d& stress);
// Principal stresses, sorted descending (sigma_1 >= sigma_2 >= sigma_3).
Eigen::Vector3d principal_stresses(const Vector6d& stress);
Eigen::VectorXd displacement_magnitude(const DisplacementField& displacement);

}  // namespace kinetofem::fem
