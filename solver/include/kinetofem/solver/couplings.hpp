#pragma once
// Load transfer onto a link's FE model: how a joint reaction, known as a
// resultant (force and moment at the joint centre), becomes nodal forces on
// the pin bore, and how a rigid-body motion becomes a body force.
//
// Two bore-load distributions are offered:
//
// * Distributing coupling (RBE3-like): nodal forces statically equivalent to
//   the resultant, weighted by each node's tributary area, leaving the bore
//   free to deform. With weights w_i, weighted centroid c, r_i = x_i - c,
//   W = sum w_i and J = sum w_i (|r_i|^2 I - r_i r_i^T):
//       f_i = w_i F / W + w_i (theta x r_i),   J theta = M + (x_ref - c) x F,
//   so that sum f_i = F and sum r_i x f_i = M + (x_ref - c) x F exactly.
//   Default: it is exact in resultant for any reaction (force and moment,
//   any direction) and needs no assumption about the contact.
//
// * Cosine bearing pressure: the pin pushes on the half of the bore facing
//   the force with a pressure p = p0 cos(phi), phi measured from the force's
//   direction in the plane normal to the pin axis, p0 = 2 F / (pi R L) for a
//   bore of radius R and length L; the traction is radial (normal to the
//   bore). On the discrete bore the cosine's amplitude vector is solved so
//   that the resultant equals the force exactly (its direction turns by the
//   mesh's asymmetry, a fraction of a degree). Closer to the real contact
//   stress near the bore, but carries only the force component normal to the
//   pin axis (no axial force, no moment).
//
// Both produce full-length nodal force vectors (3 N) in the mesh's frame.
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/element_materials.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

// A bore: its face set and axis (a point on the axis and the unit direction).
struct BoreGeometry {
  std::string face_set;
  Eigen::Vector3d axis_point_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis_direction = Eigen::Vector3d::UnitZ();
};

// Precomputed weights of a distributing coupling over a face set.
class DistributingCoupling {
 public:
  // Weights are the nodes' consistent tributary areas (integral of N_a over
  // the faces). Throws Error if the face set is missing or degenerate (J
  // singular, e.g. all nodes on one line).
  DistributingCoupling(const Mesh& mesh, const std::string& face_set);

  // Adds to `forces` (3 N) the nodal forces of resultant `force_n` and
  // `moment_nm`, the moment taken about `reference_point_m`.
  void add(const Eigen::Vector3d& force_n, const Eigen::Vector3d& moment_nm,
           const Eigen::Vector3d& reference_point_m, Eigen::Ref<Eigen::VectorXd> forces) const;

  const std::vector<Index>& nodes() const { return nodes_; }
  const Eigen::Vector3d& centroid() const { return centroid_; }

 private:
  std::vector<Index> nodes_;
  Eigen::VectorXd weight_;
  Eigen::Matrix<double, Eigen::Dynamic, 3> arm_;  // r_i = x_i - centroid
  Eigen::Vector3d centroid_;
  double total_weight_ = 0.0;
  Eigen::Matrix3d polar_inverse_;  // J^{-1}
};

// Cosine bearing pressure of a pin on a bore. Adds to `forces` (3 N) the
// nodal forces of a pin force `force_n`; its component along the bore axis is
// ignored (returned, so the caller can check it is negligible).
Eigen::Vector3d add_bearing_pressure(const Mesh& mesh, const BoreGeometry& bore,
                                     const Eigen::Vector3d& force_n,
                                     Eigen::Ref<Eigen::VectorXd> forces);

// Body force of a rigid body's motion in its own frame (the mesh frame):
//   b(x) = rho (g - a_O - alpha x x - omega x (omega x x))     [N/m^3]
// (rho the density of each element, ElementMaterials)
// for gravity g, acceleration a_O of the frame origin, angular velocity omega
// and angular acceleration alpha, all expressed in the body frame. b is
// affine in x, so its consistent nodal forces are a combination of 12 fixed
// basis vectors (rho e_k and rho x_j e_i): they are integrated once, and each
// output time costs a 12-column combination, not a new integration.
class RigidBodyMotionLoads {
 public:
  RigidBodyMotionLoads(const Mesh& mesh, const ElementMaterials& materials);

  // Nodal forces (3 N) of the motion state.
  Eigen::VectorXd forces(const Eigen::Vector3d& gravity_m_s2, const Eigen::Vector3d& origin_acceleration_m_s2,
                         const Eigen::Vector3d& angular_velocity_rad_s,
                         const Eigen::Vector3d& angular_acceleration_rad_s2) const;

  // The same as basis() * coefficients(...): the 12 coefficients of the
  // affine field b / rho = c + A x (c = g - a_O, A = -(skew(alpha) +
  // skew(omega)^2)), in the basis' column order. Linear in c and A, so a
  // history of motion states is a coefficient history on one fixed basis
  // (loads::LinkLoads' load patterns).
  static Eigen::Matrix<double, 12, 1> coefficients(const Eigen::Vector3d& gravity_m_s2,
                                                   const Eigen::Vector3d& origin_acceleration_m_s2,
                                                   const Eigen::Vector3d& angular_velocity_rad_s,
                                                   const Eigen::Vector3d& angular_acceleration_rad_s2);
  // 3 N x 12 consistent nodal forces of the basis fields (N per unit coefficient).
  const Eigen::MatrixXd& basis() const { return basis_; }

  double mass_kg() const { return mass_; }
  const Eigen::Vector3d& centre_of_mass_m() const { return centre_of_mass_; }

 private:
  Eigen::MatrixXd basis_;  // 3 N x 12: columns e_k (k = 0..2), then x_j e_i (3 + 3 i + j)
  double mass_ = 0.0;
  Eigen::Vector3d centre_of_mass_ = Eigen::Vector3d::Zero();
};

// Resultant force and moment (about `point`) of a nodal force vector (3 N).
void resultant(const Mesh& mesh, const Eigen::VectorXd& forces, const Eigen::Vector3d& point,
               Eigen::Vector3d& force_n, Eigen::Vector3d& moment_nm);

}  // namespace kinetofem::fem
