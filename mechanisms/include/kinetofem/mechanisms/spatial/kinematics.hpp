#pragma once
// Kinematic analysis of a spatial::System (system.hpp):
//   assemble             Newton on [Phi(q, t); p_k.p_k - 1] = 0 with minimum-norm
//                        steps (complete orthogonal decomposition of the
//                        Jacobian), so a mechanism with DoF > 0 or redundant
//                        rows assembles to the nearest consistent pose;
//   solve_velocities     the velocity nearest the guess in the mass metric with
//                        Pi v = nu: min |v - v_guess|_M (the exact velocities
//                        of a fully driven mechanism), by the pseudo-inverse of
//                        the mass-metric Jacobian (results.hpp);
//   run_kinematics       a fully driven mechanism (DoF 0) over output times:
//                        pose, velocity, and from the index-1 system (results.hpp)
//                        accelerations, reactions and drive efforts (inverse dynamics).
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"

namespace kinetofem::mech::spatial {

struct KinematicOptions {
  double tolerance = 1e-13;  // on the drift, relative to the characteristic length
  int max_iterations = 50;
};

Eigen::VectorXd assemble(const System& system, Eigen::VectorXd q_guess, double t, const KinematicOptions& options = {});
Eigen::VectorXd solve_velocities(const System& system, const Eigen::VectorXd& q, double t,
                                 const Eigen::VectorXd& v_guess);
// Degrees of freedom at q: 6 nb - rank(Pi) (rank at kRankTolerance, results.hpp).
int degrees_of_freedom(const System& system, const Eigen::VectorXd& q, double t);

// Throws unless the model has DoF 0 at the assembled initial pose. Each output
// time's pose is assembled from the previous one's linear prediction.
Results run_kinematics(const System& system, const std::vector<double>& times, const KinematicOptions& options = {});

}  // namespace kinetofem::mech::spatial
