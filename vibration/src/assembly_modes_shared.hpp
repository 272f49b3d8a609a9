#pragma once
// What the modes of the planar and of the spatial elastic assembly share
// (assembly_modes.cpp, spatial_assembly_modes.cpp; the method is in
// vibration/assembly_modes.hpp): a part's Craig-Bampton interfaces, one per
// face set, with the point masses they carry; the map U(pose) from the
// coordinates x to the interfaces' world motions; the null space of the
// pose's constraints and the small dense eigenproblem on it; the part-mode
// rule with its automatic cutoff.
//
// Coordinates: per interface 6 (translation m, rotation rad) in its part's
// (or rigid body's) body axes; world axes after U. Masses in kg, kg m, kg m^2.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/mesh.hpp"
#include "kinetofem/structure/rigid_motion.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"
#include "kinetofem/vibration/craig_bampton.hpp"

namespace kinetofem::vibration::detail {

using structure::detail::Matrix6d;

// Mass matrix of a rigid mass m on (translation, rotation) of a point O, in
// the axes O's coordinates are given in, with the mass's centre at c from O:
// the centre moves by t + w x c = [I, -skew(c)] (t, w). Rotary inertia is
// added to the lower right block by the caller (about the centre, the same
// axes).
Matrix6d point_mass_6x6(double m, const Eigen::Vector3d& c);

// One Craig-Bampton interface of a part per face set: the assembly's
// interfaces on the same face set move rigidly with it (the distributing
// coupling's motion at another reference point is the rigid transfer of its
// motion at the first), and a point mass on its mount face is a 6 x 6 rigid
// mass on it.
struct CbInterface {
  std::string name, face_set;
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // body frame, m
  Eigen::MatrixXd columns;                              // 3N x 6 (coupling_interface)
  Matrix6d mass = Matrix6d::Zero();                     // point masses carried, on its 6 coordinates
};

// The interface of `face_set` in `interfaces`, or -1.
int find_face_interface(const std::vector<CbInterface>& interfaces, const std::string& face_set);

// Adds an interface of the assembly (`name` at `reference` on `face_set`,
// its coupling's 6 columns) to the part's: a new CbInterface unless the face
// set has one, whose columns its own must then be (rigidly transferred; an
// Error naming the part and both otherwise).
void add_face_interface(std::vector<CbInterface>& interfaces, const std::string& label, const std::string& name,
                        const std::string& face_set, const Eigen::Vector3d& reference, const Eigen::MatrixXd& columns);

// A point mass (mass_kg, its rotary inertia about its centre in the part's
// body axes, kg m^2) at `reference` (body frame) on its mount face: carried
// by the face's CbInterface, made (a coupling of the face at the mass's
// point) when the face has none yet.
void carry_point_mass(std::vector<CbInterface>& interfaces, const fem::Mesh& mesh, const std::string& face_set,
                      const Eigen::Vector3d& reference, const std::string& name, double mass_kg,
                      const Eigen::Matrix3d& inertia_kgm2);

// Where an interface of the assembly sits in x.
struct InterfaceMap {
  int body_index = -1;
  int part = -1;            // elastic: its part; -1: rigid
  Eigen::Index column = 0;  // first of the 6 coordinates in x it moves with (its coupling's; a rigid body's)
  Eigen::Vector3d reference = Eigen::Vector3d::Zero();  // body frame
  Eigen::Vector3d arm = Eigen::Vector3d::Zero();        // from those coordinates' point to the reference, body frame
};

// U(pose), 6M x n: interface k's world motion = blockdiag(R, R) transfer(arm_k)
// times its 6 coordinates, R = body_rotation[its body] (body axes -> world).
Eigen::MatrixXd interface_map(const std::vector<InterfaceMap>& map, const std::vector<Eigen::Matrix3d>& body_rotation,
                              Eigen::Index n);

// An orthonormal basis of the null space of A diag(scale) (column-pivoting
// QR of its transpose, threshold 1e-10), scaled back: N = diag(scale) Q_2, so
// A N = 0. `scale` makes rotations commensurate with translations for the
// rank decision (1 / length on rotation coordinates).
Eigen::MatrixXd null_space_basis(const Eigen::MatrixXd& A, const Eigen::VectorXd& scale);

// The lowest `count` modes of Kc y = w^2 Mc y (Kc = N^T K N, Mc = N^T M N on
// the basis N), dense; mode shapes x = N y with x^T M x = 1. Error naming
// the time when Mc is not positive definite.
PoseModes modes_on_basis(Eigen::MatrixXd Kc, Eigen::MatrixXd Mc, const Eigen::MatrixXd& N, int count, double t);

// Option checks shared by both (Error naming the option).
void check_options(const AssemblyModesOptions& options, size_t poses);

// The part-mode rule (vibration/assembly_modes.hpp) over `parts` parts
// reduced in one pass each (CraigBamptonReducer), with the caller's steps:
struct PartRuleSteps {
  size_t parts = 0;
  // The part's reducer (K, M; no solve).
  std::function<CraigBamptonReducer(size_t)> make_reducer;
  // The part's factor lent for its reduce() calls, and given back.
  std::function<void(size_t)> borrow, give_back;
  // The options of part p's reduction from the rule's (its label, solver).
  std::function<CraigBamptonOptions(size_t, const CraigBamptonOptions&)> part_options;
  // Keeps part p's reduced model (the static one first, with the automatic
  // cutoff, then the final one).
  std::function<void(size_t, CraigBamptonModel)> take;
  // After every part's static reduction is taken: the highest frequency
  // wanted over the poses of the reduced model so made (Hz).
  std::function<double()> static_fmax_hz;
};

struct PartRuleResult {
  double cutoff_hz = 0.0;         // as used
  double fmax_estimate_hz = 0.0;  // automatic: the static reduction's bound; else 0
};

// Given cutoff: every part reduced once. Automatic (0): the static
// reduction of every part (set-up solves from the last part to the first),
// the bound f_max, then the final reduction from the first part (whose
// factor serves both without a second lend).
PartRuleResult reduce_parts_by_rule(const AssemblyModesOptions& options, size_t poses, const PartRuleSteps& steps,
                                    const Log& log);

// The rule in one line (check_rule of both).
std::string format_rule(const AssemblyModesOptions& options, double cutoff_hz, double highest_frequency_seen_hz);

}  // namespace kinetofem::vibration::detail
