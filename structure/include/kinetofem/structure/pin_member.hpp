#pragma once
// PinMember — the pin of a revolute joint whose two bores sit at different z
// (parts in their own planes), as an elastic member of the assembly: a
// Timoshenko beam of solid circular section from one bore's reference point
// (end i) to the other's (end j), with the rotation about its own axis
// released (the revolute freedom: the pin carries no torque).
//
// Each end has 6 components (translation of its point, m; rotation, rad),
// in world axes, order (u_i, theta_i, u_j, theta_j). Stiffness (J. S. Przemieniecki,
// Theory of Matrix Structural Analysis, 1968, ch. 5) in the beam's axes
// (x' along the axis, L its length; Przemieniecki's beam element with shear
// deformation, torsion left out):
//     axial       EA/L [1 -1; -1 1]
//     bending     EI/((1+phi) L^3) [ 12   6L        -12   6L      ;
//     (v, th_z)                      6L  (4+phi)L^2  -6L  (2-phi)L^2;
//                                  -12  -6L         12  -6L       ;
//                                   6L  (2-phi)L^2  -6L  (4+phi)L^2 ]
//     (w, th_y)   the same with the signs of the 6L terms flipped
//     torsion     0 (released)
// with phi = 12 EI / (kappa G A L^2), A = pi d^2/4, I = pi d^4/64, and the
// shear coefficient of a solid circle kappa = 6(1+nu)/(7+6nu) (Cowper 1966).
// The section is round, so the beam's transverse axes are any pair normal
// to its axis.
//
// End loads (what the pin applies on each body) are -K u; the section
// stresses are those of a round bar: bending sigma_b = 32 M / (pi d^3) (the
// extreme fibre), shear tau = 16 V / (3 pi d^2) (the neutral axis, 4/3 V/A).
//
// SI units: m, rad, N, N m, Pa.
#include <string>

#include <Eigen/Core>

namespace kinetofem::structure {

using Matrix12d = Eigen::Matrix<double, 12, 12>;
using Vector12d = Eigen::Matrix<double, 12, 1>;

struct PinSection {
  double diameter_m = 0.0;
  double youngs_modulus_pa = 0.0;
  double poisson_ratio = 0.3;

  double area_m2() const;
  double second_moment_m4() const;
  double shear_modulus_pa() const;
  // Cowper's kappa = 6(1+nu)/(7+6nu) of a solid circle.
  double shear_coefficient() const;
  // Throws Error naming `who` unless d > 0, E > 0, -1 < nu < 0.5, all finite.
  void validate(const std::string& who) const;
};

// What one pin carries in one pose (world axes).
struct PinLoads {
  Eigen::Vector3d force_on_i_n = Eigen::Vector3d::Zero(), moment_on_i_nm = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_on_j_n = Eigen::Vector3d::Zero(), moment_on_j_nm = Eigen::Vector3d::Zero();
  double axial_force_n = 0.0;   // tension > 0
  double shear_force_n = 0.0;   // transverse, the same at both ends (no load along the pin)
  double bending_moment_i_nm = 0.0, bending_moment_j_nm = 0.0;  // transverse moment in the section at each end
  double bending_stress_pa = 0.0;  // 32 M / (pi d^3), the larger end
  double shear_stress_pa = 0.0;    // 16 V / (3 pi d^2)
  // Transverse displacement of each end relative to the tangent of the
  // other, the larger (the pin's own bending and shear, no rigid motion).
  double deflection_m = 0.0;
};

class PinMember {
 public:
  // Ends at `end_i_m` and `end_j_m` (world, apart: else Error naming `who`).
  PinMember(const Eigen::Vector3d& end_i_m, const Eigen::Vector3d& end_j_m, const PinSection& section,
            const std::string& who);

  // 12 x 12, world axes, order (u_i, theta_i, u_j, theta_j); symmetric,
  // positive semi-definite of rank 5 (6 rigid motions and the free twist).
  const Matrix12d& stiffness() const { return k_world_; }
  // The same in the beam's own axes (x' along the pin; the textbook matrix).
  static Matrix12d local_stiffness(double length_m, const PinSection& section);
  double length_m() const { return length_; }
  const Eigen::Vector3d& end_i() const { return end_i_; }
  const Eigen::Vector3d& end_j() const { return end_j_; }
  const Eigen::Vector3d& axis() const { return axis_; }  // unit, end i -> end j
  const PinSection& section() const { return section_; }

  // The loads and stresses for end motions u (order as stiffness()); either
  // end may be held (zero).
  PinLoads loads(const Vector12d& u) const;

 private:
  Eigen::Vector3d end_i_, end_j_, axis_;
  double length_ = 0.0;
  PinSection section_;
  Eigen::Matrix3d to_local_;  // rows: the beam's axes in world
  Matrix12d k_world_;
};

}  // namespace kinetofem::structure
