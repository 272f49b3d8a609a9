#pragma once
// The pins of one link in frictionless, unilateral contact with its bores,
// solved at every output time of the motion on the link's one
// factorization (derivation and choices: docs/contact.md).
//
// A link whose joints have BoreLoad::Contact (LinkLoads::contact_bores) is
// loaded at time t by its fixed load patterns, P c'(t), where c' is c of
// LinkLoads::coefficients_at with each contact bore's coupling components
// normal to the pin axis (F_x, F_y, M_x, M_y about the bore's centroid)
// removed, plus the contact pressure p(t) on the bores' corner nodes, whose
// nodal forces are F p (F = N M, fem::BoreContactSurface). The removed
// components are what the contact must carry: E^T p = (F_x, F_y, M_x, M_y)
// per bore. With the part's condensed operators, made once from its
// factorization by m solves (m: the corner nodes of all its bores),
//     A = F^T K^-1 F   (m x m),   D = F^T K^-1 P   (m x patterns),
// each pose is fem::solve_contact with the weighted free gap
// b = clearance * area + D c'(t): a QP of size m, whose cost does not
// depend on the mesh (only on m). The bores of one link are solved
// together (they deform the same link).
// The support of the factorized model must not hold a contact node
// (pipeline's 3-2-1 support leaves them out).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::loads {

// One bore's contact over the motion.
struct BoreContactHistory {
  std::string joint;
  fem::BoreContactSurface surface;
  double clearance_m = 0.0;
  Eigen::MatrixXd pressure_pa;                 // corners x frames, Pa
  std::vector<fem::BoreContactState> states;   // per frame
  std::vector<Eigen::Vector4d> carried;        // per frame: the resultant it had to carry (F_1, F_2 N; M_1, M_2 N m)
};

// A link's contact over the motion: the contact forces and what remains on
// the load patterns, with the solver's record.
struct LinkContactHistory {
  std::vector<BoreContactHistory> bores;
  Eigen::MatrixXd pressure_pa;              // m x frames (the bores' corners stacked in order), Pa
  Eigen::MatrixXd remaining_coefficients;   // pattern_count x frames: c'(t)
  double worst_penetration_m = 0.0;         // largest mean overlap at a corner left by the solver (its tolerance)
  double worst_resultant_error = 0.0;       // |E^T p - r| / |r| (the resultant carried exactly)
  int most_active_set_steps = 0;
  int interior_point_poses = 0;             // poses that needed the fallback
  double set_up_seconds = 0.0, solve_seconds = 0.0;
  double condensed_bytes = 0.0;             // A and D, per link

  Eigen::Index contact_corners() const { return pressure_pa.rows(); }
  // Adds the nodal forces F p of corner pressures (m x k, all bores) to
  // forces (3 N x k).
  void add_forces(const Eigen::Ref<const Eigen::MatrixXd>& pressure_pa, Eigen::Ref<Eigen::MatrixXd> forces) const;
};

// Solves every frame's contact (frames in order; each starts from the last
// one's contact set). `factorized`: the link's supported model, factorized.
// Throws Error naming the link, its contact joints and the time when a pose
// does not converge, and when a contact node is held by the support.
LinkContactHistory solve_contact_over_motion(fem::LinearStaticAnalysis& factorized, const LinkLoads& loads,
                                             const std::vector<mech::Frame>& frames, const Log& log,
                                             const fem::ContactSolverOptions& options = {});

}  // namespace kinetofem::loads
