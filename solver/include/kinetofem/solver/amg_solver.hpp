#pragma once
// AmgSolver — iterative solver of K u = f for models whose Cholesky factor
// does not fit in memory: conjugate gradients preconditioned by one V-cycle of
// algebraic multigrid (hypre BoomerAMG) for 3D elasticity:
// nodal systems AMG, which interpolates the rigid translations exactly, and
// optionally the rigid rotations as interpolation vectors.
//
// The system given to hypre is the full nodal one, 3 DoFs per node
// interlaced (row 3 n + c, c = x, y, z), so that BoomerAMG's nodal options
// apply: prescribed DoFs (eliminated from K_ff) come back as decoupled rows
// d u_d = 0 (d = the mean diagonal of K_ff, which keeps the matrix scaled;
// their right-hand side is 0, prescribed values are already in f_f - K_fp u_p)
// and every free DoF gets its row of K_ff. BoomerAMG set-up for elasticity
// (Baker, Kolev, Yang, "Improving algebraic multigrid interpolation operators
// for linear elasticity problems", NLAA 17, 2010; the settings MFEM uses):
//   - systems AMG, 3 functions (the unknown approach: interpolation within
//     each displacement component, so a constant per component — the three
//     rigid translations — is reproduced exactly on every level), nodal
//     coarsening on the row-sum norm of the 3 x 3 nodal blocks, strength
//     threshold 0.5, HMIS coarsening, extended+i interpolation (4 per row),
//   - optionally (rigid_body_modes) the interpolation augmented by the three
//     rotations about the centroid, r_x = (0, -(z - zc), y - yc), ... (GM
//     variant 2). Off by default: on a 33k-DoF TET10 cantilever it cut PCG
//     iterations from 100 to 81 but raised the operator complexity from 1.9
//     to 4.8 and the time per solve from 7.6 s to 25 s (hypre 2.26, 1 core),
//   - l1-Gauss-Seidel smoothing (symmetric for PCG), one sweep up and down.
// The hierarchy is set up once in setup(); solve() runs PCG for each column
// of the right-hand side block with it. The PCG loop is our own, on hypre's
// ParCSR matrix-vector product and ParVector operations, step for step the
// one of hypre_PCGSolve (HYPRE_ParCSRPCGSolve with TwoNorm 0 and
// RecomputeResidual 1, which it replaces: same iterates, same iteration
// counts), so that it can report progress between iterations.
//
// Progress: a right-hand side that has been iterating for longer than
// AmgOptions::progress_interval_s prints a line through the Log at most every
// progress_interval_s (PcgProgress, pcg_progress.hpp), on rank 0:
//   AMG-PCG column 3/37: iteration 80, relative residual 3.2e-06 (target 1e-08), ~45 s left
// the relative residual being sqrt((r, C r) / (b, C b)), the quantity of the
// stopping test, and the time left extrapolated from its mean decrease per
// iteration so far ("time left unknown" before it decreases).
//
// Convergence: PCG stops when (r, C r) < relative_tolerance^2 (b, C b), C the
// AMG preconditioner (~K^-1, so an energy-like norm of the error). A 2-norm
// test ||K x - b|| <= 1e-10 ||b|| would be at the round-off floor (CHOLMOD's
// own solution of a 20k-DoF cantilever leaves ~1e-10), and at 2.4 M DoFs the
// preconditioned norm itself stalls near 6e-10 (bench/amg_scaling: 1000
// iterations without reaching 1e-10), hence the default 1e-8; the tests show
// the displacements then agree with CHOLMOD's far below the 1e-6 required. Every column's 2-norm residual is then
// recomputed with the assembled K_ff and must be below max_relative_residual
// (1e-6: a guard against a broken solve; the tests show 2e-8..7e-8 at the
// default tolerance while the displacements agree with CHOLMOD to ~1e-11). A column that does not converge within
// max_iterations is an Error naming the column, the iteration count and the
// residual reached; so is a breakdown of the recurrence ((A p, p) = 0, or a
// step length or (r, C r) that is not a positive normal number).
//
// MPI: hypre is built with MPI. By default each AmgSolver works on
// MPI_COMM_SELF (one process; MPI is initialised on first use if the program
// has not done it, and finalised at exit), so processes of a `kinetofem
// batch` run stay independent. With `distributed = true` it works on
// MPI_COMM_WORLD: every rank passes the same full K_ff and right-hand sides
// (each assembles the whole model — simple, not memory-scalable), owns a
// contiguous block of whole nodes, and gets the full solution back.
#include <cstdint>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/sparse.hpp"

namespace kinetofem::fem {

struct AmgOptions {
  double relative_tolerance = 1e-8;     // PCG, preconditioned norm (see above)
  double max_relative_residual = 1e-6;  // ||K x - b||_2 / ||b||_2 after PCG, else an Error
  int max_iterations = 1000;            // PCG iterations per right-hand side
  double strong_threshold = 0.5;        // BoomerAMG strength of connection (3D elasticity)
  bool rigid_body_modes = false;        // augment the interpolation with the rotations
  int max_levels = 25;
  // MPI_COMM_WORLD with each rank owning a block of nodes (see the header
  // comment); false: MPI_COMM_SELF.
  bool distributed = false;
  int hypre_print_level = 0;  // hypre's own output (1: BoomerAMG set-up summary)
  // A progress line (iteration, residual, time left) at most every this many
  // seconds of a right-hand side's PCG, once it has run that long; 0: every
  // iteration (tests, debugging), negative: never.
  double progress_interval_s = 10.0;
};

struct AmgStatistics {
  std::int64_t equations = 0;        // free equations (rows of K_ff)
  std::int64_t system_rows = 0;      // rows given to hypre: 3 per node
  std::int64_t matrix_nonzeros = 0;  // stored nonzeros of the full symmetric system
  int ranks = 1;
  int levels = 0;                    // multigrid levels
  double operator_complexity = 0.0;  // sum over levels of nnz(A_l) / nnz(A_0)
  double setup_seconds = 0.0;        // matrix hand-over + BoomerAMG hierarchy
  // Last solve(): per right-hand side.
  std::vector<int> iterations;
  std::vector<double> relative_residuals;  // ||K_ff x - b|| / ||b||, recomputed here
  std::vector<double> solve_seconds;
  double last_solve_seconds = 0.0;   // the whole block
  double total_solve_seconds = 0.0;  // all solve() calls
  std::int64_t total_rhs = 0;
  int max_iterations() const;
  double max_relative_residual() const;
};

// The six rigid-body modes over all 3 N DoFs (DoF 3 n + c): columns 0..2 the
// translations along x, y, z (unit), 3..5 the rotations about x, y, z through
// the centroid of the nodes (m per rad). K times each is zero for an
// unsupported body.
Eigen::MatrixXd rigid_body_modes(const NodeCoordinates& nodes);

class AmgSolver {
 public:
  explicit AmgSolver(AmgOptions options = {}, const Log* log = nullptr);
  ~AmgSolver();
  AmgSolver(const AmgSolver&) = delete;
  AmgSolver& operator=(const AmgSolver&) = delete;

  // Hands K_ff (upper triangle, equations numbered by `dofs`) to hypre and
  // builds the multigrid hierarchy with the rigid-body modes of `nodes`.
  // The matrix must stay alive until the last solve() (residual check).
  void setup(const SymmetricUpperMatrix& K_ff, const NodeCoordinates& nodes, const DofMap& dofs);
  // X = K_ff^{-1} B, column by column (PCG from a zero initial guess).
  // Throws Error when a column does not reach the tolerance.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs);

  const AmgStatistics& statistics() const { return stats_; }
  const AmgOptions& options() const { return options_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  AmgOptions options_;
  const Log* log_;
  AmgStatistics stats_;
};

// MPI rank and size of MPI_COMM_WORLD (initialising MPI if needed): for
// drivers of distributed solves that print on one rank only.
int mpi_world_rank();
int mpi_world_size();

}  // namespace kinetofem::fem
