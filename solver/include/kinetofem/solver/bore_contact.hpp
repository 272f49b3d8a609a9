#pragma once
// Frictionless, unilateral contact of a pin in a bore of a linear-elastic
// part, in the space of the bore's corner nodes (derivation: docs/contact.md).
//
// The bore is a face set of the part's mesh around an axis (point c, unit
// direction a; the part's frame, m). The pin pushes on it with a pressure
// p(x) >= 0 (Pa) along n(x), the unit radial direction from the axis
// (outwards, into the material). The pressure is interpolated linearly
// between the faces' corner nodes, p(x) = sum_c p_c L_c(x) (L_c: the
// corner functions of the linear face, also on quadratic faces: a positive
// basis, so p >= 0 at the corners is p >= 0 everywhere, and no corner of a
// quadratic face, whose consistent weight is zero, is asked to carry a
// force of its own). Its nodal forces are f_a = n_a sum_c M_ac p_c with
// M_ac = integral of N_a L_c over the bore (m^2).
// The pin is rigid and round; it may translate across the axis and tilt
// about the two axes normal to it, its motion q = (t_1, t_2, beta_1,
// beta_2) in the bore's own axes e_1, e_2 (normal to a; m and rad). The gap
// (m, > 0 open) at a node is clearance + n_a . u_a - E_a q, E_a = [n_a.e_1,
// n_a.e_2, (r_a x n_a).e_1, (r_a x n_a).e_2], r_a = x_a - c; the contact
// holds it in the weak sense of the pressure basis (mortar): the weighted
// gaps g_c = sum_a M_ac gap_a >= 0 (m^3), with p_c g_c = 0. The pressure
// carries the pin's resultant normal to the axis exactly, E^T p = (F.e_1,
// F.e_2, M.e_1, M.e_2) with E = M^T [E_a] (force on the part, N; moment about
// c, N m). Along the axis a frictionless round pin carries nothing (no
// force, no moment about a): the caller keeps those on the bore's
// distributing coupling.
//
// With the part's condensed compliance A = M^T N^T K^-1 N M (N: the nodes'
// normals) and the weighted gap b of the clearance and all the other loads,
// one pose is the strictly convex QP
//     min 1/2 p^T A p + b^T p,  p >= 0,  E^T p = r,
// whose KKT conditions are the contact conditions (g = A p + b - E q,
// p >= 0, g >= 0, p . g = 0; q the multipliers of the resultant).
// solve_contact solves it by a primal-dual active set method (a semismooth
// Newton method; a few steps from the last pose's contact set), with a
// primal-dual interior point method as the fallback when it cycles.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::fem {

class LinearStaticAnalysis;

struct ContactSolverOptions {
  // Complementarity, gap and resultant tolerance relative to the problem's
  // scales: a force (the resultant's, or what closes the gaps the other
  // loads close) and a gap (the largest free gap, or what that force opens).
  double tolerance = 1e-10;
  // The active set usually settles in a few steps from the last pose's
  // contact set; when it has not after these, it may be cycling (it is not
  // globally convergent) and the interior point takes over, its contact
  // set then polished by active-set steps.
  int max_active_set_steps = 8;
  int max_polish_steps = 25;
  int max_interior_point_steps = 200;
};

struct ContactSolution {
  Eigen::VectorXd pressure;    // p, per corner node, >= 0 (Pa for a bore)
  Eigen::VectorXd gap;         // g, per corner node (>= -tolerance: no penetration beyond it; m^3 for a bore)
  Eigen::VectorXd pin_motion;  // q: the multipliers of E^T p = r
  std::vector<char> in_contact;  // the final contact set (p_c > 0)
  int active_set_steps = 0;
  int interior_point_steps = 0;  // 0 unless the fallback ran
  bool polished = false;         // the fallback's contact set solved exactly (else its own solution)
  double worst_penetration = 0.0;  // max(0, -min g)
  double resultant_error = 0.0;    // |E^T p + C q - r| / max(|r|, the problem's force scale)
};

// Solves the QP of the header. `in_contact` (size m, or empty): the starting
// contact set (the last pose's); the solution's set is returned in the
// result. Throws Error (context to be added by the caller) when neither
// method converges, or when the resultant cannot be carried (E^T lambda = r
// has no solution lambda >= 0).
ContactSolution solve_contact(const Eigen::MatrixXd& compliance, const Eigen::VectorXd& free_gap,
                              const Eigen::MatrixXd& rigid_pin_map, const Eigen::VectorXd& resultant,
                              const std::vector<char>& in_contact, const ContactSolverOptions& options = {});
// The same with multipliers that meet a stiffness: E^T p + C q = r, C (k x
// k) symmetric positive semi-definite, i.e. the saddle point of
// 1/2 p^T A p + b^T p - q^T (E^T p - r) - 1/2 q^T C q over p >= 0 and q.
// The elastic assembly's pins (structure/assembly_contact.hpp): q the
// pins' motions in their bores, released from the structure, whose other
// members resist them by C when it is statically indeterminate.
ContactSolution solve_contact(const Eigen::MatrixXd& compliance, const Eigen::VectorXd& free_gap,
                              const Eigen::MatrixXd& rigid_pin_map, const Eigen::MatrixXd& motion_stiffness,
                              const Eigen::VectorXd& resultant, const std::vector<char>& in_contact,
                              const ContactSolverOptions& options = {});

// The contact surface of one bore: its corner nodes (the pressure's), its
// nodes (the forces'), and the maps of the header.
class BoreContactSurface {
 public:
  // Throws Error when the face set is missing or empty, or a node lies on
  // the axis (no radial direction).
  BoreContactSurface(const Mesh& mesh, const std::string& face_set, const Eigen::Vector3d& axis_point_m,
                     const Eigen::Vector3d& axis_direction);

  // The pressure's unknowns: the corner nodes of the bore's faces.
  Index size() const { return Index(corners_.size()); }
  const std::vector<Index>& corner_nodes() const { return corners_; }
  // Every node of the bore's faces (the forces act on them).
  const std::vector<Index>& nodes() const { return nodes_; }
  const std::string& face_set() const { return face_set_; }
  // n_a of every node, nodes x 3.
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& normals() const { return normals_; }
  // M, nodes x corners (m^2).
  const Eigen::MatrixXd& force_map() const { return force_map_; }
  // E, corners x 4 (t_1, t_2, beta_1, beta_2), m^2 and m^3.
  const Eigen::Matrix<double, Eigen::Dynamic, 4>& rigid_pin_map() const { return rigid_pin_; }
  // Each corner's share of the bore's area, integral of L_c (m^2, > 0,
  // summing to the area): a weighted gap over it is a mean gap in m.
  const Eigen::VectorXd& corner_area_m2() const { return area_; }
  // Angle of each corner about the axis from e_1 towards e_2 (rad, (-pi, pi]).
  const Eigen::VectorXd& angle_rad() const { return angle_; }
  const Eigen::Vector3d& axis_point() const { return centre_; }
  const Eigen::Vector3d& axis() const { return axis_; }
  const Eigen::Vector3d& e1() const { return e1_; }
  const Eigen::Vector3d& e2() const { return e2_; }
  double radius_m() const { return radius_; }  // mean distance of the nodes from the axis
  double length_m() const { return length_; }  // extent of the nodes along the axis

  // (F.e_1, F.e_2, M.e_1, M.e_2): what the contact carries of a resultant
  // (force; moment about the axis point).
  Eigen::Vector4d carried(const Eigen::Vector3d& force_n, const Eigen::Vector3d& moment_nm) const;
  // Adds the nodal forces n_a (M p)_a of each column's corner pressures
  // (corners x k, Pa) to `forces` (3 N x k, node-major).
  void add_forces(const Eigen::Ref<const Eigen::MatrixXd>& pressure_pa, Eigen::Ref<Eigen::MatrixXd> forces) const;
  // M^T (n_a . u_a) of displacement columns (3 N x k, node-major): corners x k, m^3.
  Eigen::MatrixXd weighted_normal_components(const Eigen::Ref<const Eigen::MatrixXd>& displacements) const;
  // The pressure at every node of the bore (nodes() order) from the corner
  // pressures: the corners' own, the mean of its edge's two corners at a
  // mid-edge node (the pressure is linear along the edge).
  Eigen::VectorXd nodal_pressure(const Eigen::Ref<const Eigen::VectorXd>& pressure_pa) const;
  // Force of each corner's unit pressure, sum_a M_ac n_a (corners x 3, N/Pa).
  const Eigen::Matrix<double, Eigen::Dynamic, 3>& pressure_resultants() const { return pressure_force_; }

 private:
  std::string face_set_;
  std::vector<Index> nodes_, corners_;
  Eigen::Matrix<double, Eigen::Dynamic, 3> normals_, pressure_force_;
  Eigen::MatrixXd force_map_;
  std::vector<std::array<Index, 2>> node_corners_;  // per node: its corner column(s) (twice the same at a corner)
  Eigen::Matrix<double, Eigen::Dynamic, 4> rigid_pin_;
  Eigen::VectorXd area_, angle_;
  Eigen::Vector3d centre_, axis_, e1_, e2_;
  double radius_ = 0.0, length_ = 0.0;
};

// The condensed operators of contact surfaces on one part's factorization,
// by m solves in blocks of 64 (m: the corners of all the surfaces, stacked
// in order): the compliance A = F^T K^-1 F (m x m, m^3/Pa, symmetrized) and
// the weighted gaps of the part's load patterns D = F^T K^-1 P (m x the
// columns of `pattern_forces`, 3 N x k, N; m^3 per unit coefficient), with
// F the surfaces' nodal forces of unit corner pressures. The surfaces'
// nodes must be free in the factorized model (the caller checks).
struct CondensedContact {
  Eigen::MatrixXd compliance;
  Eigen::MatrixXd pattern_gaps;
};
CondensedContact condense_contact(LinearStaticAnalysis& factorized,
                                  const std::vector<const BoreContactSurface*>& surfaces,
                                  const Eigen::MatrixXd& pattern_forces);

// What one bore's contact pressure means to a user.
struct BoreContactState {
  double peak_pressure_pa = 0.0;      // max p_c
  double peak_angle_rad = 0.0;        // angle of that corner about the axis (from e_1)
  double arc_rad = 0.0;               // angular extent of the corners in contact (0 .. 2 pi)
  Eigen::Vector3d force_n = Eigen::Vector3d::Zero();  // the pressure's resultant force
  int corners_in_contact = 0;
};
BoreContactState contact_state(const BoreContactSurface& bore, const Eigen::Ref<const Eigen::VectorXd>& pressure_pa);

}  // namespace kinetofem::fem
