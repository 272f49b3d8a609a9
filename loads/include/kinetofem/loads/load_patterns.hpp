#pragma once
// LoadPatterns — the fixed nodal force patterns that every load on a part is
// a combination of (unit-load superposition), whichever multibody model the
// loads come from (planar: LinkLoads; spatial: SpatialLinkLoads).
//
// Frame and units: the part's mesh frame (its body frame), m, N, N m.
//     f = P c,   P = [ B | G_1 | ... | G_k ]      (3 N x (12 + 6 k))
// B: the 12 basis fields of the affine body force b / rho = c + A x
// (fem::RigidBodyMotionLoads: c = g - a_O, A = -(skew(alpha) + skew(omega)^2),
// all in the body frame); G_j: unit force F_x, F_y, F_z and unit moment M_x,
// M_y, M_z at the centroid of the j-th distributing coupling, one per
// distinct face set. c: the body force's 12 coefficients, then per coupling
// the resultant (force, N; moment about its centroid, N m) of everything
// that enters through it.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::loads {

class LoadPatterns {
 public:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  using BodyForce = Eigen::Matrix<double, 12, 1>;

  explicit LoadPatterns(const fem::FeModel& model);

  // Index of the coupling on `face_set`, made on first use; throws naming the
  // face sets present when the mesh has no such set.
  int coupling_on(const std::string& face_set);
  int coupling_count() const { return int(couplings_.size()); }
  const fem::DistributingCoupling& coupling(int j) const { return *couplings_[std::size_t(j)]; }
  const std::vector<std::string>& face_sets() const { return face_sets_; }

  int count() const { return 12 + 6 * coupling_count(); }
  // "body_force.c_x" .. "body_force.A_zz", then "<face_set>.F_x" .. ".M_z".
  std::vector<std::string> names() const;
  // P, 3 N x count(), N per unit coefficient.
  Eigen::MatrixXd forces() const;
  // P c for c = (body_force, coupling resultants).
  Eigen::VectorXd nodal_forces(const BodyForce& body_force, const std::vector<Vector6d>& coupling) const;
  // c as one vector (count()).
  Eigen::VectorXd coefficients(const BodyForce& body_force, const std::vector<Vector6d>& coupling) const;
  // Resultant of P c: force, and moment about the body frame's origin. The
  // couplings' nodal forces are statically equivalent to their resultants
  // exactly, so it is taken from the resultants, not from nodal forces.
  Vector6d resultant(const BodyForce& body_force, const std::vector<Vector6d>& coupling) const;

  const fem::RigidBodyMotionLoads& body_force() const { return motion_loads_; }
  // The part's size (diagonal of its bounding box, at least 1 mm): the length
  // that turns moments into forces in the equilibrium checks.
  double length_scale_m() const { return length_scale_; }

 private:
  const fem::Mesh* mesh_;
  fem::RigidBodyMotionLoads motion_loads_;
  Eigen::Matrix<double, 6, 12> body_force_resultants_;  // force; moment about the origin
  std::vector<std::unique_ptr<fem::DistributingCoupling>> couplings_;
  std::vector<std::string> face_sets_;
  double length_scale_ = 1.0;
};

// A part's loads over the motion as unit-load superposition, whoever built
// them (the planar LinkLoads, link_loads.hpp; the spatial SpatialLinkLoads,
// spatial_link_loads.hpp), solved by analyse_link_over_motion
// (link_stress_history.hpp): nodal force patterns P (3 N x m, N per unit
// coefficient, body frame) and their coefficients at every output time.
struct PatternLoadHistory {
  std::string part;                         // for messages
  std::vector<std::string> names;           // one per pattern
  Eigen::MatrixXd patterns;                 // P, 3 N x m
  Eigen::MatrixXd coefficients;             // m x T
  std::vector<double> times;                // T output times, s (for messages)
  double worst_equilibrium_residual = 0.0;  // of the loads, as the builder checked them
};

}  // namespace kinetofem::loads
