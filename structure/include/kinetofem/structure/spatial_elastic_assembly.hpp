#pragma once
// SpatialElasticAssembly — a spatial mechanism (mech::spatial::Model) in one
// pose (one mech::spatial::Frame) as ONE linear-elastic structure held by the
// ground: quasi-static, small displacements, world axes, measured from the
// rigid configuration of the pose. The spatial counterpart of
// ElasticAssembly (elastic_assembly.hpp), with the same condensation; what
// changes is that bodies turn about any axis (their poses are rotation
// matrices) and the joints hold the components their type's reaction carries
// (mech::spatial::joint_facts). docs/elastic_assembly.md, "Spatial mechanisms".
//
// Model
//   * Bodies with a SpatialPart are elastic (mesh in the body frame), the
//     others rigid; the ground (fixed bodies) does not move.
//   * Interfaces: each end of a joint or motion drive on a body, each land
//     and station of a slide, each tracked point, with 6 components
//     (translation of a reference point and rotation; force and moment). On
//     an elastic part: the distributing (RBE3-like) coupling of the face set
//     its attachment names, reference point = the joint's point on that body
//     (a land: P_i + x h_i; a station: its centre on the slider's axis; a
//     tracked point: the named point). On a rigid body: the body point.
//   * Joint (revolute, prismatic, cylindrical, spherical, universal, fixed):
//     the motion of body_j's interface minus body_i's carried rigidly to P_j
//     is held in the components the joint's reaction carries (joint_facts:
//     forces across the axis f, g and along h when 3; moments about f, g and
//     h when 3, the universal joint's about h_i x h_j), turned into world by
//     body_i's rotation.
//   * Chain (SPEC §1, in the plane normal to h_i): a tension-only axial member
//     from the hinge (P_i) to its tangent point T on the roller (body_j,
//     centre P_j), k = EA / free length (SpatialAssemblyOptions::chains); a
//     slack chain in a pose is an Error naming the time.
//   * Slide (a prismatic joint with a loads::SpatialSlideAttachment on the
//     parts: a sleeve bearing an arm on two lands): at each land the slider
//     (the two stations of its slide face that bracket the land, weighted
//     linearly; a land outside them is an Error naming the time: the slide
//     beyond its stroke) moves with the land across the axis (f, g); at the
//     front land also along h (the slide's motion drive, named by the
//     attachment) and about h. Six rows, the same split the per-part loads
//     make (loads/spatial_link_loads.hpp), so the assembly's land loads are
//     the multibody ones where the structure is statically determinate.
//   * Motion drive on a rotation (angle of f_j from f_i about h_i): holds
//     h . (rotation_j - rotation_i) of its interfaces; on a translation:
//     h . (u_j - u_i) + (h x d) . rotation_i, d = P_j - P_i. Rigidly.
//   * Loads on each part: loads::SpatialLinkLoads WITHOUT its joints, drives
//     and slides (they are internal here): inertia and weight, point masses
//     with rotary inertia, point forces; as fixed load patterns solved once
//     (unit-load superposition). A rigid body's: the multibody frame's
//     applied minus inertia loads, which are minus the sum of its joints' and
//     drives' reactions. Each part's resultant is checked against the same
//     (a load missing from the part, e.g. a spring, or mass properties that
//     are not the mesh's, show there).
//
// Method: as ElasticAssembly's. Per part: K_s with the 3-2-1 support of
// spatial_supported_model, G (3N x 6m), Z_G = K_s^-1 G, F = G^T Z_G (body
// axes, once); Z_p = K_s^-1 P for the load patterns P. Per pose: with Q =
// blockdiag(R, R) of the part's body, u_k = Q F Q^T lambda + Q d + T(arm_k)
// alpha (alpha the body's rigid motion, world), equilibrium sum T^T lambda +
// r = 0, lambda = C^T mu, C u = 0: one small dense system, scaled and solved
// by full-pivoting LU. A rank-deficient system is an Error naming the bodies
// and rows in its kernel (a mechanism, not a structure).
//
// SI units: m, rad, N, N m, Pa.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/structure/elastic_assembly.hpp"
#include "kinetofem/structure/spatial_part.hpp"

namespace kinetofem::structure {

// A point whose elastic displacement, compliance and split are reported
// (the gripper point M). On an elastic part: the coupling of `face_set`.
struct SpatialAssemblyPoint {
  std::string name;
  std::string body;
  std::string point = "origin";  // named point of the body (body frame)
  std::string face_set;          // elastic part: the face set whose coupling carries the point
};

struct SpatialAssemblyOptions {
  std::vector<SpatialAssemblyPoint> points;
  std::vector<ChainMember> chains;  // the EA of every chain of the mechanism
  fem::StaticSolverOptions solver;
  // |resultant of a part's loads - its body's applied minus inertia loads|
  // relative to their size; above: Error. Infinity: no check.
  double load_check_tolerance = 1e-6;
  // Pivots below this fraction of the largest (scaled system) count as zero.
  double rank_tolerance = 1e-10;
  bool recover_stress = true;  // von Mises field of every part
  // Per tracked point: its compliance and the split of its displacement
  // into the parts' contributions (unit-load method).
  bool unit_load_split = true;
};

// What a joint (or slide, its drive's axial force included) applies on each
// of its bodies: world axes, moments about the joint's point on that body.
struct SpatialJointLoad {
  std::string joint;
  std::string body_i, body_j;
  Eigen::Vector3d point_i_m = Eigen::Vector3d::Zero(), point_j_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_on_i_n = Eigen::Vector3d::Zero(), moment_on_i_nm = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_on_j_n = Eigen::Vector3d::Zero(), moment_on_j_nm = Eigen::Vector3d::Zero();
};

struct SpatialDriveLoad {
  std::string drive;
  double effort = 0.0;  // torque N m about h (force N along it) on body_j
};

struct SpatialPoseSolution {
  double t = 0.0;
  std::vector<BodyMotion> bodies;        // moving bodies, model order
  std::vector<PartField> parts;          // elastic parts, in the order given
  std::vector<SpatialJointLoad> joints;  // model joint order
  std::vector<SpatialDriveLoad> drives;  // motion drives not taken by a slide, model order
  std::vector<ChainResult> chains;       // model joint order
  std::vector<PointResult> points;       // options.points order (contributions: "part.<body>", "chain.<c>")
  int unknowns = 0, rank = 0;
  double relative_residual = 0.0;  // of the scaled dense system
  double max_displacement_m = 0.0;
  std::string max_displacement_body;

  // Throw Error when the name is absent. Not on a temporary.
  const PartField& part(const std::string& body) const&;
  const SpatialJointLoad& joint(const std::string& name) const&;
  const PointResult& point(const std::string& name) const&;
  const PartField& part(const std::string&) const&& = delete;
  const SpatialJointLoad& joint(const std::string&) const&& = delete;
  const PointResult& point(const std::string&) const&& = delete;
};

// An interface of the assembly (interfaces() order) and its place.
struct SpatialInterfaceInfo {
  std::string body;
  std::string name;      // "joint '<j>'", "drive '<d>'", "slide '<j>' front land", "point '<p>'", ...
  std::string face_set;  // elastic part; empty on a rigid body
  Eigen::Vector3d reference_body_m = Eigen::Vector3d::Zero();  // body frame
};

class SpatialElasticAssembly {
 public:
  // Sets every part up (factorization, interface and load-pattern solves).
  // Throws Error naming the part, joint, drive or point for: a part of no
  // body or of the ground, two parts of one body, a joint or drive on a part
  // that names no face set for it, a chain joint, a tracked point of no body
  // or on a part without its face set, a missing face set.
  // `factorized`: empty, or per part (in order) a factorization of the part
  // with the support of spatial_supported_model, lent by the caller (e.g.
  // shared with the per-part stress stage: one factorization per part); it
  // is used during the construction only.
  SpatialElasticAssembly(const std::vector<SpatialPart>& parts, const mech::spatial::Model& model,
                         SpatialAssemblyOptions options = {}, const Log& log = Log::quiet(),
                         const std::vector<fem::LinearStaticAnalysis*>& factorized = {});
  ~SpatialElasticAssembly();
  SpatialElasticAssembly(SpatialElasticAssembly&&) noexcept;
  SpatialElasticAssembly& operator=(SpatialElasticAssembly&&) noexcept;

  // One pose (a frame of the model given: the spatial core's output).
  // Throws Error naming the time for a mechanism (rank-deficient system), a
  // slide beyond its stroke, or a part's loads that disagree with its body.
  SpatialPoseSolution solve(const mech::spatial::Frame& frame);
  std::vector<SpatialPoseSolution> solve(const std::vector<mech::spatial::Frame>& frames);

  std::vector<SpatialInterfaceInfo> interfaces() const;
  // The pose's constraints and springs (InterfaceStructure of
  // elastic_assembly.hpp, over interfaces()): the joints', slides' and
  // drives' rows (every one rigid) and the chains' springs, S = sum k g^T g
  // (g: the chain's elongation per interface motion, k = EA / free length;
  // the modes of the assembly use the rows alone). Throws Error like solve()
  // for a frame of another mechanism, a slide beyond its stroke or a chain
  // whose hinge lies within its roller.
  InterfaceStructure interface_structure(const mech::spatial::Frame& frame) const;
  // The point masses each part carries and their mount face sets
  // (attachments.point_masses), and the rigid bodies: for the modes.
  const std::vector<SpatialPart>& parts() const;
  // Flexibility G^T K_s^-1 G of the part of `body` over its interfaces
  // (interfaces() order of that body's), body axes; 6m x 6m.
  const Eigen::MatrixXd& flexibility(const std::string& body) const;
  // The part's 3-2-1-supported model (what its mesh, support and fields refer to).
  const fem::FeModel& supported_model(const std::string& body) const;
  // What a pose's CalculiX deck needs (calculix_assembly_export.hpp), the
  // part of `body` (Error if it has none): its interface columns G (3N x 6m,
  // body axes, interfaces() order of the body's interfaces; the reference
  // point's motion is G^T u, a load [F; M] at it enters the nodes as
  // G [F; M]) and its nodal loads in the pose (3N, N, body axes: inertia,
  // weight, point masses and forces; the joints', drives' and slides' loads
  // are the interfaces'), what solve() applies.
  const Eigen::MatrixXd& interface_columns(const std::string& body) const;
  Eigen::VectorXd part_loads(const std::string& body, const mech::spatial::Frame& frame) const;
  // Per moving body (model order, the ground skipped): the multibody frame's
  // applied minus inertia loads, world axes, force N and moment N m about the
  // body's origin (a rigid body's loads in solve()).
  std::vector<Vector6d> body_loads(const mech::spatial::Frame& frame) const;
  double setup_seconds() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kinetofem::structure
