#pragma once
// Generalized symmetric eigenproblem of a structure's free vibration,
//
//   K phi = omega^2 M phi,   phi^T M phi = I,                K in N/m, M in kg
//
// by shift-invert Lanczos (Spectra 1.0, SymGEigsShiftSolver, M-inner
// product): the Ritz values of (K - sigma M)^-1 M are nu = 1 / (omega^2 -
// sigma), so the modes nearest the shift sigma converge first. The operator
// (K - sigma M)^-1 is one CHOLMOD factorization (cholmod_solver.hpp).
//
// The shift must lie below the lowest eigenvalue wanted so that K - sigma M
// is positive definite (CHOLMOD's Cholesky): sigma = 0 for a supported part,
// sigma < 0 for a free-free part (its six rigid-body modes then come out at
// omega^2 ~ 0 and their frequencies are returned as ~0 Hz).
//
// Optional point masses tied to the mesh through couplings add a low-rank
// term: M_total = M + U C U^T (U: n x p coupling columns, C: p x p, kg and
// kg m^2, e.g. a point mass with rotary inertia at a distributing coupling's
// reference, U = its 6 columns G). Its inverse is applied by Woodbury's
// identity on the sparse factor, so the face's nodes do not fill the pattern.
//
// solve_eigen() is the same Lanczos on any operators (the Craig-Bampton
// fixed-interface problem uses it with a constrained inverse, vibration/).
//
// Errors (kinetofem::Error, one line): modes < 1 or >= the problem size, a
// mass matrix that is not positive (a zero diagonal: zero density), a shift
// at or above an eigenvalue (K - sigma M not positive definite), and
// non-convergence (EigenNotConverged, naming how many modes converged).
//
// Units: omega^2 in rad^2/s^2, frequencies in Hz (f = omega / 2 pi; a
// numerically negative omega^2 gives f = -sqrt(-omega^2) / 2 pi).
#include <functional>
#include <string>

#include <Eigen/Core>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/sparse.hpp"

namespace kinetofem::fem {

struct EigenOptions {
  int modes = 10;                 // number wanted, >= 1
  double shift_rad2_s2 = 0.0;     // sigma, (rad/s)^2; below the lowest eigenvalue
  int lanczos_vectors = 0;        // Spectra's ncv; 0: max(2 modes + 1, modes + 20), <= size
  int max_restarts = 1000;        // implicit restarts before giving up
  double tolerance = 1e-10;       // Spectra's relative Ritz-value tolerance
  std::string label = "part";     // who is solved, for messages
};

struct EigenStatistics {
  long long size = 0;              // equations
  long long converged = 0;         // Ritz pairs converged (>= modes on success)
  long long restarts = 0;
  long long operator_applications = 0;  // solves with K - sigma M
  double factor_nonzeros = 0.0;    // nnz(L) of K - sigma M (0 for a user operator)
  double seconds = 0.0;             // solve_generalized_eigen: with the factorization
  // max_i ||K phi - w2 M phi|| / (||K phi|| + max(|w2|, |sigma|) ||M phi||)
  double max_relative_residual = 0.0;
  double max_orthogonality_error = 0.0;  // max |phi^T M phi - I|
};

// Thrown when fewer modes than wanted converged.
class EigenNotConverged : public Error {
 public:
  EigenNotConverged(const std::string& message, EigenStatistics statistics)
      : Error(message), statistics_(statistics) {}
  const EigenStatistics& statistics() const { return statistics_; }

 private:
  EigenStatistics statistics_;
};

struct EigenSolution {
  Eigen::VectorXd omega2_rad2_s2;  // ascending
  Eigen::VectorXd frequency_hz;    // signed sqrt(omega^2) / 2 pi
  Eigen::MatrixXd modes;           // n x m, mass-normalized (phi^T M phi = I)
  EigenStatistics statistics;
};

// y = A x on the problem's space (n).
using LinearOperator =
    std::function<void(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::VectorXd> y)>;

// The operators of a generalized eigenproblem for Lanczos.
struct EigenOperators {
  Eigen::Index size = 0;
  LinearOperator shift_inverse;  // y = (K - sigma M)^-1 x, symmetric
  LinearOperator mass;           // y = M x, symmetric positive definite on the space
  LinearOperator stiffness;      // y = K x (residual check)
  double shift_rad2_s2 = 0.0;    // the sigma of shift_inverse
  // Optional start vector; must lie in the space the operators act on (a
  // constrained problem: apply shift_inverse to a random vector first).
  Eigen::VectorXd start;
};

// Lanczos on the given operators (options.shift_rad2_s2 is ignored: the
// operators carry sigma). Throws EigenNotConverged or Error (header).
EigenSolution solve_eigen(const EigenOperators& operators, const EigenOptions& options,
                          const Log* log = nullptr);

// Point masses tied through couplings: M_total = M + basis * mass * basis^T.
struct LowRankMass {
  Eigen::MatrixXd basis;  // n x p (free equations)
  Eigen::MatrixXd mass;   // p x p, symmetric positive semidefinite (kg, kg m^2)
};

// K phi = w^2 (M + U C U^T) phi with K, M the free-free blocks of one part
// (upper triangles on the same pattern: assemble_stiffness / assemble_mass
// on one DofMap). One CHOLMOD factorization of K - sigma M.
EigenSolution solve_generalized_eigen(const SymmetricUpperMatrix& stiffness,
                                      const SymmetricUpperMatrix& mass,
                                      const EigenOptions& options,
                                      const LowRankMass* point_masses = nullptr,
                                      const Log* log = nullptr,
                                      const CholmodOptions& cholmod = {});

// Signed frequency (Hz) of an eigenvalue omega^2 (rad^2/s^2).
double frequency_hz(double omega2_rad2_s2);

// Throws Error naming `label` and the equation unless every diagonal entry of
// the mass matrix is positive and finite (zero density, a node with no mass).
void check_mass_positive(const SymmetricUpperMatrix& mass, const std::string& label);

}  // namespace kinetofem::fem
