#pragma once
// spatial::System — a checked, compiled spatial::Model: coordinates, the
// constraint equations with their Jacobians and acceleration right-hand side,
// the mass matrix and the applied forces. Solvers (kinematics.hpp,
// dynamics.hpp) work on it; it holds no solver state.
//
// Coordinates. Every moving body k has q_k = (r_k, p_k), 7 numbers: the world
// position of its centre of mass (bare body plus point masses) and the Euler
// parameters of its frame (rotation.hpp). Its velocity is v_k = (r_k', w_k),
// 6 numbers, with w_k the angular velocity in body axes; q' = L(q) v with
// L = blockdiag(I3, (1/2) G(p_k)^T). Why velocities with angular velocities
// rather than p': the mass matrix is then constant and block diagonal,
//     M = blockdiag(m_k I3, J_k)   (J_k centroidal, body axes, point masses included),
// positive definite, with no 4x4 singular G^T J G block and no norm row at
// velocity level (d(p.p)/dt = p^T G^T w = 0 identically). Local points are
// stored relative to the centre of mass, s' = point - c (body axes):
//     r_P = r + A(p) s',  r_P' = r' - A s'~ w,  r_P'' = r'' - A s'~ w' + A w~ w~ s'.
//
// Constraints. Joint and drive rows Phi(q, t) = 0 (m rows), and one norm row
// per moving body, p_k . p_k - 1 = 0, kept apart (norm_*). Two Jacobians:
//     Phi_q (m x 7nb)  with respect to q = (r, p), for assembly and GGL;
//     Pi    (m x 6nb)  with respect to v = (r', w): Phi' = Pi v - nu, Pi = Phi_q L.
// Acceleration equation Pi v' = gamma = -(Pi v)' |_(v' = 0) - Phi_tt.
// Every row is built from the basic constraints of Haug ch. 9 on world vectors:
// body vectors a = A a' (a' = h', f', g') and the point difference
// d = r_Pj - r_Pi, composed by dot products:
//     dot-1      a_i . a_j = 0
//     dot-2      a_i . d   = 0
//     spherical  d = 0                   (three rows: d along the world axes)
// and, for a relative rotation about h_i, the angle atan2(g_i . f_j, f_i . f_j).
// For a product u . w of two such vectors:
//     (u.w)_q = u^T w_q + w^T u_q,  Pi row = u^T w_v + w^T u_v,
//     quadratic term (u.w)'' - Pi v' = u_quad . w + 2 u' . w' + u . w_quad,
// with a_quad = A w~ w~ a', d_quad = A_j w_j~ w_j~ s_j' - A_i w_i~ w_i~ s_i';
// gamma = -(quadratic term) (+ law'' for a drive). Rows per joint type, in order:
//   spherical    d = 0                                           (3)
//   revolute     d = 0; f_i.h_j = 0, g_i.h_j = 0                 (5)
//   cylindrical  f_i.h_j = 0, g_i.h_j = 0; f_i.d = 0, g_i.d = 0  (4)
//   prismatic    cylindrical rows; angle(f_i -> f_j) - theta_ref = 0   (5)
//   universal    d = 0; h_i.h_j = 0                              (4)
//   fixed        d = 0; f_i.h_j = 0, g_i.h_j = 0; angle - theta_ref = 0   (6)
//   chain        b + r sigma (alpha - psi) - r acos(r / rho) - L = 0    (1)
//   drive        s(q) - s_0 - law(t) = 0, s the angle or h_i.d (1)
// Angle rows are wrapped to (-pi, pi], so multi-turn motion stays continuous.
//
// Chain (SPEC §1, the planar core's row written in the plane normal to h_i):
// the hinge P_i on body_i, the roller of radius r on body_j centred at P_j,
// e = r_Pi - r_Pj = -d and its coordinates in body_i's frame, x = f_i.e,
// y = g_i.e (its part along h_i does not count: the chain lies in the plane);
// rho = sqrt(x^2 + y^2) > r, b = sqrt(rho^2 - r^2) the free straight length,
// psi = atan2(y, x) the direction of the hinge seen from the centre and
// alpha = atan2(g_i.f_j, f_i.f_j) the roller's angle, both from f_i about h_i;
// sigma = +1 when the chain, followed from the hinge onto the roller, turns
// counter-clockwise about h_i. The tangent point is at the angle
// tau = psi + sigma acos(r / rho) and the wrapped angle is sigma (alpha - tau),
// so the row is free length + r * wrapped angle - L,
//     Phi = G(rho) - r sigma psi + r sigma alpha - L,   G = b - r acos(r / rho),
// taken modulo 2 pi r nearest to zero (multi-turn winding stays continuous).
// It is a function F(x, y) + r sigma alpha of three rows built as above, so
// its Jacobian and quadratic term follow from the chain rule with
//     G' = b / rho,  G'' = r^2 / (rho^2 b),  F_x = (b x + sigma r y) / rho^2,
//     F_y = (b y - sigma r x) / rho^2,
// F_xx = G'' x^2/rho^2 + G' y^2/rho^3 - 2 r sigma x y / rho^4 and likewise
// (system.cpp). With body_i the ground and h_i = z these are the planar row
// (F_x, F_y = g, the unit vector from the tangent point to the hinge). Its
// multiplier is the chain tension (N), positive when pulling: the load on the
// hinge, -F_e lambda, pulls it toward the tangent point.
//
// Equations of motion with multipliers lambda:
//     M v' + Pi^T lambda = Q(q, v, t) - h(v),   h_k = (0, w_k~ J_k w_k)  (gyroscopic),
// Q: gravity on the centre of mass, point forces (force world, moment
// s'~ A^T F in body axes), springs and dampers: N = k (L - L0) + c L' along
// u = (r_Pj - r_Pi) / L, the force N u on body_i at P_i and -N u on body_j at
// P_j, L' = u . (r_Pj' - r_Pi'); force drives: effort times the Pi row of
// their coordinate (the load a drive row's multiplier -effort would give). The constraint load on body k is -Pi(rows, k)^T lambda:
// a force (world) and a moment about the centre of mass in body axes.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/spatial/model.hpp"

namespace kinetofem::mech::spatial {

// Mass properties of a body with its point masses (body frame).
struct EffectiveBody {
  double mass_kg = 0.0;
  Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Zero();  // about com_body, body axes
  Eigen::Vector3d com_body = Eigen::Vector3d::Zero();
};

enum class BlockKind { Joint, Drive };

// One block of constraint rows: a joint or a motion drive, with its geometry
// compiled relative to the bodies' centres of mass.
struct ConstraintBlock {
  std::string name;
  BlockKind kind = BlockKind::Joint;
  JointType joint = JointType::Revolute;  // the joint's type (a drive: that of the joint it drives)
  DriveCoordinate coordinate = DriveCoordinate::Rotation;  // drives
  int first_row = 0, rows = 0;
  int body_i = -1, body_j = -1;           // indices into model().bodies
  Eigen::Vector3d s_i, s_j;               // joint points relative to the centre of mass, body axes
  Eigen::Vector3d h_i, f_i, g_i, h_j, f_j;  // unit vectors, body axes
  double reference = 0.0;                 // prismatic/fixed theta_ref, chain L (m), drive s_0
  double radius_m = 0.0, sigma = 1.0;     // chain: roller radius, +1 counter-clockwise wrap about h_i
  const MotionLaw* law = nullptr;         // motion drives; the shared_ptr in model().motion_drives owns it
  int source = -1;                        // index into joints or motion_drives
  std::vector<bool> length_row;
};

// A block's values at one state: residual, Jacobians over the two bodies'
// coordinates (jq: rows x 14, body i's (r, p) then body j's; pi: rows x 12,
// body i's (r', w) then body j's, also for a fixed body, whose columns do not
// enter the global matrices), nu = -Phi_t and gamma.
struct BlockValues {
  Eigen::VectorXd phi, nu, gamma;
  Eigen::MatrixXd jq, pi;
};

class System {
 public:
  explicit System(Model model);

  const Model& model() const { return model_; }
  int n_moving() const { return static_cast<int>(moving_.size()); }
  int n_positions() const { return 7 * n_moving(); }   // q
  int n_velocities() const { return 6 * n_moving(); }  // v
  int n_constraints() const { return n_rows_; }         // joint and drive rows (norm rows apart)
  int n_bodies() const { return static_cast<int>(model_.bodies.size()); }
  // Index of body b among the moving bodies (q at 7k, v at 6k), or -1 for a fixed body.
  int moving_index(int body) const { return moving_index_[body]; }
  int body_index(const std::string& name) const;
  const EffectiveBody& effective(int body) const { return effective_[body]; }
  const std::vector<ConstraintBlock>& blocks() const { return blocks_; }
  const ConstraintBlock& block(const std::string& name) const;
  double characteristic_length() const { return model_.characteristic_length_m; }

  // q from the bodies' poses (the assembly's initial guess) and v from their velocities.
  Eigen::VectorXd initial_positions() const;
  Eigen::VectorXd initial_velocities() const;

  // Body b at q (a fixed body: its constant pose): centre of mass (world),
  // Euler parameters, rotation matrix; at v: centre-of-mass velocity and angular
  // velocity in body axes (zero for a fixed body).
  Eigen::Vector3d com(int body, const Eigen::VectorXd& q) const;
  Eigen::Vector4d euler_parameters(int body, const Eigen::VectorXd& q) const;
  Eigen::Matrix3d rotation(int body, const Eigen::VectorXd& q) const;
  Eigen::Vector3d com_velocity(int body, const Eigen::VectorXd& v) const;
  Eigen::Vector3d angular_velocity_body(int body, const Eigen::VectorXd& v) const;
  // World position of a named point of body b (body frame; "origin" is the frame origin).
  Eigen::Vector3d point_world(int body, const std::string& point, const Eigen::VectorXd& q) const;
  Eigen::Vector3d named_point(int body, const std::string& point) const;

  BlockValues evaluate(const ConstraintBlock& block, const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                       double t) const;
  Eigen::VectorXd phi(const Eigen::VectorXd& q, double t) const;
  Eigen::MatrixXd jacobian_q(const Eigen::VectorXd& q, double t) const;   // Phi_q, m x 7nb
  Eigen::MatrixXd jacobian_v(const Eigen::VectorXd& q, double t) const;   // Pi, m x 6nb
  Eigen::VectorXd nu(const Eigen::VectorXd& q, double t) const;
  Eigen::VectorXd gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) const;
  // Norm rows p_k . p_k - 1 and their Jacobian (nb x 7nb).
  Eigen::VectorXd norm_phi(const Eigen::VectorXd& q) const;
  Eigen::MatrixXd norm_jacobian(const Eigen::VectorXd& q) const;
  // q' = L(q) v (7nb).
  Eigen::VectorXd position_rates(const Eigen::VectorXd& q, const Eigen::VectorXd& v) const;
  // Scatters a block's local columns into global ones (jq into 7nb columns, pi into 6nb).
  void scatter_q(const ConstraintBlock& block, const Eigen::MatrixXd& local, Eigen::Ref<Eigen::MatrixXd> rows) const;
  void scatter_v(const ConstraintBlock& block, const Eigen::MatrixXd& local, Eigen::Ref<Eigen::MatrixXd> rows) const;

  // Constraint residual as a length: length rows as they are, the others times
  // the characteristic length; the norm rows likewise; max norm.
  double position_drift_m(const Eigen::VectorXd& q, double t) const;
  double velocity_drift_m_per_s(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) const;

  // M = blockdiag(m I3, J), 6nb x 6nb, constant.
  Eigen::MatrixXd mass_matrix() const;
  // Effort of force drive d (model().force_drives) at a state: N m or N, on body_j.
  double force_drive_effort(int d, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) const;
  // Q - h: gravity, point forces, springs and dampers, force drives, minus the gyroscopic terms (6nb).
  Eigen::VectorXd forces(const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t) const;

  double kinetic_energy(const Eigen::VectorXd& v) const;
  double potential_energy(const Eigen::VectorXd& q) const;  // gravity and springs
  // Angular momentum of the moving bodies about a world point (world axes).
  Eigen::Vector3d angular_momentum(const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                   const Eigen::Vector3d& about_world) const;

 private:
  Eigen::Vector3d relative_point(int body, const std::string& point) const;

  Model model_;
  std::vector<int> moving_;        // model body index of each moving body
  std::vector<int> moving_index_;  // per model body
  std::vector<EffectiveBody> effective_;
  std::vector<ConstraintBlock> blocks_;
  // Force drives' coordinates, compiled as drive rows without a law (reference s_0);
  // not constraint rows (first_row = -1).
  std::vector<ConstraintBlock> force_blocks_;
  std::vector<Eigen::Vector4d> fixed_p_;  // per model body: the normalised initial Euler parameters
  int n_rows_ = 0;
};

}  // namespace kinetofem::mech::spatial
