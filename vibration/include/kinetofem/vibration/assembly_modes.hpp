#pragma once
// AssemblyModes — the natural frequencies and mode shapes of the elastic
// assembly (structure/elastic_assembly.hpp) in any pose, from one
// Craig-Bampton reduction per part (vibration/craig_bampton.hpp) made once,
// and per pose one small dense eigenproblem. docs/vibration.md.
//
// Coordinates x (the same in every pose): per elastic part, in its body axes,
//   [u_b; q; r]  its interfaces' motions (the assembly's joint, drive and
//                tracked-point couplings, then one coupling per point mass it
//                carries: the gripper, the casting), its fixed-interface
//                modes and its residual vectors;
// per moving rigid body, its origin's translation and rotation (body axes).
// A part of the ground (the frame, structure::Part::held_face) is reduced
// with its foundation held (vibration::reduce_held_craig_bampton: no
// rigid-body modes); its interfaces, like in the assembly's statics, move by
// its deformation alone (the ground does not move).
// In body axes the parts' K_r, M_r and the rigid bodies' 6 x 6 masses do not
// change with the pose; the pose enters through the interfaces' world
// coordinates u = U(pose) x: the joints and rigid drives hold C U x = 0 and
// the chains and compliant drives add U^T S U to K (InterfaceStructure). On
// the null space N of C U (orthonormal basis, by QR):
//   (N^T K N) y = w^2 (N^T M N) y,   mode shape x = N y, x^T M x = 1.
// Mass: each part's consistent mass; a point mass m at its mount face's
// coupling, diag(m, m, m) on the coupling's translation (no rotary inertia:
// the planar model has none); a rigid body's m, centre of mass and I_zz from
// the multibody model, with I_xx = I_yy = I_zz / 2 about its centre of mass
// (a planar lamina with equal principal moments: the planar model gives no
// out-of-plane inertia; said in the log).
// The stiffness is the structure's about each pose: no geometric stiffness of
// the weight and inertia loads, no gyroscopic or centrifugal terms (the pose
// frozen, docs/vibration.md "What is neglected").
//
// Part-mode rule (CraigBamptonOptions): each part keeps every fixed-interface
// mode up to part_mode_cutoff_hz, plus its residual vectors. Automatic cutoff
// (0, the default): cutoff_factor x f_max, f_max = the highest assembly
// frequency wanted, estimated from the parts' static reduction (constraint
// modes and residual vectors only, no fixed-interface modes) over the poses given; by
// Rayleigh-Ritz the final frequencies lie below that estimate, so the rule
// holds for them (checked and printed by check_rule()).
// One pass per part (vibration::CraigBamptonReducer): K, M, the constraint
// modes and the static response X_0 are made once and serve both the static
// reduction (the bound: no solve) and the final one (the fixed-interface
// modes' block solves only).
// Part by part: each part's factor is borrowed (PartFactorLender) for its
// set-up (Z_G, X_0), given back, and borrowed again for its fixed-interface
// modes after the bound, parts from the last to the first and then back, so
// the first part's factor serves both without a second lend (and a lender
// that kept the last part's factor from the assembly's set-up need not make
// it again); with a lender that frees it in
// between only one factor is in memory at a time (the others are made again
// for their second use), with the reducers' n x 5 n_b columns and K, M of
// every part.
//
// SI units: Hz, rad/s; x in m, rad, sqrt(kg) m.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/part.hpp"
#include "kinetofem/vibration/craig_bampton.hpp"

namespace kinetofem::vibration {

using structure::ElasticAssembly;

struct AssemblyModesOptions {
  int modes = 6;                      // natural frequencies wanted per pose, >= 1
  double part_mode_cutoff_hz = 0.0;   // > 0: fixed-interface modes kept up to it; 0: automatic (header)
  double cutoff_factor = 2.0;         // automatic cutoff = factor x f_max, >= 1
  // The parts' fixed-interface modes (vibration/craig_bampton.hpp); the
  // single-vector Lanczos is the reference the block method is tested on.
  FixedInterfaceSolver fixed_interface_solver = FixedInterfaceSolver::BlockDavidson;
};

// One part's reduction, for the log and the summary.
struct PartReduction {
  std::string body;
  long long dofs = 0;
  Eigen::Index boundary = 0, modes = 0, residual = 0;  // coordinates
  double cutoff_hz = 0.0, first_dropped_hz = 0.0;       // the rule: first dropped > cutoff
  double seconds = 0.0;
};

struct PoseModes {
  double t = 0.0;
  Eigen::VectorXd omega_rad_s;    // m, ascending
  Eigen::VectorXd frequency_hz;   // m
  Eigen::MatrixXd shapes;         // n x m over x, mass-normalized
  Eigen::Index constrained_size = 0;  // dimension of the null space of C U
};

// Lends each part's factorized 3-2-1-supported analysis (the elastic
// assembly's, ElasticAssembly::supported_analysis) to the reductions and
// takes it back between their uses (pipeline::PartFactors: it frees the
// factor in between when the parts' factors do not fit in memory together).
class PartFactorLender {
 public:
  virtual ~PartFactorLender() = default;
  virtual fem::LinearStaticAnalysis& lend(const std::string& body) = 0;  // factorized
  virtual void give_back(const std::string& body) = 0;                   // not solved with until lent again
};

class AssemblyModes {
 public:
  // Reduces every part of `assembly` once (its shared factorizations); the
  // automatic cutoff is estimated over `poses`: give every pose whose modes
  // will be asked for (the bound holds pose by pose only; the vibration stage
  // gives every output time and the static pose). Throws Error for bad
  // options, rigid-bore couplings, a part of zero density, an eigen solve
  // that does not converge (vibration::EigenNotConverged names the part).
  // `lender` (may be null: the assembly's factors are alive throughout) lends
  // each part's factor for its reductions, part by part (header).
  AssemblyModes(const ElasticAssembly& assembly, const std::vector<structure::Part>& parts,
                const mech::MultibodyModel& model, const AssemblyModesOptions& options,
                const std::vector<mech::Frame>& poses, const Log& log, PartFactorLender* lender = nullptr);
  ~AssemblyModes();
  AssemblyModes(AssemblyModes&&) noexcept;
  AssemblyModes& operator=(AssemblyModes&&) noexcept;

  // The lowest options.modes modes of the pose. Error naming the time when
  // fewer coordinates are free than modes wanted.
  PoseModes modes(const mech::Frame& frame) const;

  Eigen::Index size() const;  // n = the coordinates x
  const Eigen::MatrixXd& mass() const;  // M_x, n x n (constant)
  // Generalized load on x of the frame's inertia and weight loads (the
  // parts' load patterns without joints and motion drives; the rigid
  // bodies' applied minus inertia loads), N, N m, N/sqrt(kg)... per coordinate.
  Eigen::VectorXd load(const mech::Frame& frame) const;
  // The tracked point's translation (world axes, m) as rows over x: 3 x n.
  Eigen::MatrixXd point_rows(const std::string& point, const mech::Frame& frame) const;
  // The reduced model's static response to load(frame), x (for the check
  // against the elastic assembly's own static solution).
  Eigen::VectorXd static_response(const mech::Frame& frame, const Eigen::VectorXd& load) const;
  // Per part: its displacement field (N x 3, world axes) of a vector x.
  std::vector<Eigen::MatrixXd> part_fields(const Eigen::VectorXd& x, const mech::Frame& frame) const;

  const std::vector<PartReduction>& reductions() const;
  double cutoff_hz() const;       // as used (the same for every part)
  double estimated_fmax_hz() const;  // automatic rule: f_max of the static reduction; else 0
  // The rule in one line: cutoff, f_max of the final modes over the poses
  // seen, the factor achieved.
  std::string check_rule(double highest_frequency_seen_hz) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kinetofem::vibration
