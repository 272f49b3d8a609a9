#pragma once
// Private to the spatial core: the velocity Jacobian in the mass metric and its
// rank-revealing factorization, shared by the index-1 solve (results.cpp), the
// velocity projection and the DoF count (kinematics.cpp).
//
// With M = C C^T (C = blockdiag(sqrt(m) I3, chol(J)), lower triangular) and
// x = C^T v, the constraint rows read Pi~ x with Pi~ = Pi C^-T. The rank of Pi
// is decided on Pi~ alone, by a complete orthogonal decomposition of Pi~^T with
// a threshold relative to its largest pivot: factoring the whole
// [M Pi^T; Pi 0] instead would compare the pivots of J (1e-10 kg m^2 for a
// small pin in SI) with those of Pi (order 1) and misjudge the rank.
// P = pinv(Pi~^T) (m x n); pinv(Pi~) = P^T; pinv(Pi~ Pi~^T) = P P^T.
#include <Eigen/Dense>

#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spatial/system.hpp"

namespace kinetofem::mech::spatial {

struct ScaledJacobian {
  Eigen::MatrixXd c;          // C (n x n, lower triangular)
  Eigen::MatrixXd pi_scaled;  // Pi~ = Pi C^-T (m x n)
  Eigen::MatrixXd pinv;       // P = pinv(Pi~^T) (m x n)
  int rank = 0;

  ScaledJacobian(const System& system, const Eigen::VectorXd& q, double t, double rank_tolerance = kRankTolerance) {
    const int n = system.n_velocities(), m = system.n_constraints();
    c = system.mass_matrix().llt().matrixL();
    const Eigen::MatrixXd pi = system.jacobian_v(q, t);
    // Pi C^-T = (C^-1 Pi^T)^T.
    pi_scaled = c.triangularView<Eigen::Lower>().solve(pi.transpose()).transpose();
    if (m == 0) {
      pinv.resize(0, n);
      return;
    }
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(rank_tolerance);
    cod.compute(pi_scaled.transpose());
    rank = static_cast<int>(cod.rank());
    pinv = cod.pseudoInverse();
  }

  // v = C^-T x and x = C^T v.
  Eigen::VectorXd to_velocity(const Eigen::VectorXd& x) const {
    return c.transpose().triangularView<Eigen::Upper>().solve(x);
  }
  Eigen::VectorXd to_scaled(const Eigen::VectorXd& v) const { return c.transpose() * v; }
  // C^-1 f: a generalised force in the scaled metric.
  Eigen::VectorXd scaled_force(const Eigen::VectorXd& f) const { return c.triangularView<Eigen::Lower>().solve(f); }
};

}  // namespace kinetofem::mech::spatial
