#pragma once
// Stress and deformation of one link over the whole motion.
//
// The link's stiffness (body frame, free body held by a statically
// determinate 3-2-1 support) is assembled and factorized once; the loads of
// all output times are solved as blocks of right-hand sides. Each step's
// displacement (elastic, body frame, m) and nodal stresses (Pa) are handed to
// a callback (to stream them to the results file) and folded into the
// envelope: per node the maximum von Mises stress and deformation magnitude
// over the motion and the step where each occurs. The deformation is the
// elastic displacement minus its best-fitting rigid-body motion
// (fem::remove_rigid_body_motion), so it does not depend on which nodes the
// 3-2-1 support holds.
//
// Two paths, the same results (to round-off; tests/verification/loads):
//   * unit-load superposition (LoadPath::Superposition; the default when the
//     link's loads allow it, LinkLoads::superposable()): the m load patterns
//     of LinkLoads are solved and their stresses recovered once; every
//     output time is the combination of the pattern fields with the frame's
//     coefficients c(t) (a matrix product over blocks of times), so the cost
//     of more output times is a GEMM, not a solve and a stress recovery.
//     The envelope takes the products chunk of nodes by chunk, in cache;
//     full fields are formed only at the times the callback gets.
//     Patterns whose coefficient is exactly zero at every time are dropped.
//   * step by step (LoadPath::StepByStep; forced for a link with a cosine
//     bearing pressure, which is not linear in the force's direction): each
//     output time's loads solved and recovered.
// The support's six reactions are computed at every step from K u - f and
// must vanish (the loads are self-equilibrated): above `reaction_tolerance`
// of the link's total load (sum of the nodal force magnitudes; on the
// superposition path its bound sum_k |c_k| sum_i |P_ik|, so no f = P c is
// formed per step) it is an Error naming link and time.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_contact.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"

namespace kinetofem::loads {

enum class LoadPath { Auto, Superposition, StepByStep };

struct LinkStressOptions {
  int block_size = 32;  // right-hand sides per block solve
  // Auto: superposition when the link's loads allow it, else step by step.
  // Superposition on a link with a bearing pressure is an Error.
  LoadPath load_path = LoadPath::Auto;
  // Frames whose fields go to the step callback (mask over the frames;
  // empty = all). The envelope always covers every frame.
  std::vector<bool> callback_steps;
  double reaction_tolerance = 1e-6;
  // Only the first `envelope_steps` frames enter the envelope (the rest, e.g.
  // a static pose study solved in the same block, go to the callback only);
  // 0 = all frames.
  std::size_t envelope_steps = 0;
  fem::StaticSolverOptions solver;  // direct, iterative, or chosen by the factor size
};

// The pattern solution of the superposition path: field(t) = fields * c(t).
struct LinkLoadPatterns {
  std::vector<std::string> names;           // of the kept patterns (LinkLoads::pattern_names)
  Eigen::MatrixXd coefficients;             // m x frames
  Eigen::MatrixXd elastic_displacement_m;   // 3 N x m, node-major (x, y, z), rigid-body motion removed
  Eigen::MatrixXd stress_pa;                // 6 N x m, node-major Voigt (fem::StressField order)
};

struct LinkEnvelope {
  Eigen::VectorXd max_von_mises_pa;            // per node
  Eigen::VectorXi max_von_mises_step;          // per node, index into the frames
  Eigen::VectorXd max_displacement_m;          // per node, magnitude
  Eigen::VectorXi max_displacement_step;
  // The critical instant and place.
  double peak_von_mises_pa = 0.0;
  fem::Index peak_von_mises_node = 0;
  int peak_von_mises_step = 0;
  double peak_displacement_m = 0.0;
  fem::Index peak_displacement_node = 0;
  int peak_displacement_step = 0;
  double worst_equilibrium_residual = 0.0;
  double worst_support_reaction = 0.0;  // relative to the total load (sum of |f_i|)
  double max_out_of_plane_moment_nm = 0.0;  // largest moment the pins carry about in-plane axes (LinkLoadResult)
  fem::CholmodStatistics solver;  // on the iterative path: the symbolic analysis only, if any
  bool iterative_solver = false;
  std::string solver_summary;     // fem::LinearStaticAnalysis::solver_summary()
  // Superposition path: the patterns solved (else empty) and how many.
  std::optional<LinkLoadPatterns> patterns;
  // Pins in contact, when analyse_link_over_motion solved them itself (not
  // when the caller gave their history).
  std::optional<LinkContactHistory> contact;
  long solved_right_hand_sides = 0;
  double assembly_seconds = 0.0, solve_seconds = 0.0, recovery_seconds = 0.0;
};

// Called once per frame (or per frame of options.callback_steps), in order,
// with the elastic deformation (rigid-body motion removed, body frame, m) and
// the nodal stresses (Pa; on the superposition path principal_pa is left
// empty: nobody downstream needs it per step).
using StepCallback = std::function<void(std::size_t step, const fem::DisplacementField& elastic_displacement,
                                        const fem::NodalStress& stress)>;

// `supported_model`: the link's FE model with its 3-2-1 support (see
// fem::three_two_one_support); `loads` built for the same mesh.
LinkEnvelope analyse_link_over_motion(const fem::FeModel& supported_model, const LinkLoads& loads,
                                      const std::vector<mech::Frame>& frames, const Log& log,
                                      const LinkStressOptions& options = {},
                                      const StepCallback& on_step = {});

// The same on a factorization made before (of the supported model, which it
// refers to), e.g. one shared with the elastic assembly, so that a part is
// factorized once for both. options.solver is not used. A link with pins in
// contact (LinkLoads::contact_bores) takes `contact`, the contact solved
// before on the same factorization and frames (solve_contact_over_motion),
// or solves it here when it is null; its forces are added as load patterns
// (superposition) or to each step's loads.
LinkEnvelope analyse_link_over_motion(fem::LinearStaticAnalysis& factorized, const LinkLoads& loads,
                                      const std::vector<mech::Frame>& frames, const Log& log,
                                      const LinkStressOptions& options = {},
                                      const StepCallback& on_step = {},
                                      const LinkContactHistory* contact = nullptr);

// The superposition path on a pattern history (the same checks, envelope and
// callback as above); options.load_path and options.solver are not used.
LinkEnvelope analyse_link_over_motion(fem::LinearStaticAnalysis& factorized, const PatternLoadHistory& loads,
                                      const Log& log, const LinkStressOptions& options = {},
                                      const StepCallback& on_step = {});

}  // namespace kinetofem::loads
