#pragma once
// ElasticAssembly — a planar linkage in one pose (one mech::Frame) as ONE
// linear-elastic structure held by the ground: quasi-static, small
// displacements, in world axes, measured from the rigid configuration of the
// pose. What SPEC §3 calls the "total deformation" of the assembly (the
// bending of every link plus what the joints, the chain and the drive let
// move), where the per-link analysis (pipeline/part_stress.hpp) gives each
// link's deformation relative to its own rigid motion. docs/elastic_assembly.md.
//
// Model
//   * Bodies with a Part are elastic (mesh in the body frame), the
//     others rigid; the ground is fixed. A Part of the ground (the frame,
//     Part::held_face) is elastic and held on that face set, its
//     foundation: its interfaces (the ground joints' bores, the drives'
//     ground sides, a chain hinge on one of its faces) move by G^T u of the
//     held model, with no rigid motion and no equilibrium rows (the
//     foundation takes the resultant), and its loads (its weight) are not
//     checked against a multibody body (the ground has none).
//   * Interfaces. Each end of a joint on a body, each end of a motion drive
//     and each tracked point is an interface with 6 components (translation
//     of a reference point and rotation; force and moment). On an elastic
//     part it is the distributing (RBE3-like) coupling of a face set
//     (fem::DistributingCoupling): its motion is G^T u, its load enters as G
//     [F; M]. Reference point: the joint point in the body frame with z =
//     the face set's centroid z (drives: the face set's centroid). On a rigid
//     body it is the body point, moving with the body.
//   * Revolute joint: the two interfaces move together in the three
//     translations and the rotations about world x and y (a rigid pin from
//     one reference point to the other); the rotation about z is free, so the
//     pin carries no moment about z. To the ground: those five held.
//     Bores at different z (parts in their own planes: reference points more
//     than pin_offset_tolerance x the model's characteristic length apart in
//     z; the rigid ground's side at z = 0): the pin is an elastic member
//     instead, a Timoshenko beam from one reference point to the other with
//     its twist released (structure/pin_member.hpp; PinOption), a spring of S.
//     Fixed joint: all six held.
//   * Prismatic joint (a slider in its guide, mech::AssemblyTie::Slide):
//     the slider's interface (body_j: the joint point, or its face set's
//     coupling) follows the guide carried rigidly across in the translations
//     across the slide (in the plane and along z) and the three rotations;
//     the translation along the slide axis (axis_i turned into world) is
//     free, held by a displacement drive on it if any. On the rigid ground or
//     a rigid guide the guide side is the joint point. On an elastic guide
//     (body_i with a part) the guide side is the guide's face set where the
//     slider sits: the face set is cut into windows one contact length long
//     (SlideOption) centred on stations along the axis, each window an
//     interface, and in a pose the slider is tied to the two stations that
//     bracket its position, weighted linearly (a slide outside the stations,
//     beyond the guide, is an Error naming the time).
//   * Motion drive on an angle (theta_j - theta_i): holds the relative
//     rotation about z of its interfaces (the part's DriveAttachment face set)
//     rigidly (default) or through a torsional stiffness k_d (N m/rad). On a
//     displacement (s = u_i . (r_Pj - r_Pi), a slider's drive): holds s at
//     its interfaces (the coordinate's points) rigidly or through an axial
//     stiffness k_s (N/m), the drive train's.
//   * Transmission (mech::Transmission, s_out = ratio s_in + c): its
//     interfaces are the four ends of its two coordinates (the parts'
//     TransmissionAttachment face sets, at their centroids); it holds
//     ds_out - ratio ds_in (the relative rotations about z) rigidly or
//     through a torsional stiffness on the output coordinate
//     (TransmissionMember: a belt's spans, a gear pair's mesh).
//   * Chain (mech::JointType::Chain, hinge on the ground): a tension-only
//     axial member from the hinge to its tangent point T on the roller
//     (mech::chain_tangent), k = EA / free length; it acts on the roller's
//     interface (reference: the roller centre) at T. Its tension in the pose
//     must be positive (else Error: slack).
//   * Loads on each part: those of loads::LinkLoads at the frame WITHOUT the
//     joint reactions and without the efforts of the motion drives (they are
//     internal here): d'Alembert inertia and weight, point masses, force-drive
//     efforts, springs, point forces. A rigid body's: the multibody model's
//     applied loads minus its inertia. Each part's load resultant is checked
//     against its multibody body's (a load attachment missing from the part,
//     or mass properties that are not the mesh's, show there).
//
// Method (one factorization per part, reused for every pose)
//   Per part: K_s with a 3-2-1 support (fem::three_two_one_support), the 6m
//   interface columns G, Z_G = K_s^-1 G and the flexibility F = G^T Z_G (body
//   axes, once). Per pose: f_loads, Z_f = K_s^-1 f_loads (one block solve for
//   all poses), d = G^T Z_f. Interface displacements u = F lambda + d + R alpha
//   (R: the interfaces' rigid-body modes; alpha: the part's rigid motion
//   relative to its support), equilibrium R^T lambda + resultant(f_loads) = 0.
//   Rotated into world axes, with the joints' compatibility C u = 0, lambda =
//   C^T mu - S u (S: chain and drive springs, elastic pins), they form one small dense
//   system in (u, lambda, alpha, mu), solved by full-pivoting LU after
//   scaling. A rank-deficient system is an Error naming the joint (or drive)
//   whose rotation nothing holds, or the joints of a statically
//   indeterminate loop of rigid bodies. Fields: u = Z_G lambda + Z_f +
//   rigid(alpha), rotated to world axes.
//   Pins in contact (a part's joint attachment with loads::BoreLoad::
//   Contact): frictionless, unilateral contact of a rigid round pin with
//   that bore, over a radial clearance (docs/contact.md, "In the elastic
//   assembly"). The joint's tie (or its elastic pin's end) is released at the
//   bore across the axis (x, y and the tilts about x and y, body axes): the
//   pin's motion delta in the bore is free, and the contact pressure p >= 0
//   on the bore's corner functions (fem::BoreContactSurface) carries what the
//   tie carried there; the force along the axis and the rotation about it
//   stay as they were. Per pose, on the factorized pose system of the
//   couplings: p's and delta's responses (one solve of the small system per
//   corner and per released component), then one QP in p
//   (fem::solve_contact: A = H^T K^-1 H plus the structure's response, H the
//   pressure's nodal forces less their resultant on the bore's coupling,
//   E^T p + C delta = r with C the structure's stiffness against delta,
//   nonzero when it is statically indeterminate); reciprocity of the two
//   responses is checked. Each part costs m solves once (m: its contact
//   corners) and one block solve of its contact forces per block of poses.
//   The poses' contact sets start from the last pose's.
//   Unit-load superposition (AssemblyOptions::superpose_loads, default):
//   f_loads = P c(t) with the fixed load patterns P of loads::LinkLoads, so
//   Z_f = (K_s^-1 P) c and the stress (S_G lambda + S_p c) come from
//   columns solved and recovered once; a pose costs no part solve.
//
// SI units: m, rad, N, N m, Pa.
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/structure/part.hpp"
#include "kinetofem/structure/pin_member.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/bore_contact.hpp"
#include "kinetofem/solver/static_analysis.hpp"

namespace kinetofem::structure {

using Vector6d = Eigen::Matrix<double, 6, 1>;
inline constexpr double kRigid = std::numeric_limits<double>::infinity();

// The axial stiffness of a chain of the model (every chain needs one).
struct ChainMember {
  std::string chain;               // joint name (mech::JointType::Chain)
  double axial_stiffness_n = 0.0;  // EA, N (> 0); k = EA / free length in the pose
};

// How a motion drive holds its coordinate (drives not listed: rigidly). The
// stiffness of the other coordinate type than the drive's is an Error.
struct DriveHold {
  std::string drive;                               // motion drive name
  double torsional_stiffness_nm_per_rad = kRigid;  // angle drive: >= 0; kRigid: a constraint
  double axial_stiffness_n_per_m = kRigid;         // displacement drive: >= 0; kRigid: a constraint
};

// A transmission of the mechanism (mech::Transmission: s_out = ratio s_in +
// c) in the assembly: its twist g = ds_out - ratio ds_in (rad, the
// coordinates' relative rotations about z of its interfaces) is held
// rigidly (transmissions not listed) or stores k g^2 / 2, k on the output
// coordinate (docs/transmissions.md: a belt's k from its spans' EA, a gear
// pair's from its mesh stiffness).
struct TransmissionMember {
  std::string transmission;
  double torsional_stiffness_nm_per_rad = kRigid;  // >= 0
  // A belt or chain (radius_m > 0: its output pulley's): the spans'
  // tension from the output moment M, T0 +- M / (2 r) with both spans taut
  // (preload T0 > 0: a span that would drop to zero goes slack, an Error
  // naming the time and the span), or M / r on one span (T0 = 0, a chain).
  double radius_m = 0.0;
  double preload_n = 0.0;
};

// The guide of a prismatic joint whose body_i has a part (an elastic
// guide); joints not listed take the defaults. Naming a joint that is not
// prismatic, or whose guide is rigid, is an Error.
struct SlideOption {
  std::string joint;
  // Length of the slider's bearing on the guide (m): the load spreads over a
  // window this long on the guide's face set. 0: the extent along the axis
  // of the slider's face set (a slider with a part), else required.
  double contact_length_m = 0.0;
  // Distance between the stations (m); 0: a quarter of the contact length.
  double station_spacing_m = 0.0;
};

// The pin of a revolute joint whose bores sit at different z (an elastic
// member; joints not listed take the defaults). Naming a joint that is not
// revolute is an Error; one whose bores sit at the same z keeps the rigid
// tie (nothing bends that the tie leaves out: a note says so) and its
// diameter is only checked against the bores.
struct PinOption {
  std::string joint;
  // 0: the diameter of the smaller of its bores on elastic parts (twice the
  // mean distance of the face set's nodes from the joint's axis). Larger
  // than a bore it passes through: Error.
  double diameter_m = 0.0;
  // Absent: the material of a part it joins (the case's).
  std::optional<double> youngs_modulus_pa, poisson_ratio;
};

// A point of the assembly whose elastic displacement, split and compliance
// are reported (e.g. the gripper point H; a case's [[assembly_point]]).
struct AssemblyPoint {
  std::string name;
  std::string body;
  std::string point = "origin";  // named point of the body (body frame)
  std::string face_set;          // elastic part: the face set whose coupling carries the point
};

// How an interface's reference point is tied to its face set on an elastic
// part. Distributing (RBE3-like, fem::DistributingCoupling): the reference
// moves with the face's weighted mean motion and the face deforms freely; it
// loads the part by statically equivalent forces only. RigidBore
// (kinematic): every node of the face moves rigidly with the reference, as
// under a pin pressed into the bore; stiffer locally. docs/elastic_assembly.md
// says why Distributing is the default and how much the choice moves the result.
enum class BoreCoupling { Distributing, RigidBore };
// "distributing", "rigid_bore".
const char* name_of(BoreCoupling coupling);

struct AssemblyOptions {
  BoreCoupling coupling = BoreCoupling::Distributing;
  std::vector<ChainMember> chains;
  std::vector<DriveHold> drives;
  std::vector<AssemblyPoint> points;
  std::vector<PinOption> pins;
  std::vector<SlideOption> slides;
  std::vector<TransmissionMember> transmissions;
  // A revolute joint's bores more than this fraction of the model's
  // characteristic length apart in z get an elastic pin; closer: the rigid
  // tie (bit-identical to a model whose parts all sit in one plane).
  double pin_offset_tolerance = 1e-3;
  fem::StaticSolverOptions solver;
  // |resultant of a part's loads - its multibody body's applied minus inertia
  // loads| relative to their size; above: Error. Infinity: no check.
  double load_check_tolerance = 1e-6;
  // Pivots below this fraction of the largest (scaled system) count as zero.
  double rank_tolerance = 1e-10;
  bool recover_stress = true;  // von Mises field of every part
  // Per part and pose, its nodal stress tensor too (PartField::stress_pa, or
  // with superposed loads PartField::stress_coefficients of the part's
  // stress_patterns()), e.g. for a fatigue check on the assembly's stress
  // (parts in several planes). Needs recover_stress.
  bool keep_part_stress = false;
  // Per tracked point: its compliance (unit forces at it) and the split of
  // its displacement into the contributions of the parts, chains and
  // compliant drives (the unit-load method; three more right-hand sides of
  // the small system per point and pose).
  bool unit_load_split = true;
  // Each part's loads as loads::LinkLoads' load patterns, solved (and their
  // stresses recovered) once: a pose costs matrix products with the pattern
  // coefficients, not a solve and a stress recovery per part. Exact (to
  // round-off); false: one solve per pose (the reference in the tests).
  bool superpose_loads = true;
  // Output times whose fields analyse_assembly_over_motion writes (mask over
  // the motion; empty = all); histories and envelopes cover every one.
  std::vector<bool> field_steps;
  // The pins in contact: their QP's solver.
  fem::ContactSolverOptions contact;
};

// Tag: construct the topology and checks only; each part is set up later
// with its factor lent (ElasticAssembly::set_up_part).
struct PartsLentOneByOne {};

// Rigid motion alpha of a moving body (world axes): translation of its frame
// origin and rotation. For an elastic part, relative to its 3-2-1 support.
struct BodyMotion {
  std::string body;
  bool elastic = false;
  Eigen::Vector3d translation_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();
};

// A pin in contact with a bore of an elastic part in one pose.
struct BoreContactResult {
  std::string joint, body, face_set;
  double clearance_m = 0.0;                    // radial
  Eigen::VectorXd pressure_pa;                 // per corner (fem::BoreContactSurface order), >= 0
  fem::BoreContactState state;                 // peak, its angle from the part's x axis, arc, force (body axes)
  // The pin's motion in the bore relative to the bore's coupling reference
  // (body axes): x, y (m), rotations about x, y (rad).
  Eigen::Vector4d pin_motion = Eigen::Vector4d::Zero();
};

// The contact solve of one pose (every pin in contact together).
struct ContactRecord {
  int corners = 0, in_contact = 0;
  int active_set_steps = 0;
  bool interior_point = false;       // the fallback ran
  double worst_penetration_m = 0.0;  // largest mean overlap at a corner left by the solver
  double resultant_error = 0.0;      // |E^T p + C delta - r| relative (fem::ContactSolution)
  double reciprocity_error = 0.0;    // |E_gap - E_force| / |E|: Maxwell-Betti of the two responses (round-off)
};

struct PartField {
  std::string body;
  // N x 3, world axes, from the rigid configuration; N (empty unless
  // recover_stress). Both empty for a pose that ElasticAssembly::solve with
  // MotionFields does not write: the scalars below and the envelope hold it.
  fem::DisplacementField displacement_m;
  Eigen::VectorXd von_mises_pa;
  // AssemblyOptions::keep_part_stress (else empty): the nodal stress tensor
  // (Pa, body axes, node-major Voigt as fem::StressField, 6N) is
  // ElasticAssembly::stress_patterns(body) * stress_coefficients when the
  // part's loads are superposed, else stress_pa itself.
  Eigen::VectorXd stress_coefficients, stress_pa;
  double max_displacement_m = 0.0;
  fem::Index max_displacement_node = 0;
  double max_von_mises_pa = 0.0;  // over the nodes (recover_stress)
};

// Per elastic part, over the poses of a motion: each node's largest
// displacement magnitude (world axes, from the rigid configuration, m) and
// von Mises stress (Pa; empty unless recover_stress), with the motion's step
// of each maximum (the first pose on ties). -1 before any pose.
struct PartEnvelope {
  std::string body;
  Eigen::VectorXd max_displacement_m, max_von_mises_pa;  // N
  Eigen::VectorXi displacement_step, von_mises_step;     // N, steps of the motion
};

// How ElasticAssembly::solve forms the parts' fields over a motion solved in
// calls of consecutive frames: every pose folds into `envelopes`, and only
// the poses with `write` set get PartField::displacement_m and von_mises_pa;
// the others carry PartField's scalars. A part whose loads are superposed
// (and has no pin in contact) is then done over chunks of nodes in cache:
// the pattern products, the rigid motion, the von Mises stress, the
// magnitude and the envelope together, without the full fields of every
// pose in memory (those cost several times their arithmetic at many output
// times). The others fold their full fields.
struct MotionFields {
  std::vector<bool> write;              // per frame of the next solve() call; empty: every frame
  size_t first_step = 0;                // the motion's step of that call's first frame
  std::vector<PartEnvelope> envelopes;  // per part in the order given; sized by the first call
};

// What a joint applies on each of its bodies (world axes; moments about the
// body's reference point, point_*_m). Ground side: minus the other side's.
struct JointLoad {
  std::string joint;
  mech::JointType type = mech::JointType::Revolute;
  std::string body_i, body_j;
  Eigen::Vector3d point_i_m = Eigen::Vector3d::Zero(), point_j_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_on_i_n = Eigen::Vector3d::Zero(), moment_on_i_nm = Eigen::Vector3d::Zero();
  Eigen::Vector3d force_on_j_n = Eigen::Vector3d::Zero(), moment_on_j_nm = Eigen::Vector3d::Zero();
};

struct ChainResult {
  std::string chain;
  double axial_stiffness_n = 0.0, free_length_m = 0.0, stiffness_n_per_m = 0.0;
  double elongation_m = 0.0, tension_n = 0.0;
  Eigen::Vector3d tangent_point_m = Eigen::Vector3d::Zero();  // world
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();        // unit, tangent point -> hinge
};

struct DriveResult {
  std::string drive;
  bool rigid = true;
  bool displacement = false;     // a displacement drive (the *_n and *_m fields), else an angle drive
  double stiffness_nm_per_rad = kRigid;
  double moment_on_j_nm = 0.0;  // about z, on body_j (the drive's effort)
  double twist_rad = 0.0;       // relative rotation theta_j - theta_i of its interfaces
  double stiffness_n_per_m = kRigid;
  double force_on_j_n = 0.0;    // along the drive's axis, on body_j (the drive's effort)
  double stretch_m = 0.0;       // change of s by the structure's deflection
};

// A transmission in one pose: the moment it applies on the output's body_j
// (the multibody TransmissionFrame's moment_output_Nm where the structure is
// determinate), its twist, and a belt's span tensions.
struct TransmissionResult {
  std::string transmission;
  bool rigid = true;
  double stiffness_nm_per_rad = kRigid;
  double moment_output_nm = 0.0;
  double twist_rad = 0.0;  // ds_out - ratio ds_in by the structure's deflection
  // A belt (TransmissionMember::radius_m > 0): span 1 is the one a positive
  // output moment tightens (N); zero without a radius.
  bool has_spans = false;
  double span_tension_n[2] = {0.0, 0.0};
};

// An elastic pin in one pose: its ends (world, the bores' reference points),
// section, and what it carries (PinLoads: end loads on the bodies, shear and
// bending at each end, sigma_b = 32 M/(pi d^3), tau = 16 V/(3 pi d^2), its
// own deflection).
struct PinResult {
  std::string joint, body_i, body_j;
  Eigen::Vector3d end_i_m = Eigen::Vector3d::Zero(), end_j_m = Eigen::Vector3d::Zero();
  double diameter_m = 0.0, length_m = 0.0;
  PinLoads loads;
};

// What one element of the structure adds to a tracked point's displacement,
// by the unit-load method: component c is the virtual work of the unit force
// e_c at the point (its internal loads in this element) on the element's real
// deformation. A part: lambda_v^T (F lambda + d) over its interfaces; a
// chain: N_v N / k; a compliant drive: M_v M / k_d; an elastic pin:
// u_v^T K_pin u over its two ends. Rigid bodies, rigid pins and rigid drives
// do no work. The contributions add up to the displacement
// exactly (Maxwell-Betti; up to round-off).
struct PointContribution {
  std::string name;  // "part.<body>", "chain.<chain>", "drive.<drive>", "pin.<joint>"
  Eigen::Vector3d displacement_m = Eigen::Vector3d::Zero();  // world axes
};

struct PointResult {
  std::string name, body;
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // world, rigid configuration
  Eigen::Vector3d displacement_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d rotation_rad = Eigen::Vector3d::Zero();
  // Unless AssemblyOptions::unit_load_split is false:
  // column c = the point's displacement under a unit force e_c at it alone
  // (world axes, m/N; symmetric by Maxwell-Betti).
  Eigen::Matrix3d compliance_m_per_n = Eigen::Matrix3d::Zero();
  // Every part, chain, compliant drive and elastic pin, in that order (model
  // order), then with pins in contact each contact joint's "play.<joint>":
  // the work of the virtual joint loads on the pins' motions in their bores
  // (their clearance and the contact's local give against the coupling).
  std::vector<PointContribution> contributions;
  // The same point with couplings at the pins in contact (no clearance, no
  // contact; the loads' own distribution): displacement_m - this is the
  // pins' share (clearance and contact). Equal to displacement_m without
  // pins in contact.
  Eigen::Vector3d coupling_displacement_m = Eigen::Vector3d::Zero();
};

// How many joint loads the rigid-body equilibrium of the pose leaves
// undetermined: (number of held components and spring members) - rank of
// the bodies' equilibrium equations, in the plane (x, y, rotation about z)
// and out of it (z, rotations about x and y). 0: statically determinate, the
// joint loads are the multibody reactions whatever the parts' stiffness; > 0:
// they depend on the stiffness of the parts, chains and drives.
struct Indeterminacy {
  int in_plane = 0, out_of_plane = 0;
};

struct PoseSolution {
  double t = 0.0;
  std::vector<BodyMotion> bodies;  // moving bodies, model order
  std::vector<PartField> parts;    // elastic parts, in the order given
  std::vector<JointLoad> joints;   // model joint order
  std::vector<ChainResult> chains;
  std::vector<DriveResult> drives;  // motion drives, model order
  std::vector<TransmissionResult> transmissions;  // model order
  std::vector<PinResult> pins;      // elastic pins, model joint order
  std::vector<PointResult> points;  // options.points order
  std::vector<BoreContactResult> contacts;  // pins in contact: part order, then the part's interface order
  ContactRecord contact;
  int unknowns = 0, rank = 0;
  double relative_residual = 0.0;   // of the dense system (scaled)
  Indeterminacy indeterminacy;
  double max_displacement_m = 0.0;  // over the parts' nodes
  std::string max_displacement_body;

  // Throw Error when the name is absent. Not on a temporary (the reference
  // would dangle: keep the solution in a variable).
  const PartField& part(const std::string& body) const&;
  const JointLoad& joint(const std::string& name) const&;
  const PointResult& point(const std::string& name) const&;
  const ChainResult& chain(const std::string& name) const&;
  const DriveResult& drive(const std::string& name) const&;
  const TransmissionResult& transmission(const std::string& name) const&;
  const PinResult& pin(const std::string& joint) const&;
  const BodyMotion& body(const std::string& name) const&;
  const PartField& part(const std::string&) const&& = delete;
  const JointLoad& joint(const std::string&) const&& = delete;
  const PointResult& point(const std::string&) const&& = delete;
  const ChainResult& chain(const std::string&) const&& = delete;
  const DriveResult& drive(const std::string&) const&& = delete;
  const TransmissionResult& transmission(const std::string&) const&& = delete;
  const PinResult& pin(const std::string&) const&& = delete;
  const BodyMotion& body(const std::string&) const&& = delete;
};

struct InterfaceInfo {
  std::string body;
  std::string kind;                                            // "joint", "drive" or "point"
  std::string name;                                            // joint, drive or tracked point name
  std::string face_set;                                        // elastic part; empty on a rigid body
  Eigen::Vector3d reference_body_m = Eigen::Vector3d::Zero();  // body frame
  bool elastic = false;
};

// The linear structure of one pose at the interfaces (interfaces() order),
// what the modes of the assembly need (vibration/assembly_vibration.hpp):
// u (6M) the interfaces' motions in world axes (translation of the reference
// point, m; rotation, rad); the joints and rigid drives hold C u = 0; the
// chains, compliant drives and elastic pins store the energy u^T S u / 2.
struct InterfaceStructure {
  std::vector<Eigen::Matrix3d> body_rotation;   // per model body: body axes -> world
  std::vector<Eigen::Vector3d> interface_arm_m;  // per interface: reference point - its body's origin, world axes
  Eigen::MatrixXd constraints;                   // rows x 6M, dimensionless (rotation rows: rad)
  std::vector<std::string> constraint_owner;     // per row, e.g. "joint 'A0' (x)"
  Eigen::MatrixXd springs;                       // 6M x 6M: N/m, N/rad, N m/rad
};

struct AssemblyStatistics {
  int elastic_parts = 0, rigid_bodies = 0, interfaces = 0, unknowns = 0;
  long part_dofs = 0;          // sum over the parts
  long interface_columns = 0;  // sum of 6 m over the parts (solved once)
  double setup_seconds = 0.0;  // assembly, factorization and interface solves, all parts
  int contact_corners = 0;     // pins in contact: the pressure's unknowns, all bores
  double contact_setup_seconds = 0.0, contact_seconds = 0.0;  // condensation (in setup_seconds); the poses' QPs
  int contact_interior_point_poses = 0, most_contact_active_set_steps = 0;
  double factorize_seconds = 0.0;
  long poses = 0;
  // Sums over every pose solved so far.
  double loads_seconds = 0.0, load_solve_seconds = 0.0, system_seconds = 0.0, recovery_seconds = 0.0;
  double pose_seconds() const {
    return poses > 0 ? (loads_seconds + load_solve_seconds + system_seconds + recovery_seconds) / double(poses) : 0.0;
  }
};

class ElasticAssembly {
 public:
  // Throws Error naming the part, joint or drive for a body without a model
  // body, a frame part without held_face or with one its mesh lacks,
  // held_face on a moving body's part, a frame part no joint, chain or
  // drive acts on, two parts of one body, a joint or motion
  // drive acting on a part that names no face set for it, a chain without
  // its EA or hinged off the ground, an elastic guide shorter than its
  // slider's contact length or without one, an option naming an unknown
  // chain, drive, body, point or prismatic joint, a drive stiffness of the
  // other coordinate type, a pin option naming no revolute joint, a pin
  // wider than a bore it passes through.
  // Every part is set up here. `factorized`: empty, or per part (in order)
  // a factorization of the part with its 3-2-1 support, lent by the caller
  // (nullptr: made and owned here); a lent one must be factorized and
  // outlive the assembly, which never frees it.
  ElasticAssembly(const std::vector<Part>& parts, const mech::MultibodyModel& model,
                  AssemblyOptions options = {}, const Log& log = Log::quiet(),
                  const std::vector<fem::LinearStaticAnalysis*>& factorized = {});
  // The topology and the checks only: the caller sets every part up with
  // set_up_part, e.g. right after the part's per-part stage while its factor
  // is in memory (pipeline::PartFactors, factors one at a time).
  ElasticAssembly(const std::vector<Part>& parts, const mech::MultibodyModel& model, AssemblyOptions options,
                  const Log& log, PartsLentOneByOne);
  ~ElasticAssembly();
  ElasticAssembly(ElasticAssembly&&) noexcept;
  // The part's interface and load-pattern solves with its factorization
  // (factorized, of this part with its 3-2-1 support; lent: it must outlive
  // the assembly, whose poses solve with it unless solves_with_factor says
  // no); each part once (else Error). Everything below, solve() included,
  // needs every part set up (else Error).
  void set_up_part(const std::string& body, fem::LinearStaticAnalysis& factor);
  // Whether solve() still solves with the part's factor (its loads not
  // superposed); false: its lender may free it after set_up_part.
  bool solves_with_factor(const std::string& body) const;
  bool is_set_up() const;
  ElasticAssembly& operator=(ElasticAssembly&&) noexcept;

  // One pose / several poses (the parts' load solves in one block). The frames
  // come from the model given (its bodies, drives, solver coordinates).
  // Throws Error naming the time for a mechanism (rank-deficient system), a
  // slack chain, or a part's loads that disagree with its multibody body.
  PoseSolution solve(const mech::Frame& frame);
  std::vector<PoseSolution> solve(const std::vector<mech::Frame>& frames);
  // The same poses, their fields as `fields` says (MotionFields); Error when
  // `write` is neither empty nor one flag per frame.
  std::vector<PoseSolution> solve(const std::vector<mech::Frame>& frames, MotionFields& fields);

  std::vector<InterfaceInfo> interfaces() const;
  // The pose's constraints and springs (InterfaceStructure); throws Error
  // like solve() for a frame of another model or a chain without free length.
  InterfaceStructure interface_structure(const mech::Frame& frame) const;
  // What the elastic part of `body` is made of here (Error if it has none):
  // its interface columns G (3N x 6m, body axes, interfaces() order of the
  // body's interfaces: u_b = G^T u; distributing couplings only, Error for
  // BoreCoupling::RigidBore), its 3-2-1-supported factorized analysis and
  // its loads without the joints and motion drives (loads::LinkLoads).
  const Eigen::MatrixXd& interface_columns(const std::string& body) const;
  fem::LinearStaticAnalysis& supported_analysis(const std::string& body) const;
  const loads::LinkLoads& part_loads(const std::string& body) const;
  // Per moving body (model order, the ground skipped): the multibody model's
  // applied minus inertia loads at the frame, world axes, force N and moment
  // N m about the body's origin.
  std::vector<Vector6d> body_loads(const mech::Frame& frame) const;
  // Flexibility G^T K_s^-1 G of the elastic part of `body` over its
  // interfaces (interfaces() order), body axes; 6m x 6m.
  Eigen::MatrixXd flexibility(const std::string& body) const;
  // The nodal stress (Pa, body axes, 6N rows as PartField::stress_pa) of the
  // part of `body` under each unit interface load and each load pattern,
  // [S_G S_p] (6N x (6m + p)): the patterns of PartField::stress_coefficients.
  // Error when its loads are not superposed or its stress is not recovered.
  Eigen::MatrixXd stress_patterns(const std::string& body) const;
  const AssemblyStatistics& statistics() const;
  // The contact surface of the bore of `body`'s part that joint's pin is in
  // contact with (Error when there is none).
  const fem::BoreContactSurface& contact_surface(const std::string& body, const std::string& joint) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kinetofem::structure
