#pragma once
// Kinematic analysis of a MultibodySystem: assembly, velocities,
// accelerations with multipliers, singular-position detection, and the
// prescribed-motion (kinetostatic) run of a fully driven mechanism.
//
// Assembly: Newton iterations q <- q - Phi_q^+ Phi(q, t) (minimum-norm step,
// complete orthogonal decomposition, so under-determined systems move as little
// as possible from the guess) until max|Phi| (angles times the characteristic
// length) < tolerance * L. Failure throws "cannot be assembled at t = ...,
// residual ...".
// Velocities: q' = g - Phi_q^T (Phi_q Phi_q^T)^-1 (Phi_q g - nu), the
// constrained velocity closest to the guess g.
// Accelerations: the index-1 system of results.hpp.
// Singular position: the smallest singular value of Phi_q relative to the
// largest below the tolerance (rank loss: a dead centre, a limit of assembly).
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/mechanisms/multibody/system.hpp"

namespace kinetofem::mech {

struct KinematicOptions {
  double tolerance = 1e-13;          // relative to the characteristic length
  int max_iterations = 50;
  double singular_tolerance = 1e-6;  // on sigma_min / sigma_max of Phi_q
  bool slack_is_error = true;
  // Largest change of any coordinate from one assembled pose to the next while
  // following the motion (rad for angles; for positions, a fraction of the
  // characteristic length): keeps Newton on the assembly branch it started on.
  double max_substep = 0.1;
  // Most substeps of one run besides one per output interval (a substep aims
  // at half of max_substep: 100 000 follow some 800 crank turns): a motion far
  // beyond any mechanism's (1e7 deg/s for 1 s) is an error, not an endless run.
  long max_substeps = 100000;
};

Eigen::VectorXd assemble(const MultibodySystem& system, Eigen::VectorXd q_guess, double t,
                         const KinematicOptions& options = {});
Eigen::VectorXd solve_velocities(const MultibodySystem& system, const Eigen::VectorXd& q, double t,
                                 const Eigen::VectorXd& qd_guess);

struct Accelerations {
  Eigen::VectorXd q_ddot, lambda;
};
Accelerations solve_accelerations(const MultibodySystem& system, const Eigen::VectorXd& q,
                                  const Eigen::VectorXd& qd, double t);

// sigma_max / sigma_min of Phi_q (infinity when rank-deficient).
double jacobian_condition(const MultibodySystem& system, const Eigen::VectorXd& q, double t);
// Throws "singular position at t = ...: ..." naming the time, the condition and the body poses.
void check_regular(const MultibodySystem& system, const Eigen::VectorXd& q, double t, double singular_tolerance);

// Number of degrees of freedom at q: n - rank(Phi_q).
int degrees_of_freedom(const MultibodySystem& system, const Eigen::VectorXd& q, double t);

// Follows the assembly (q, q') from t_from to t_to in substeps: each pose is
// assembled from the previous one's linear prediction and accepted only when no
// coordinate moved by more than options.max_substep (else the substep is
// halved), and every substep's pose is checked regular. Thus the result is on
// the branch the motion started on, however far apart t_from and t_to are.
// Throws, naming the times, where the motion cannot be followed (a limit of
// assembly, a dead centre or a branch point), a substep's pose is singular, or
// `substeps` (counted across calls: the run's substeps so far) would pass
// options.max_substeps.
void follow_assembly(const MultibodySystem& system, Eigen::VectorXd& q, Eigen::VectorXd& qd, double t_from,
                     double t_to, const KinematicOptions& options, long& substeps);

// Kinematically determined run (DoF 0): follow the assembly from each output
// time to the next (follow_assembly), solve velocities and accelerations, and the multipliers (drive efforts,
// reactions) by kinetostatics. Drive work is integrated with the trapezoidal rule
// over the output times (a coarse check, not used for verification).
Results run_kinematics(const MultibodySystem& system, const std::vector<double>& times,
                       const KinematicOptions& options = {});

}  // namespace kinetofem::mech
