#pragma once
// MultibodySystem — a checked, compiled MultibodyModel: coordinates, the
// constraint equations with their Jacobian and acceleration right-hand side,
// the mass matrix and the applied forces. Solvers (kinematics.hpp,
// dynamics.hpp) work on it; it holds no solver state.
//
// Coordinates. Every moving body k has q_k = (x_k, y_k, theta_k): the world
// position of its centre of mass (bare body plus point masses) and the angle of
// its frame; q = (q_1, ..., q_nb), n = 3*nb. Local points are stored relative
// to that centre of mass, s = p_body - c_body, so that the mass matrix is
// diagonal, M = diag(m_k, m_k, J_k) with J_k the centroidal inertia including
// point masses (parallel axis). A point P of body k is at
//     r_P = r_k + A(theta_k) s_P,   A = [cos -sin; sin cos],
// with dr_P/dtheta_k = B s_P = rot90(A s_P) and the quadratic acceleration
// term -A s_P theta_k'^2. The ground has a fixed pose and no coordinates.
//
// Constraints Phi(q, t) = 0 (m rows); Jacobian Phi_q (m x n); velocity
// equation Phi_q q' = nu = -Phi_t; acceleration equation Phi_q q'' = gamma,
//     gamma = -(Phi_q q')_q q' - 2 Phi_qt q' - Phi_tt.
// Per joint (i, j the two bodies, s_i, s_j their points, d = r_Pj - r_Pi):
//   revolute   Phi = r_Pi - r_Pj                              (2 rows)
//              gamma = A_i s_i theta_i'^2 - A_j s_j theta_j'^2
//   prismatic  Phi = [ n_i . d ; theta_j - theta_i - theta_ref ]  n_i = A_i rot90(u_i)   (2 rows)
//              gamma_1 = n.d theta_i'^2 + 2 theta_i' u.d' + n.(A_j s_j theta_j'^2 - A_i s_i theta_i'^2)
//   fixed      revolute rows + theta_j - theta_i - theta_ref   (3 rows)
//   chain      body i carries the chain's hinge B0 (point_i), body j the roller of
//              radius r with centre A (point_j); e = r_B0 - r_A, d = |e|,
//              b = sqrt(d^2 - r^2) the free straight length, sigma = +1 for a
//              counter-clockwise wrap (-1 clockwise), tangent-point angle
//              tau = atan2(e) + sigma*acos(r/d), wrapped angle w = sigma*(theta_j - tau):
//                  Phi = b + r*w - L                           (1 row)
//              (taken modulo 2*pi*r nearest to zero, so that multi-turn winding stays
//              continuous). Phi_q: dPhi = g.(dr_B0 - dr_A) + sigma*r*dtheta_j with
//              g = (b e - sigma r rot90(e)) / d^2, the unit vector from the tangent
//              point to B0; gamma = g.(A_i s_i theta_i'^2 - A_j s_j theta_j'^2) - g'.e'.
//              The multiplier is the chain tension (N), positive when pulling.
//   drive      Phi = s(q) - s_0 - law(t)                      (1 row)
//              angle:        s = theta_j - theta_i,  gamma = law''
//              displacement: s = u_i.d,  u_i = A_i axis_i,
//                  gamma = u.d theta_i'^2 - 2 theta_i' n.d' + u.(A_j s_j theta_j'^2 - A_i s_i theta_i'^2) + law''
//              nu = law'(t).
//   transmission  two angles, s_in = theta_jin - theta_iin (input) and
//              s_out = theta_jout - theta_iout (output), up to four bodies:
//                  Phi = s_out - i s_in - c                    (1 row)
//              Phi_q: +1 at theta_jout, -1 at theta_iout, -i at theta_jin, +i at
//              theta_iin (summed where a body is on both sides, as the link that
//              carries a belt is); nu = 0, gamma = 0 (linear in the angles). The
//              load -Phi_q^T lambda is a moment -lambda on the output's body_j and
//              i lambda on the input's body_j, reversed on the body_i's: pure moments
//              that sum to zero and do no work on the constrained motion.
// Equations of motion with multipliers lambda:
//     M q'' + Phi_q^T lambda = Q(q, q', t),
// so the constraint load on body k is -Phi_q(rows, k)^T lambda: force (world
// frame) and moment about the body's centre of mass; reactions (results.hpp)
// move that moment to the joint point.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/multibody/model.hpp"

namespace kinetofem::mech {

// Mass properties of a body with its point masses (body frame).
struct EffectiveBody {
  double mass_kg = 0.0;
  double inertia_kgm2 = 0.0;  // about com_body
  Eigen::Vector2d com_body = Eigen::Vector2d::Zero();
};

enum class ConstraintKind { Joint, Drive, Transmission };

// One block of constraint rows: a joint, a motion drive or a transmission.
struct ConstraintBlock {
  std::string name;
  ConstraintKind kind = ConstraintKind::Joint;
  JointType joint = JointType::Revolute;        // kind == Joint
  int first_row = 0;
  int rows = 0;
  int body_i = -1, body_j = -1;                 // indices into model().bodies (transmission: the output's)
  int input_i = -1, input_j = -1;               // transmission: the input coordinate's bodies
  double ratio = 0.0;                           // transmission: i
  Eigen::Vector2d s_i, s_j;                     // points relative to the centre of mass, body frame
  Eigen::Vector2d axis_i{1.0, 0.0};             // unit, body_i frame
  CoordinateType coordinate = CoordinateType::Angle;  // drives
  double reference = 0.0;                       // fixed/prismatic angle, chain length, drive s_0, transmission c
  double radius_m = 0.0, sigma = 1.0;           // chain
  const MotionLaw* law = nullptr;               // drives; non-owning: the shared_ptr in model().motion_drives owns it
  int source = -1;                              // index into joints, motion_drives or transmissions
  std::vector<bool> length_row;                 // row measures a length (else an angle)
};

// Values of a constraint block at one state: residual, local Jacobian over the
// two bodies' coordinates (rows x 6: body i's (x, y, theta), then body j's),
// and the right-hand sides nu and gamma. A transmission also has the columns
// of its input coordinate's two bodies (input_i, input_j).
struct BlockValues {
  Eigen::VectorXd phi, nu, gamma;
  Eigen::MatrixXd jac;        // rows x 6
  Eigen::MatrixXd jac_input;  // rows x 6 for a transmission, else empty
};

class MultibodySystem {
 public:
  explicit MultibodySystem(MultibodyModel model);

  const MultibodyModel& model() const { return model_; }
  int n_coordinates() const { return 3 * static_cast<int>(moving_.size()); }
  int n_constraints() const { return n_rows_; }
  int n_bodies() const { return static_cast<int>(model_.bodies.size()); }
  // Offset of body b's coordinates in q, or -1 for a fixed body.
  int offset(int body) const { return offset_[body]; }
  int body_index(const std::string& name) const;
  const EffectiveBody& effective(int body) const { return effective_[body]; }
  const std::vector<ConstraintBlock>& blocks() const { return blocks_; }
  const ConstraintBlock& block(const std::string& name) const;
  double characteristic_length() const { return model_.characteristic_length_m; }

  // q from the bodies' poses (the assembly's initial guess) and q' from their velocities.
  Eigen::VectorXd initial_coordinates() const;
  Eigen::VectorXd initial_velocities() const;

  // Pose (centre of mass x, y, theta) of body b at q; a fixed body's constant pose.
  Eigen::Vector3d com_pose(int body, const Eigen::VectorXd& q) const;
  Eigen::Vector3d com_velocity(int body, const Eigen::VectorXd& qd) const;
  // Body frame origin pose (x, y, theta) <-> centre-of-mass pose.
  Eigen::Vector3d origin_pose(int body, const Eigen::VectorXd& q) const;
  // World position of a body point given in the body frame.
  Eigen::Vector2d point_world(int body, const Eigen::Vector2d& p_body, const Eigen::VectorXd& q) const;
  // Named point of a body in its frame ("origin" is (0, 0)).
  Eigen::Vector2d named_point(int body, const std::string& point) const;

  BlockValues evaluate(const ConstraintBlock& block, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                       double t) const;
  Eigen::VectorXd phi(const Eigen::VectorXd& q, double t) const;
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& q, double t) const;
  Eigen::VectorXd nu(const Eigen::VectorXd& q, double t) const;  // -Phi_t
  Eigen::VectorXd gamma(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const;
  // Constraint residual as a length: length rows as they are, angle rows times the
  // characteristic length; max norm.
  double position_drift_m(const Eigen::VectorXd& q, double t) const;
  double velocity_drift_m_per_s(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const;

  Eigen::VectorXd mass_diagonal() const;
  // Generalised applied forces Q (gravity, force drives, springs/dampers, point forces).
  Eigen::VectorXd applied_forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const;
  // Applied loads on every body (model order): (Fx, Fy, moment about its centre
  // of mass), world frame; also valid for the ground.
  std::vector<Eigen::Vector3d> applied_loads(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const;

  double kinetic_energy(const Eigen::VectorXd& qd) const;
  double potential_energy(const Eigen::VectorXd& q) const;  // gravity + springs
  // Power of the force drives, and of dampers and point forces (W).
  double force_drive_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const;
  double other_power(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const;

  // A relative coordinate's value, gradient over the two bodies (6 entries) and
  // quadratic acceleration term (s'' = grad . q_local'' + quad).
  struct CoordinateValues {
    double value = 0.0, rate = 0.0, quadratic = 0.0;
    Eigen::Matrix<double, 1, 6> grad;
  };
  struct CompiledCoordinate {
    CoordinateType type = CoordinateType::Angle;
    int body_i = -1, body_j = -1;
    Eigen::Vector2d s_i, s_j, axis_i;
  };
  CompiledCoordinate compile(const RelativeCoordinate& c, const std::string& owner) const;
  CoordinateValues coordinate(const CompiledCoordinate& c, const Eigen::VectorXd& q, const Eigen::VectorXd& qd) const;
  // Scatters a 6-column local block (bodies i, j) into n global columns.
  void scatter(int body_i, int body_j, const Eigen::MatrixXd& local, Eigen::Ref<Eigen::MatrixXd> global) const;
  Eigen::Matrix<double, 6, 1> gather(int body_i, int body_j, const Eigen::VectorXd& v) const;
  // Scatters a block's local Jacobian (both column blocks of a transmission) into
  // its rows of the global Jacobian (rows x n).
  void scatter(const ConstraintBlock& block, const BlockValues& values, Eigen::Ref<Eigen::MatrixXd> rows) const;

  // Effort (torque or force) of force drive d at a state.
  double force_drive_effort(int d, const Eigen::VectorXd& q, const Eigen::VectorXd& qd, double t) const;
  const CompiledCoordinate& force_drive_coordinate(int d) const { return force_coords_[d]; }

 private:
  Eigen::Vector2d relative_point(int body, const std::string& point) const;

  MultibodyModel model_;
  std::vector<int> moving_;  // model body index of each moving body
  std::vector<int> offset_;  // per model body
  std::vector<EffectiveBody> effective_;
  std::vector<ConstraintBlock> blocks_;
  std::vector<CompiledCoordinate> force_coords_;
  std::vector<double> force_initial_;
  std::vector<CompiledCoordinate> drive_coords_;
  int n_rows_ = 0;
};

}  // namespace kinetofem::mech
