#pragma once
// LinkLoads — the loads on one link's FE model at an output time of the
// mechanism's motion, built from the multibody results (mech::Frame).
//
// Frames: the FE mesh of a link is in the link's BODY frame of the planar
// multibody model (x, y in the mechanism plane, z along the pin axes), so a
// link's stiffness matrix is the same at every output time. Planar
// quantities are lifted to 3D with z = 0 (forces) and about z (moments).
//
// At time t the link carries, all in its body frame:
//   * the reaction of every joint on it (mech::Reaction: force at the joint
//     point, moment about it), spread over the joint's bore (or, for the
//     chain, the roller rim) by a distributing coupling (default) or a cosine
//     bearing pressure (pins only; see solver/couplings.hpp for why the
//     coupling is the default);
//   * its own d'Alembert inertia and weight, the affine body force
//     rho (g - a_O - alpha x r - omega x (omega x r));
//   * each point mass it carries (gripper, casting) as the force
//     m (g - a_P) at the mass's point, tied to its mount face by a
//     distributing coupling;
//   * each drive's effort (torque) and each transmission's moment (a belt's
//     or gear train's, mech::Transmission, on the body of either of its two
//     coordinates) on its shaft face, each spring's force
//     (tension k (L - L0) + c L', from the frame's body states) and each
//     constant point force, at their points, through distributing couplings.
// A joint's reaction, a point mass, a spring end or a point force acts at its
// body point (x, y) at the z of its face's centroid: the planar model does not
// place it along the pins, the bore or the mount face does (a lever built
// 175 mm out of the mechanism's plane takes its pin loads in its own bores,
// and a casting held in the jaws of a gripper built 245 mm out is there, not
// at z = 0), as in the elastic assembly's interfaces and the vibration's
// point masses. A part in its own plane thus gets the planar loads in that
// plane; what the offsets between the parts add out of the plane is the
// elastic assembly's (pins as members).
// Out of the plane (force along z, moments about x and y: a part or a load
// off the mid-plane z = 0) the planar model gives no reaction; loads_at hands
// them to the part's revolute pins, split equally (a pin holds the moments
// normal to its axis), and reports their size.
// Load patterns (unit-load superposition). Every load above except the
// cosine bearing pressure is linear in a fixed set of nodal force patterns:
//     f(t) = P c(t),   P = [ B | G_1 | ... | G_k ]      (3 N x (12 + 6 k))
// B: the 12 basis fields of the affine body force (fem::RigidBodyMotionLoads);
// G_j: unit force F_x, F_y, F_z and unit moment M_x, M_y, M_z at the centroid
// of the j-th distributing coupling, one per distinct face set (a joint, a
// mass, a drive, a transmission, a spring or a force on the same face share it). c(t): the
// body force's 12 coefficients, then per coupling the resultant (force, N;
// moment about its centroid, N m) of everything that enters through it. So a
// link is solved for its m patterns once and any output time is the
// combination c(t): loads_at(frame) == pattern_forces() * coefficients_at(frame)
// up to round-off. The bearing pressure turns with the force's direction (not
// linear): a link with one is not superposable() and goes step by step.
// These loads are in equilibrium when the multibody body has the FE mesh's
// mass properties (pipeline::apply_mass_properties); loads_at checks it and throws an
// Error naming the link and the time when the resultant force or moment
// exceeds `equilibrium_tolerance` of the loads' magnitude.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/loads/load_patterns.hpp"
#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::loads {

// How a joint's reaction enters the bore: a distributing coupling, a cosine
// bearing pressure, or the contact of a round pin (loads::LinkContact,
// fem::BoreContactSurface): the bore's coupling pattern then carries only
// what a frictionless pin cannot (force along the axis, moment about it)
// and the contact forces the rest.
enum class BoreLoad { DistributingCoupling, BearingPressure, Contact };

// Where a joint of the multibody model acts on the link's mesh.
struct JointAttachment {
  std::string joint;     // joint name in the multibody model
  std::string face_set;  // bore (pins) or roller rim (chain) of the mesh
  BoreLoad distribution = BoreLoad::DistributingCoupling;
  double clearance_m = 0.0;  // Contact: radial clearance of the pin in the bore (>= 0)
  // Contact: an ISO 286 clearance fit ("H7/g6", loads/iso_fit.hpp) instead:
  // its mean radial clearance at the bore's diameter (measured on the mesh).
  std::string fit;
  // Contact: the pin's material when the pin is elastic (fem::ElasticPin: a
  // pin meshed from the bore's diameter less the clearance and its span);
  // none: a rigid pin.
  std::optional<fem::IsotropicMaterial> pin_material;
};

// A pin in contact with a bore of the link (BoreLoad::Contact): the joint,
// its bore (face set, axis through the bore coupling's centroid, along z),
// the bore coupling's first load pattern (its F_x; the next five are F_y,
// F_z, M_x, M_y, M_z about the centroid) and the pin's clearance.
struct ContactBore {
  std::string joint;
  fem::BoreGeometry bore;
  int first_pattern = -1;
  double clearance_m = 0.0;  // radial (from JointAttachment::clearance_m or its fit)
  double diameter_m = 0.0;   // of the bore: twice the mean distance of its nodes from the axis
  std::optional<fem::IsotropicMaterial> pin_material;  // elastic pin (JointAttachment::pin_material); none: rigid
};

// A point mass of the multibody body carried through a mount face.
struct PointMassAttachment {
  std::string point_mass;  // name in mech::Body::point_masses
  std::string face_set;    // mount face of the mesh
};

// A drive whose effort enters the link through a face set by a distributing
// coupling: a torque (an angle drive: the motor shaft's bore), or a force
// along the drive's axis at the coordinate's point on this link (a
// displacement drive: a linear actuator's mount; on its body_i also the
// couple of the axis turning with that body).
struct DriveAttachment {
  std::string drive;     // name in mech::MultibodyModel::motion_drives / force_drives
  std::string face_set;
};

// A transmission (mech::Transmission) whose moment on this link enters
// through a face set (the bore of the pulley, sprocket or gear it turns, or of
// the shaft that carries it), by a distributing coupling, as a drive's effort.
// A link can be a body of both coordinates (the arm that carries a belt from
// the frame's pulley to the next link's): one attachment per side.
enum class TransmissionSide { Input, Output };

struct TransmissionAttachment {
  std::string transmission;  // name in mech::MultibodyModel::transmissions
  TransmissionSide side = TransmissionSide::Output;
  std::string face_set;
};

// A spring of the multibody model, its end on this link tied to a face set.
struct SpringAttachment {
  std::string spring;  // name in mech::MultibodyModel::springs
  std::string face_set;
};

// A constant point force of the multibody model on this link.
struct PointForceAttachment {
  std::string point_force;  // name in mech::MultibodyModel::point_forces
  std::string face_set;
};

struct LinkDefinition {
  std::string body;  // body name in the multibody model
  const fem::FeModel* model = nullptr;  // mesh in the body frame; not owned
  std::vector<JointAttachment> joints;
  std::vector<PointMassAttachment> point_masses;
  std::vector<DriveAttachment> drives;
  std::vector<SpringAttachment> springs;
  std::vector<PointForceAttachment> point_forces;
  // The link is a part of the ground (a frame) held on its foundation: its
  // loads (the ground sides of the joints, drives and chain, its weight) are
  // not self-equilibrated, the foundation takes their resultant, so
  // loads_at neither checks their equilibrium nor gives the out-of-plane
  // components to the pins.
  bool held_on_foundation = false;
  // Last, so that the positional initialisers of the fields above still hold.
  std::vector<TransmissionAttachment> transmissions;
};

// Mass, centre of mass and inertia (about z) of a mech::Body from an FE
// model in the body frame (the point masses are added by the multibody model
// itself).
void assign_mass_properties(mech::Body& body, const fem::FeModel& model);

struct LinkLoadResult {
  Eigen::VectorXd forces;  // 3 N nodal forces, N, body frame
  double equilibrium_residual = 0.0;  // |resultant| relative to the loads' magnitude
  // What the pins carry out of the plane (see loads_at): |(M_x, M_y)| about
  // the pins' mean centre, N m, and |F_z|, N, of the other loads.
  double out_of_plane_moment_nm = 0.0, out_of_plane_force_n = 0.0;
};

// The coefficients c(t) of a frame (see "Load patterns" above) with the
// same checks as LinkLoadResult.
struct LinkLoadCoefficients {
  Eigen::VectorXd coefficients;  // pattern_count(); units of each pattern's unit load
  double equilibrium_residual = 0.0;
  double out_of_plane_moment_nm = 0.0, out_of_plane_force_n = 0.0;
};

class LinkLoads {
 public:
  // `model` is the multibody model the frames come from. Throws Error if the
  // body, a joint, a point mass or a face set is missing.
  LinkLoads(const LinkDefinition& link, const mech::MultibodyModel& model,
            double equilibrium_tolerance = 1e-6);

  // Loads at one output time; throws Error naming link and time if out of
  // equilibrium beyond the tolerance.
  LinkLoadResult loads_at(const mech::Frame& frame) const;

  const std::string& body() const { return link_.body; }

  // Unit-load superposition (see "Load patterns" above). A link with pins in
  // contact is superposable: the contact forces are added to its patterns
  // by the stress stage (link_stress_history.hpp).
  bool superposable() const { return !has_bearing_pressure_; }
  // The pins in contact with the link's bores (BoreLoad::Contact), in the
  // order of the attachments.
  const std::vector<ContactBore>& contact_bores() const { return contact_bores_; }
  int pattern_count() const { return patterns_.count(); }
  // "body_force.c_x" .. "body_force.A_zz", then "<face_set>.F_x" .. ".M_z".
  std::vector<std::string> pattern_names() const { return patterns_.names(); }
  // P, 3 N x pattern_count(), N per unit coefficient.
  Eigen::MatrixXd pattern_forces() const { return patterns_.forces(); }
  // c(t); throws like loads_at (out of equilibrium), also for a link that is
  // not superposable (the bearing pressure has no coefficient).
  LinkLoadCoefficients coefficients_at(const mech::Frame& frame) const;

 private:
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  // Everything loads_at and coefficients_at share: the loads of a frame as
  // body-force coefficients, coupling resultants (force, moment about the
  // coupling's centroid) and, for bearing joints, their nodal forces.
  struct LoadState {
    Eigen::Matrix<double, 12, 1> body_force;
    std::vector<Vector6d> coupling;   // per coupling of patterns_
    Eigen::VectorXd bearing_forces;   // 3 N; empty without bearing joints
    double equilibrium_residual = 0.0;
    double out_of_plane_moment_nm = 0.0, out_of_plane_force_n = 0.0;
  };
  LoadState state_at(const mech::Frame& frame) const;

  struct Attached {
    std::string joint;
    int joint_index = -1;
    bool on_i = false;  // this link is the joint's body_i (else body_j)
    BoreLoad distribution;
    bool revolute = false;  // a pin: carries the out-of-plane moments
    fem::BoreGeometry bore;
    int coupling = -1;
  };
  struct Drive {
    std::string name;
    int drive_index = -1;
    bool on_j = true;  // the effort acts on body_j (+), reacts on body_i (-)
    int coupling = -1;
    // A displacement drive (a linear actuator): its axis in body_i's frame
    // (unit), its bodies and points (their frames); else a torque.
    bool displacement = false;
    Eigen::Vector2d axis_i = Eigen::Vector2d::UnitX();
    int body_i = -1, body_j = -1;
    Eigen::Vector2d point_i = Eigen::Vector2d::Zero(), point_j = Eigen::Vector2d::Zero();
  };
  struct TransmissionLoad {
    std::string name;
    int transmission_index = -1;  // into mech::Frame::transmissions
    TransmissionSide side = TransmissionSide::Output;
    bool on_j = true;  // the side's moment acts on its body_j (+), reacts on body_i (-)
    int coupling = -1;
  };
  struct Spring {
    std::string name;
    int spring_index = -1;
    bool on_i = false;  // this link carries point_i (else point_j)
    Eigen::Vector3d point_body = Eigen::Vector3d::Zero();
    int coupling = -1;
  };
  struct PointForce {
    std::string name;
    Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d point_body = Eigen::Vector3d::Zero();
    int coupling = -1;
  };
  struct Mass {
    std::string name;
    double mass_kg = 0;
    Eigen::Vector3d position_body = Eigen::Vector3d::Zero();
    int coupling = -1;
  };
  LinkDefinition link_;
  int body_index_ = -1;
  Eigen::Vector3d gravity_world_ = Eigen::Vector3d::Zero();
  double tolerance_;
  LoadPatterns patterns_;
  bool has_bearing_pressure_ = false;
  std::vector<ContactBore> contact_bores_;
  std::vector<Attached> joints_;
  std::vector<Mass> masses_;
  std::vector<Drive> drives_;
  std::vector<TransmissionLoad> transmissions_;
  std::vector<Spring> springs_;
  std::vector<PointForce> point_forces_;
  std::vector<mech::Spring> model_springs_;
  std::vector<int> spring_body_i_, spring_body_j_;  // body indices of each model spring
  std::vector<Eigen::Vector2d> spring_point_i_, spring_point_j_;
};

}  // namespace kinetofem::loads
