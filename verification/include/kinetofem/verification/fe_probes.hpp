#pragma once
// Probes for verification tests: consistent nodal loads of a non-uniform
// traction field, surface integrals of a finite-element displacement field,
// node selection by position, and the observed order of convergence.
//
// Surface integrals use Gauss rules finer than the element library's (degree 4
// on triangles, 4 x 4 points on quadrilaterals, so a quadratic traction times a
// quadratic shape function is integrated exactly on flat faces) on the
// isoparametric face geometry: dA = |dx/dxi x dx/deta| dxi deta, normal
// n = (dx/dxi x dx/deta) / |...| (outward for outward-numbered face sets).
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::verification {

// Traction (force per area, Pa) at point x (m) on a face with outward unit normal n.
using TractionField =
    std::function<Eigen::Vector3d(const Eigen::Vector3d& x, const Eigen::Vector3d& n)>;

// Consistent nodal forces f_i = int N_i t dA over the faces of a face set,
// one entry per node touched (N).
std::vector<fem::NodalForce> consistent_face_forces(const fem::Mesh& mesh,
                                                    const std::string& face_set,
                                                    const TractionField& traction);

// int g(x, n, u_h(x)) dA over a face set, u_h interpolated from the nodal
// displacement by the face shape functions.
using SurfaceIntegrand = std::function<double(const Eigen::Vector3d& x, const Eigen::Vector3d& n,
                                              const Eigen::Vector3d& u)>;
double face_integral(const fem::Mesh& mesh, const std::string& face_set,
                     const fem::DisplacementField& displacement, const SurfaceIntegrand& g);

// Nodes whose position satisfies `predicate`, ascending.
std::vector<fem::Index> nodes_where(const fem::Mesh& mesh,
                                    const std::function<bool(const Eigen::Vector3d&)>& predicate);

// Observed order of convergence from a quantity on three meshes refined by
// `ratio` each time (Richardson): p = log(|q1 - q2| / |q2 - q3|) / log(ratio).
double observed_order(double coarse, double medium, double fine, double ratio = 2.0);

// One DisplacementSupport per node, prescribing u(x) on all three components.
std::vector<fem::DisplacementSupport> prescribe_field(
    const fem::Mesh& mesh, const std::vector<fem::Index>& nodes,
    const std::function<Eigen::Vector3d(const Eigen::Vector3d& x)>& u);

}  // namespace kinetofem::verification
