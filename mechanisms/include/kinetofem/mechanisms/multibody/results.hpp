#pragma once
// Results of a multibody run: one Frame per output time, and the run's checks.
//
// All quantities SI. World frame unless a name says body frame. For every frame
// the accelerations and multipliers are recomputed from the integrator's
// (q, q') by the index-1 system
//     [M  Phi_q^T] [q'' ]   [Q    ]
//     [Phi_q   0 ] [lambda] = [gamma],
// so that the reactions satisfy each body's d'Alembert equilibrium to round-off
// whatever the integrator's tolerance; the integrator's own accuracy shows in the
// constraint drift and the energy balance.
//
// Reaction of a joint on one of its bodies: the load -Phi_q(rows, body)^T lambda,
// i.e. a force F (world, and the same force in the body frame) and the moment
// about the joint point on that body, M_P = M_com - (r_P - r_com) x F (zero for a
// revolute; the moment a fixed or prismatic pair carries; for a chain, the moment
// about the roller centre of the chain's pull on the roller).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/multibody/system.hpp"

namespace kinetofem::mech {

struct BodyFrame {
  std::string name;
  Eigen::Vector3d q, q_dot, q_ddot;     // body frame origin (x, y, theta) and its derivatives
  Eigen::Vector2d com, com_velocity, com_acceleration;  // centre of mass incl. point masses
};

struct Reaction {
  std::string body;
  Eigen::Vector2d point_world = Eigen::Vector2d::Zero();  // where it acts (joint point on this body)
  Eigen::Vector2d force_world = Eigen::Vector2d::Zero();
  Eigen::Vector2d force_body = Eigen::Vector2d::Zero();   // same force in the body's frame
  double moment_Nm = 0.0;                                 // about point_world
};

struct JointFrame {
  std::string name;
  JointType type = JointType::Revolute;
  Reaction on_i, on_j;  // load the joint applies on body_i and on body_j
};

struct DriveFrame {
  std::string name;
  bool prescribed = false;   // motion drive (constraint) or force drive
  double s = 0.0, s_dot = 0.0, s_ddot = 0.0;  // relative coordinate (rad or m) and derivatives
  double effort = 0.0;       // torque N m (force N) applied on body_j, reacted on body_i
  double power_W = 0.0;      // effort * s_dot
};

struct ChainFrame {
  std::string name;
  double tension_N = 0.0;
  double free_length_m = 0.0;
  double wrap_angle_rad = 0.0;  // sigma*(theta_roller - tau), as in system.hpp
};

// A transmission (model.hpp) at one output time, from its multiplier lambda.
// The moments are what the transmission applies to the bodies of each
// coordinate: on body_j (+), reversed on body_i (-), as a drive's effort.
struct TransmissionFrame {
  std::string name;
  double s_in = 0.0, s_out = 0.0;          // the two relative angles (rad)
  double s_in_dot = 0.0, s_out_dot = 0.0;  // rad/s
  double moment_output_Nm = 0.0;  // -lambda: on the output's body_j
  double moment_input_Nm = 0.0;   // i lambda = -i moment_output: on the input's body_j
  // moment_output / radius (N): a belt's effective pull (tight minus slack strand)
  // or the tangential tooth force on the output's pitch circle.
  double force_N = 0.0;
};

struct Frame {
  double t = 0.0;
  std::vector<BodyFrame> bodies;   // model order, ground included
  std::vector<JointFrame> joints;  // model joint order
  std::vector<DriveFrame> drives;  // motion drives, then force drives
  std::vector<ChainFrame> chains;
  std::vector<TransmissionFrame> transmissions;  // model order
  Eigen::VectorXd q, q_dot, q_ddot, lambda;  // solver coordinates (centre-of-mass based), multipliers
  double kinetic_energy_J = 0.0, potential_energy_J = 0.0;
  double work_drives_J = 0.0;   // from t0: all drives (prescribed and force laws)
  double work_other_J = 0.0;    // from t0: dampers and point forces
  double drift_position_m = 0.0, drift_velocity_m_per_s = 0.0;
  double equilibrium_residual = 0.0;  // max over bodies, relative to the largest load
  double jacobian_condition = 0.0;    // sigma_max / sigma_min of Phi_q
};

struct RunSummary {
  std::string method;  // "IDAS GGL index-2", "CVODES minimal coordinate", "kinematic"
  double max_drift_position_m = 0.0, max_drift_velocity_m_per_s = 0.0;
  double max_drift_relative = 0.0;  // position drift / characteristic length
  double max_equilibrium_residual = 0.0;
  double energy_balance_error = 0.0;  // max |dT + dV - W| / energy scale (dynamic runs)
  std::vector<std::string> slack_chains;  // "name at t = ..." when slack is not an error
  long steps = 0, residual_evaluations = 0, jacobian_evaluations = 0, error_test_failures = 0,
       nonlinear_failures = 0;
  double first_step_s = 0.0;  // the integrator's first step (dynamic runs; DynamicsOptions::initial_step_s)
};

struct Results {
  std::vector<Frame> frames;
  RunSummary summary;
  // Human-readable check block: drift, equilibrium, energy balance, solver statistics.
  std::string format_checks() const;
  // The joints' reactions at the last output time, a line each ("  t = 2 s, revolute 'A0': on lever F = ...").
  std::string format_final_reactions() const;
};

struct FrameOptions {
  double singular_tolerance = 1e-6;  // 1/cond(Phi_q) below this is a singular position
  bool slack_is_error = true;
};

// Builds the frame at (t, q, q') (coordinates as in system.hpp); throws on a
// singular position or, when options say so, a slack chain.
Frame make_frame(const MultibodySystem& system, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                 const FrameOptions& options, RunSummary* summary = nullptr);

// Fills the summary's drift, equilibrium and energy-balance fields from frames.
// energy_balance: also compute the energy-balance error (needs the frames' work fields).
void summarize(const MultibodySystem& system, Results& results, bool energy_balance = false);

}  // namespace kinetofem::mech
