#pragma once
// RigidBoreCondensation — the KINEMATIC (rigid-bore, RBE2-like) coupling of
// a part's interfaces, condensed exactly onto them in the same form as the
// distributing coupling of ElasticAssembly (docs/elastic_assembly.md), so
// that swapping the coupling type swaps the matrices G, Z_G, F and adds one
// load correction per block of poses.
//
// Frame and units: the part's body frame; m, N, N m, rad. The model (B u = T q
// on each bore's face nodes), the condensation (F_SS, F_r, H, D, W and the
// load correction c(f)), why it is exact, held face DoFs, several interfaces
// on one bore, and the cost: docs/elastic_assembly.md, "The rigid-bore coupling".
//
// Ownership: the analysis and the mesh are referenced, not copied; both
// must outlive this object. correction() solves with the analysis (non-const).
// The log is used during construction only (one summary line).
//
// Usage
//   fem::LinearStaticAnalysis analysis(supported_model, log, options);
//   RigidBoreCondensation bores(analysis, supported_model.mesh,
//                               {{"x0", {0, 0, 0}}, {"x1", {0.3, 0, 0}}}, log);
//   G = bores.loads(); Z_G = bores.load_displacement(); F = bores.flexibility();
//   Z_f = K_s^-1 f (block);  Z_f += bores.correction(Z_f);
//   d = G^T Z_f;  field = Z_G lambda + Z_f (+ rigid motion).
#include <string>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::structure {

// One interface: the face set of its bore and its reference point (body frame, m).
struct RigidBoreInterface {
  std::string face_set;
  Eigen::Vector3d reference_m = Eigen::Vector3d::Zero();
};

struct RigidBoreOptions {
  int chunk_columns = 64;  // unit columns of F_SS per block solve (>= 1)
};

struct RigidBoreStatistics {
  int interfaces = 0, bores = 0;
  long face_nodes = 0;      // over all bores (distinct)
  long free_face_dofs = 0;  // k_f: the size of F_SS
  long held_face_dofs = 0;  // face DoFs held by the support (zero eigenvalues of F_r)
  long setup_solves = 0;    // columns solved at setup: k_f + 6 b
  long correction_solves = 0;  // columns solved by correction() so far
  double face_solve_seconds = 0.0;       // the k_f solves for F_SS
  double factor_seconds = 0.0;           // Cholesky of F_SS and the 6b x 6b algebra
  double interface_solve_seconds = 0.0;  // Z_D (6 b solves) and D, F_r
  double setup_seconds = 0.0;            // all of the above
  double correction_seconds = 0.0;       // correction() so far
  double working_bytes = 0.0;            // peak dense storage of the setup (estimate)
  // |D^T Z_D - F_r|_max / |F_r|_max: F_r from the small algebra against the
  // solved columns (round-off of the face solves).
  double consistency = 0.0;
};

class RigidBoreCondensation {
 public:
  // `analysis`: the part with its support, factorized; `mesh`: its mesh (the
  // analysis's model's). Throws Error naming the face set for a missing or
  // empty face set, two face sets that share a node (naming both and the
  // node), a bore that cannot fix a rigid motion (collinear nodes), supports
  // that prescribe a nonzero value or hold more of a bore than a rigid
  // motion allows, or a mesh that is not the analysis's.
  RigidBoreCondensation(fem::LinearStaticAnalysis& analysis, const fem::Mesh& mesh,
                        std::vector<RigidBoreInterface> interfaces, const Log& log = Log::quiet(),
                        RigidBoreOptions options = {});

  // D (3N x 6m, N per unit load): nodal loads of unit interface loads,
  // columns (Fx, Fy, Fz, Mx, My, Mz) per interface in the order given. Takes G's place.
  const Eigen::MatrixXd& loads() const { return loads_; }
  // Z_D = K_s^-1 D (3N x 6m, m per unit load). Takes Z_G's place.
  const Eigen::MatrixXd& load_displacement() const { return load_displacement_; }
  // F_r (6m x 6m, symmetric, m/N, rad/(N m), ...). Takes F's place.
  const Eigen::MatrixXd& flexibility() const { return flexibility_; }

  // c = -K_s^-1 B^T W B Z_f (3N x P) for load displacements Z_f (3N x P,
  // one column per pose): add it to Z_f. One block solve.
  Eigen::MatrixXd correction(const Eigen::MatrixXd& load_displacement_block);

  // The bores' reactions on the part as nodal loads (3N x P, N, nonzero on
  // face nodes only) for interface loads lambda (6m x P) and load
  // displacements Z_f (3N x P): B^T r, r = H lambda - W d_S, with the
  // reactions of the DoFs held by the support included. Their resultant
  // about a bore's reference is the bore's load, and K_s^-1 (f + them) is
  // the field Z_D lambda + Z_f + c (for checks and reaction output).
  Eigen::MatrixXd face_loads(const Eigen::MatrixXd& interface_loads, const Eigen::MatrixXd& load_displacement_block) const;

  // Face nodes of interface l's bore (sorted).
  const std::vector<fem::Index>& face_nodes(int interface) const;
  const std::vector<RigidBoreInterface>& interfaces() const { return interfaces_; }
  const RigidBoreStatistics& statistics() const { return stats_; }
  // One line for logs: bores, face nodes, solves and times.
  std::string summary() const;

 private:
  struct Bore {
    std::string face_set;
    Eigen::Vector3d reference_m = Eigen::Vector3d::Zero();  // its first interface's
    std::vector<fem::Index> nodes;
  };

  fem::LinearStaticAnalysis& analysis_;
  const fem::Mesh& mesh_;
  std::vector<RigidBoreInterface> interfaces_;
  std::vector<int> bore_of_interface_;
  std::vector<Bore> bores_;
  std::vector<fem::Index> free_dofs_, held_dofs_;  // global DoFs (3 node + c) of the face nodes
  Eigen::MatrixXd t_free_, t_held_;                // T_f (k_f x 6b), T_p (k_p x 6b)
  Eigen::MatrixXd transfer_;                       // X (6m x 6b): q = X q_b
  Eigen::VectorXd face_scale_;                     // Jacobi scaling of F_SS
  Eigen::LLT<Eigen::MatrixXd> face_factor_;        // of the scaled F_SS
  Eigen::MatrixXd reaction_free_;                  // H_b (k_f x 6b)
  Eigen::MatrixXd reaction_held_;                  // E_b (k_p x 6b): held DoFs' reactions
  Eigen::MatrixXd loads_, load_displacement_, flexibility_;
  RigidBoreStatistics stats_;

  void collect_bores();
  void number_face_dofs();
  Eigen::MatrixXd face_flexibility(int chunk_columns);
  void condense(const Eigen::MatrixXd& face_flexibility);
  void interface_columns();
  Eigen::MatrixXd solve_face(const Eigen::MatrixXd& rhs) const;  // F_SS^-1 rhs
  Eigen::MatrixXd free_face_reactions(const Eigen::MatrixXd& load_displacement_block) const;  // W B Z_f
};

// Support candidates off the bores: all nodes of the mesh except those of
// the face sets given, so that fem::three_two_one_support keeps every face
// DoF free and F_r positive definite. Throws Error for a missing face set.
std::vector<fem::Index> rigid_bore_support_candidates(const fem::Mesh& mesh, const std::vector<std::string>& face_sets);

}  // namespace kinetofem::structure
