#pragma once
// Element library — isoparametric shape functions and Gauss rules of the
// solid elements (TET4, TET10, HEX8, HEX20) and of their faces (TRI3, TRI6,
// QUAD4, QUAD8). Node numbering as in mesh.hpp (Gmsh convention).
//
// Gauss rules (exact for the element's stiffness on undistorted geometry):
//   TET4 1 point, TET10 4 points (degree 2), HEX8 2x2x2, HEX20 3x3x3 (full),
//   TRI3 1, TRI6 3, QUAD4 2x2, QUAD8 3x3.
#include <array>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

struct QuadraturePoint {
  Eigen::Vector3d xi;  // reference coordinates (2D rules leave xi[2] = 0)
  double weight;
};

// The element's Gauss rule.
const std::vector<QuadraturePoint>& quadrature(ElementType type);
const std::vector<QuadraturePoint>& quadrature(FaceType type);

// Shape functions N (n) and their reference derivatives dN/dxi (n x 3) at xi.
void shape_functions(ElementType type, const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                     Eigen::MatrixXd& dN_dxi);
// Face shape functions N (n) and derivatives dN/d(xi, eta) (n x 2).
void shape_functions(FaceType type, const Eigen::Vector3d& xi, Eigen::VectorXd& N,
                     Eigen::MatrixXd& dN_dxi);

// Reference coordinates of the element's nodes (n x 3).
Eigen::MatrixXd reference_nodes(ElementType type);

// Gauss rule for load integrals (N times a body-force field): degree 3 on
// tetrahedra (5 points, exact for a linear field on TET10), else the
// element's stiffness rule.
const std::vector<QuadraturePoint>& load_quadrature(ElementType type);

// Gauss rule exact for the mass integrand N^T N on undistorted elements:
// degree 3 (5 points) on TET4, degree 5 (14 points) on TET10, the stiffness
// rule on hexahedra (2x2x2 is degree 3, 3x3x3 degree 5 per direction).
const std::vector<QuadraturePoint>& mass_quadrature(ElementType type);

// Least-squares extrapolation from the Gauss points of quadrature(type) to
// the corner nodes: a linear (tetrahedra: 1, xi, eta, zeta) or trilinear
// (hexahedra: 1, xi, eta, zeta, xi eta, eta zeta, zeta xi, xi eta zeta)
// field in reference coordinates, evaluated at the corners. corners x gauss
// points; TET4 (one point): a column of ones.
Eigen::MatrixXd corner_extrapolation(ElementType type);

// Degree-5, 14-point positive rule on the tetrahedron: the stiffness rule of
// TET10 elements with curved edges (the 4-point rule is exact only for
// straight-sided ones and fails the patch test on curved ones).
const std::vector<QuadraturePoint>& curved_tet_quadrature();

// The two corner nodes of a mid-edge node (TET10: 4..9, HEX20: 8..19).
std::array<int, 2> edge_corners(ElementType type, int mid_node);

}  // namespace kinetofem::fem
