#pragma once
// Results of a spatial multibody run: one Frame per output time, and the run's checks.
//
// All quantities SI, world axes unless a name says body. For every frame the
// accelerations and multipliers are recomputed from (q, v) by the index-1 system
//     [M   Pi^T] [v'    ]   [Q - h]
//     [Pi   0  ] [lambda] = [gamma],
// in the mass metric (x = C^T v', M = C C^T, Pi~ = Pi C^-T) by a complete
// orthogonal decomposition of Pi~^T (rank-revealing, threshold kRankTolerance
// relative to its largest pivot), so that redundant constraint rows (a planar
// loop built from spatial revolutes, Bricard's mechanism) give the
// minimum-norm multipliers instead of a singular failure; Frame::redundant_rows
// counts them. v' is unique either way. Redundant rows whose right-hand sides
// disagree are an error.
//
// Reaction of a joint on one of its bodies: the load -Pi(rows, body)^T lambda
// (system.hpp), i.e. a force F (world) and a moment about the body's centre of
// mass, moved to the joint point on that body: M_P = M_com - (r_P - r_com) x F,
// both in world axes. For redundant rows the split of the reaction between the
// joints is the minimum-norm one: the rigid-body problem does not determine it.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/spatial/system.hpp"

namespace kinetofem::mech::spatial {

// Relative threshold on the pivots of the mass-metric Jacobian Pi~^T below
// which a constraint row counts as redundant (index-1 solve, velocity
// projection, DoF count, IDAS's row selection).
inline constexpr double kRankTolerance = 1e-10;

struct BodyState {
  std::string name;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // body frame origin
  Eigen::Vector4d euler_parameters{1.0, 0.0, 0.0, 0.0};
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // body axes -> world
  Eigen::Vector3d com, com_velocity, com_acceleration;     // centre of mass incl. point masses
  Eigen::Vector3d angular_velocity, angular_acceleration;  // world axes
};

struct Reaction {
  std::string body;
  Eigen::Vector3d point_world = Eigen::Vector3d::Zero();   // joint point on this body
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_world = Eigen::Vector3d::Zero();  // about point_world
};

struct JointState {
  std::string name;
  JointType type = JointType::Revolute;
  Reaction on_i, on_j;  // load the joint applies on body_i and on body_j
};

struct DriveState {
  std::string name;
  double s = 0.0, s_dot = 0.0, s_ddot = 0.0;  // the driven coordinate (rad or m) and its derivatives
  double effort = 0.0;                         // torque N m (force N) on body_j, reacted on body_i: -lambda
  // The drive row's load on each body, as a joint's reaction (at the driven
  // joint's points): what a part that carries the motor or the actuator takes
  // through its mount. For a translation the pair also holds the couple of
  // the axis turning with body_i.
  Reaction on_i, on_j;
};

struct Frame {
  double t = 0.0;
  std::vector<BodyState> bodies;   // model order, ground included
  std::vector<JointState> joints;  // model joint order
  std::vector<DriveState> drives;  // model drive order
  Eigen::VectorXd q, v, v_dot, lambda;
  double kinetic_energy_J = 0.0, potential_energy_J = 0.0;
  double drift_position_m = 0.0, drift_velocity_m_per_s = 0.0;
  int redundant_rows = 0;             // m - rank(Pi)
  double equilibrium_residual = 0.0;  // max |M v' + Pi^T lambda - (Q - h)| over the largest load
};

struct RunSummary {
  std::string method;  // "IDAS GGL index-2", "kinematic"
  double max_drift_position_m = 0.0, max_drift_velocity_m_per_s = 0.0;
  double max_drift_relative = 0.0;  // position drift / characteristic length
  double max_equilibrium_residual = 0.0;
  int redundant_rows = 0;           // at the initial state
  // IDAS: the rows left out of the integrated set, "'C' row 4 of 5" (1-based),
  // chosen by the pivoting; which rows of a redundant loop go is arbitrary.
  std::vector<std::string> dropped_rows;
  long steps = 0, residual_evaluations = 0, error_test_failures = 0, nonlinear_failures = 0;
};

struct Results {
  std::vector<Frame> frames;
  RunSummary summary;
  std::string format_checks() const;
};

// The index-1 solve at (t, q, v): v' and the minimum-norm multipliers, and the
// number of redundant rows found by the rank-revealing factorization.
struct IndexOneSolution {
  Eigen::VectorXd v_dot, lambda;
  int redundant_rows = 0;
};
IndexOneSolution solve_index_one(const System& system, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double t);

// Builds the frame at (t, q, v) (coordinates as in system.hpp).
Frame make_frame(const System& system, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v);

// Fills the summary's drift and equilibrium fields from the frames.
void summarize(const System& system, Results& results);

}  // namespace kinetofem::mech::spatial
