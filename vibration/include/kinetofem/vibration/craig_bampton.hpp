#pragma once
// Craig-Bampton reduction of one elastic part (docs/vibration.md).
//
// A part's FE model (mesh, material, its own supports; none: a free body)
// with boundary coordinates u_b = G^T u (G: 3N x n_b over the mesh's DoFs,
// a column per coordinate) is reduced to
//
//   u = Psi u_b + Phi q + X r,   K_r = T^T K T,  M_r = T^T M T,  T = [Psi Phi X],
//
// coordinates x_r = [u_b; q; r]:
//   * Psi (n x n_b), static constraint modes: the least-energy fields with
//     G^T Psi = I (unit motion of one boundary coordinate, the others held,
//     no other load);
//   * Phi (n x n_q), fixed-interface normal modes: K phi = w^2 M phi on the
//     fields with G^T phi = 0, mass-normalized, all those up to the cutoff
//     frequency (the part-mode rule below);
//   * X (n x n_x, n_x <= n_b; optional, default on), residual vectors: the
//     fixed-interface static response to the constraint modes' inertia
//     less its part in the kept modes, X = K_0^+ M Psi - Phi W^-2 Phi^T M Psi
//     (W = diag(w)), M-orthonormalized and K-diagonalized among themselves
//     (the static correction for the truncated modes; "Craig-Bampton with
//     residual vectors", e.g. Nastran's RESVEC on the interface). They are
//     M- and K-orthogonal to Phi and K-orthogonal to Psi.
// Without X the error of a reduced frequency f falls like (f / f_cutoff)^2
// (the truncated modes' static part is missing); with X like (f / f_cutoff)^4
// or faster (tests/verification/vibration/test_craig_bampton.cpp prints both).
// Phi^T K Psi = 0 (checked and printed), Phi^T M Phi = I, Phi^T K Phi =
// diag(w^2). Units: K_r in N/m, N/rad, N m/rad, M_r in kg, kg m, kg m^2 for
// translation / rotation coordinates; q and r in sqrt(kg) m.
//
// Interfaces. A joint's coupling reference (the elastic assembly's
// interfaces, structure/elastic_assembly.hpp): coupling_interface() gives
// G = the distributing coupling's 6 load columns (fem::DistributingCoupling),
// so u_b = G^T u is the reference point's translation and rotation (the
// coordinates the joints tie together) and G [F; M] its load on the part.
// Plain nodal DoFs: nodal_interface() (unit columns); clamping them in the
// reduced model reproduces the FE model clamped there.
//
// One factorization. A supported part: K_s = K (free equations). A free
// part: K_s = K with a 3-2-1 support (fem::three_two_one_support; it holds
// the rigid motion without constraining the deformation) and the rigid-body
// modes R (n x 6) are carried explicitly. With Z_G = K_s^-1 G,
// F = G^T Z_G and H = G^T R, the small matrix
//   S = [F H; H^T 0]
// gives all three families:
//   Psi = Z_G L + R A,                 [L; A] = S^-1 [I; 0];
//   fixed-interface inverse  y = K_0^+ b = Z_b + Z_G mu + R alpha,
//     Z_b = K_s^-1 b,  [mu; alpha] = S^-1 [-G^T Z_b; -R^T b]
// (the solution of K y = b + G mu with G^T y = 0): its block application to
// M Psi gives the static response X_0 = K_0^+ M Psi (once per part), and its
// block solves yield Phi (below). Every solve is with K_s, on blocks of
// right-hand sides.
// S singular (interfaces that do not hold the part's rigid motion, or
// dependent boundary coordinates) is an Error.
//
// One pass per part (CraigBamptonReducer). K, M, G, Z_G, Psi and X_0 are
// made once; the static reduction [Psi X_0] (no fixed-interface modes) and
// the final one [Psi Phi X] both come from them, X = X_0 - Phi W^-2 Phi^T
// M Psi needing no further solve. So the part-mode rule's bound (the static
// reduction, AssemblyModes) costs nothing but the small projections, and the
// final reduction only the fixed-interface modes' solves.
//
// Fixed-interface modes by a block method on block solves
// (FixedInterfaceSolver::BlockDavidson, the default): Rayleigh-Ritz with K
// and M on a growing M-orthonormal basis V inside G^T u = 0, expanded each
// step by K_0^+ M Y, Y the wanted Ritz vectors not converged yet and the next
// 2 (block Davidson with the exact inverse as preconditioner: LOBPCG's
// expansion, every direction kept). Start: X_0 (the interface inertia's
// static response, rich in the modes the boundary excites) and 4 random
// fields K_0^+ M v (for those it does not excite). Each step is one block
// solve; the basis is taken back onto G^T u = 0 at every orthonormalization
// (round-off magnified off the constraint would let the Ritz values sink
// below the constrained problem's). Converged: every mode kept with
//   ||P (K phi - w^2 M phi)|| / (||K phi|| + w^2 ||M phi||) <= residual_tolerance
// (P: off the interface columns, whose reactions G mu the constrained problem
// admits), the first dropped with sqrt of it (it only has to lie above the
// cutoff). Why this one, measured on the lever-chain manipulator's links
// (80 k DoFs, 1 mode kept; docs/vibration.md): the single-vector Lanczos
// (fem::solve_eigen, Spectra: 33-43 single solves) 1.9-2.5 s; block Lanczos
// expanding the whole latest block of n_b + 4 (3 blocks) 2.7-3.6 s, the
// wide block's orthogonalization and products costing more than its solves
// save; subspace iteration keeps only the latest block and needs more steps
// than either; this method 0.9-1.0 s (3 steps of 3-4 right-hand sides). The
// single-vector Lanczos stays as FixedInterfaceSolver::Lanczos, the reference
// of tests/verification/vibration/test_craig_bampton_one_pass.cpp.
//
// Part-mode rule. Keep every fixed-interface mode with
//   f <= cutoff = cutoff_factor x highest_frequency_of_interest_hz,
// plus the residual vectors. The modes are solved until one above the
// cutoff has converged, so "every" is checked, not assumed.
// Default cutoff_factor = 2: with the residual vectors the reduced
// frequencies up to f_max then agree with the full model to 3e-7 or better
// on the beam tests (1e-4 is the requirement); without them factor 2 gives
// 5e-3 and even factor 16 only 1e-4. format_check() prints the rule, the
// modes kept, the first mode dropped and the orthogonality checks.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/fe_model.hpp"
#include "kinetofem/solver/generalized_eigen.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::vibration {

// Boundary coordinates of one interface: u_b = columns^T u, u over the mesh's
// 3N DoFs (rows of prescribed DoFs are ignored).
struct PartInterface {
  std::string name;
  Eigen::MatrixXd columns;  // 3N x n_b
};

// The 6 coordinates (translation of the reference point, m; rotation, rad;
// in the mesh frame) of a distributing coupling of `face_set` with
// reference point `reference_point_m`. Throws Error if the face set is
// missing or degenerate.
PartInterface coupling_interface(const fem::Mesh& mesh, const std::string& face_set,
                                 const Eigen::Vector3d& reference_point_m, std::string name);

// The 3 displacement DoFs of every node listed (m), in order.
PartInterface nodal_interface(const fem::Mesh& mesh, const std::vector<fem::Index>& nodes,
                              std::string name);

// How the fixed-interface modes are solved (header).
enum class FixedInterfaceSolver {
  BlockDavidson,  // Rayleigh-Ritz on a basis grown by block solves (default)
  Lanczos,       // fem::solve_eigen (Spectra), one solve per Lanczos vector, growing batches
};

struct CraigBamptonOptions {
  double highest_frequency_of_interest_hz = 0.0;  // f_max, Hz, > 0
  double cutoff_factor = 2.0;                     // cutoff = factor x f_max, >= 1
  int first_batch = 12;                           // modes of the first request (Lanczos only)
  int max_modes = 400;                            // more needed below the cutoff: Error
  // Add the residual vectors X (header): n_b more coordinates, frequency
  // error O((f / f_cutoff)^4) instead of O((f / f_cutoff)^2).
  bool residual_vectors = true;
  // false: no fixed-interface modes at all (no solve): the static
  // reduction Psi plus the residual vectors, whose frequencies bound the
  // full model's from above (an estimate for choosing the cutoff);
  // highest_frequency_of_interest_hz is then not used.
  bool fixed_interface_modes = true;
  fem::EigenOptions eigen;                        // tolerance, label (modes, shift: set here)
  FixedInterfaceSolver solver = FixedInterfaceSolver::BlockDavidson;
  // BlockDavidson: relative residual of every mode kept (the first dropped:
  // its square root; header). The frequencies' error goes with its square.
  double residual_tolerance = 1e-8;
};

struct CraigBamptonModel {
  std::string label;
  std::vector<std::string> interface_names;
  std::vector<Eigen::Index> interface_offset;  // first boundary coordinate of each, + total
  Eigen::Index boundary_count = 0;             // n_b
  Eigen::Index mode_count = 0;                 // n_q
  bool free_body = false;                      // 3-2-1 support and rigid modes used
  Eigen::MatrixXd stiffness;                   // K_r, (n_b + n_q)^2
  Eigen::MatrixXd mass;                        // M_r
  Eigen::MatrixXd constraint_modes;            // Psi, n_free x n_b
  Eigen::MatrixXd normal_modes;                // Phi, n_free x n_q
  Eigen::VectorXd normal_frequency_hz;         // kept fixed-interface modes, ascending
  Eigen::Index residual_count = 0;             // n_x (0 without residual vectors)
  Eigen::MatrixXd residual_vectors;            // X, n_free x n_x (M-orthonormal, K-diagonal)
  Eigen::VectorXd residual_frequency_hz;       // sqrt(X^T K X) / 2 pi, Hz
  double cutoff_hz = 0.0;
  double first_dropped_hz = 0.0;               // lowest fixed-interface mode above the cutoff
  double coupling_stiffness_check = 0.0;       // max |Phi^T K Psi| / max |K_r|
  double constraint_check = 0.0;               // max |G^T Psi - I|, max |G^T Phi| / max |Phi|
  long long free_dofs = 0;
  double factor_nonzeros = 0.0;
  long long lanczos_solves = 0;               // right-hand sides solved with K_s for this model
  double seconds = 0.0;
  // K and M assembly, constraint modes, fixed-interface modes,
  // residual vectors, projection (and checks), s. The set-up's phases (K and
  // M, constraint modes, the static response X_0) and solves count in the
  // first model a CraigBamptonReducer makes only.
  std::array<double, 5> phase_seconds{};
};

// One part's reduction in one pass over its factorization (header): the
// constructor assembles K and M and checks the interfaces and supports (no
// solve: a lent analysis need not be factorized yet); the first reduce()
// solves Z_G and X_0 and forms Psi; reduce() gives the static reduction
// (fixed_interface_modes = false: no further solve) or the final one (the
// fixed-interface modes' solves only), as often as asked. A lent analysis
// must be factorized during the reduce() calls that solve and outlive the
// reducer. Memory: K, M and G, Z_G, Psi, M Psi, X_0 (n x 5 n_b)
// until the reducer goes.
class CraigBamptonReducer {
 public:
  // With its own factorization of `part` (its supports; none: a free body).
  CraigBamptonReducer(const fem::FeModel& part, const std::vector<PartInterface>& interfaces,
                      const std::string& label);
  // held = false: a free part on its 3-2-1-supported analysis (as
  // reduce_craig_bampton below); true: a part held by its analysis's
  // supports (as reduce_held_craig_bampton: rows over its free equations).
  CraigBamptonReducer(fem::LinearStaticAnalysis& analysis, const std::vector<PartInterface>& interfaces,
                      const std::string& label, bool held);
  ~CraigBamptonReducer();
  CraigBamptonReducer(CraigBamptonReducer&&) noexcept;
  CraigBamptonReducer& operator=(CraigBamptonReducer&&) noexcept;

  // The reduced model by `options` (labelled as the reducer). Errors like
  // reduce_craig_bampton's.
  CraigBamptonModel reduce(const CraigBamptonOptions& options, const Log* log = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Reduces `part` (its supports as given; none: free body). Throws Error on
// bad options, a zero-density part, interfaces that do not hold the part, or
// an eigen solve that does not converge (EigenNotConverged names the part).
CraigBamptonModel reduce_craig_bampton(const fem::FeModel& part,
                                       const std::vector<PartInterface>& interfaces,
                                       const CraigBamptonOptions& options,
                                       const Log* log = nullptr);

// The rule and the checks in a few lines (printed by the reduction's log).
std::string format_check(const CraigBamptonModel& model);

// The same for a free part whose 3-2-1-supported static analysis exists
// already (pipeline::SupportedPart::analysis(): the stress stage's one
// factorization, shared): every K_s solve goes through
// supported.solve_forces. Its model's supports must be statically
// determinate (6 prescribed DoFs holding the rigid modes; else Error). The
// mesh is copied for the mass assembly; the analysis must outlive the call.
CraigBamptonModel reduce_craig_bampton(fem::LinearStaticAnalysis& supported,
                                       const std::vector<PartInterface>& interfaces,
                                       const CraigBamptonOptions& options,
                                       const Log* log = nullptr);

// The same for a part held by the supports of its factorized static
// analysis (a frame on its foundation: every node of a face set fixed):
// K_s = K on the free equations, no rigid-body modes (S = F), every solve
// through held.solve_forces. Psi, Phi and X are over the analysis's free
// equations (n_free rows; expand_to_mesh_dofs gives them over the mesh's 3N
// DoFs, zero on the held ones). Error if the analysis has no supports.
CraigBamptonModel reduce_held_craig_bampton(fem::LinearStaticAnalysis& held,
                                            const std::vector<PartInterface>& interfaces,
                                            const CraigBamptonOptions& options,
                                            const Log* log = nullptr);

// Rows over the free equations of `dofs` as rows over all its DoFs (3N),
// zero on the prescribed ones.
Eigen::MatrixXd expand_to_mesh_dofs(const Eigen::MatrixXd& free_rows, const fem::DofMap& dofs);

// The lowest `count` frequencies (Hz) of a small dense model K x = w^2 M x
// (M symmetric positive definite), e.g. a reduced model with point masses
// added or coordinates held (rows / columns removed).
Eigen::VectorXd dense_frequencies_hz(const Eigen::MatrixXd& stiffness, const Eigen::MatrixXd& mass,
                                     Eigen::Index count);

}  // namespace kinetofem::vibration
