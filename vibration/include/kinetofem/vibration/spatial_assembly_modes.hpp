#pragma once
// SpatialAssemblyModes — the natural frequencies and mode shapes of a spatial
// mechanism's elastic assembly (structure/spatial_elastic_assembly.hpp) in
// any pose, from one Craig-Bampton reduction per part
// (vibration/craig_bampton.hpp) made once and, per pose, one small dense
// eigenproblem. The spatial counterpart of AssemblyModes
// (vibration/assembly_modes.hpp), with the same coordinates, constraints,
// part-mode rule and eigen solve (assembly_modes_shared.hpp); what changes is
// that bodies turn about any axis (their poses are rotation matrices) and
// that point masses and rigid bodies have their full rotary inertia.
//
// Coordinates x (the same in every pose): per elastic part, in its body axes,
//   [u_b; q; r]  its interfaces' motions (one distributing coupling per face
//                set the assembly's interfaces use: joints, drives, slide
//                lands and stations, tracked points; then one per point mass
//                on a face no interface uses), its fixed-interface modes and
//                its residual vectors;
// per moving rigid body (a body without a part), its origin's translation
// and rotation (body axes). The ground does not move and has no coordinates.
//
// Per pose, with R_b the body's rotation (body axes -> world) and arm_k the
// interface's reference point from the coordinates' point (body frame), the
// interfaces' world motions are u = U(pose) x, U_k = blockdiag(R_b, R_b)
// transfer(arm_k); the joints and rigid drives hold C U x = 0 (C:
// SpatialElasticAssembly::interface_structure, the statics' own rows). On
// the null space N of C U (orthonormal basis, by QR, rotations scaled by the
// model's characteristic length for the rank decision):
//   (N^T K N) y = w^2 (N^T M N) y,   mode shape x = N y, x^T M x = 1.
// K and M are in body axes and do not change with the pose.
//
// Mass: each part's consistent mass (its mesh and material); a point mass of
// the part (mech::spatial::PointMass: mass and rotary inertia about its
// centre, body axes) rigidly on its mount face's coupling, referred to the
// mass's point: diag(m, m, m) on the translation, m skew terms if the
// coupling sits elsewhere, J on the rotation; a rigid body: its mass, centre
// of mass and full inertia tensor with its point masses
// (mech::spatial::System::effective), as a 6 x 6 on its origin's motion.
//
// Neglected (the pose frozen, as the planar modes): the geometric stiffness
// of the weight, inertia and joint loads; the gyroscopic and centrifugal
// terms of the bodies' angular velocity (omega x J omega, Coriolis); the
// drives' and joints' compliance (every tie is rigid here, as in the
// assembly's statics); the model's springs and dampers (the assembly's only
// springs are its chains, U^T S U added to K as in the planar modes).
//
// Part-mode rule: AssemblyModesOptions, as the planar modes (each part keeps
// every fixed-interface mode up to part_mode_cutoff_hz plus its residual
// vectors; automatic: cutoff_factor x the highest wanted frequency of the
// static reduction over the poses given, an upper bound by Rayleigh-Ritz).
// Each part is reduced on its own direct (CHOLMOD) factorization of the
// assembly's 3-2-1-supported model (SpatialElasticAssembly::supported_model: the
// assembly frees its factors after its set-up), made when the part's
// reduction needs it and freed after (one factor at a time with a given
// cutoff; with the automatic one, every part's K, M and constraint modes are
// kept between the bound and the final reduction).
//
// Ownership: the modes keep a reference to the assembly (its interfaces and
// each pose's constraints), which must outlive them.
//
// SI units: Hz, rad/s; x in m, rad, sqrt(kg) m; loads in N, N m.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/structure/spatial_elastic_assembly.hpp"
#include "kinetofem/vibration/assembly_modes.hpp"

namespace kinetofem::vibration {

class SpatialAssemblyModes {
 public:
  // Reduces every part of `assembly` once; the automatic cutoff is estimated
  // over `poses` (give every pose whose modes will be asked for: the bound
  // holds pose by pose only). Throws Error for bad options, a part of zero
  // density, a rigid moving body without mass, a model that is not the
  // assembly's, an eigen solve that does not converge
  // (vibration::EigenNotConverged names the part).
  SpatialAssemblyModes(const structure::SpatialElasticAssembly& assembly, const mech::spatial::Model& model,
                       const AssemblyModesOptions& options, const std::vector<mech::spatial::Frame>& poses,
                       const Log& log = Log::quiet());
  ~SpatialAssemblyModes();
  SpatialAssemblyModes(SpatialAssemblyModes&&) noexcept;
  SpatialAssemblyModes& operator=(SpatialAssemblyModes&&) noexcept;

  // The lowest options.modes modes of the pose. Error naming the time when
  // fewer coordinates are free than modes wanted.
  PoseModes modes(const mech::spatial::Frame& frame) const;

  Eigen::Index size() const;                 // n = the coordinates x
  const Eigen::MatrixXd& mass() const;       // M_x, n x n (constant)
  const Eigen::MatrixXd& stiffness() const;  // K_x, n x n (constant)
  // Generalized load on x of the frame's loads other than the joints' and
  // drives' (the parts' inertia, weight, point masses and point forces as
  // the assembly's statics take them; the rigid bodies' applied minus
  // inertia loads).
  Eigen::VectorXd load(const mech::spatial::Frame& frame) const;
  // The reduced model's static response to a load on x: x with C U x = 0.
  Eigen::VectorXd static_response(const mech::spatial::Frame& frame, const Eigen::VectorXd& load) const;
  // The tracked point's translation (world axes, m) as rows over x: 3 x n.
  Eigen::MatrixXd point_rows(const std::string& point, const mech::spatial::Frame& frame) const;

  const std::vector<PartReduction>& reductions() const;
  double cutoff_hz() const;          // as used (the same for every part)
  double estimated_fmax_hz() const;  // automatic rule: f_max of the static reduction; else 0
  // The rule in one line: cutoff, f_max of the final modes over the poses
  // seen, the factor achieved.
  std::string check_rule(double highest_frequency_seen_hz) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kinetofem::vibration
