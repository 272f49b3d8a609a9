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
//   * each drive's effort (torque) on its shaft face, each spring's force
//     (tension k (L - L0) + c L', from the frame's body states) and each
//     constant point force, at their points, through distributing couplings.
// Out of the plane (force along z, moments about x and y: a part or a load
// off the mid-plane z = 0) the planar model gives no reaction; loads_at hands
// them to the part's revolute pins, split equally (a pin holds the moments
// normal to its axis), and reports their size.
// These loads are in equilibrium when the multibody body has the FE mesh's
// mass properties (pipeline::apply_mass_properties); loads_at checks it and throws an
// Error naming the link and the time when the resultant force or moment
// exceeds `equilibrium_tolerance` of the loads' magnitude.
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/multibody/model.hpp"
#include "kinetofem/mechanisms/multibody/results.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::loads {

enum class BoreLoad { DistributingCoupling, BearingPressure };

// Where a joint of the multibody model acts on the link's mesh.
struct JointAttachment {
  std::string joint;     // joint name in the multibody model
  std::string face_set;  // bore (pins) or roller rim (chain) of the mesh
  BoreLoad distribution = BoreLoad::DistributingCoupling;
};

// A point mass of the multibody body carried through a mount face.
struct PointMassAttachment {
  std::string point_mass;  // name in mech::Body::point_masses
  std::string face_set;    // mount face of the mesh
};

// A drive (motor) whose torque enters the link through a face set (the
// shaft's bore), by a distributing coupling.
struct DriveAttachment {
  std::string drive;     // name in mech::MultibodyModel::motion_drives / force_drives
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

 private:
  struct Attached {
    std::string joint;
    int joint_index = -1;
    bool on_i = false;  // this link is the joint's body_i (else body_j)
    BoreLoad distribution;
    bool revolute = false;  // a pin: carries the out-of-plane moments
    fem::BoreGeometry bore;
    std::unique_ptr<fem::DistributingCoupling> coupling;
  };
  struct Drive {
    std::string name;
    int drive_index = -1;
    bool on_j = true;  // the effort acts on body_j (+), reacts on body_i (-)
    std::unique_ptr<fem::DistributingCoupling> coupling;
  };
  struct Spring {
    std::string name;
    int spring_index = -1;
    bool on_i = false;  // this link carries point_i (else point_j)
    Eigen::Vector3d point_body = Eigen::Vector3d::Zero();
    std::unique_ptr<fem::DistributingCoupling> coupling;
  };
  struct PointForce {
    std::string name;
    Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d point_body = Eigen::Vector3d::Zero();
    std::unique_ptr<fem::DistributingCoupling> coupling;
  };
  struct Mass {
    std::string name;
    double mass_kg = 0;
    Eigen::Vector3d position_body = Eigen::Vector3d::Zero();
    std::unique_ptr<fem::DistributingCoupling> coupling;
  };
  LinkDefinition link_;
  int body_index_ = -1;
  Eigen::Vector3d gravity_world_ = Eigen::Vector3d::Zero();
  double tolerance_;
  std::vector<Attached> joints_;
  std::vector<Mass> masses_;
  std::vector<Drive> drives_;
  std::vector<Spring> springs_;
  std::vector<PointForce> point_forces_;
  std::vector<mech::Spring> model_springs_;
  std::vector<int> spring_body_i_, spring_body_j_;  // body indices of each model spring
  std::vector<Eigen::Vector2d> spring_point_i_, spring_point_j_;
  fem::RigidBodyMotionLoads motion_loads_;
  double length_scale_ = 1.0;
};

}  // namespace kinetofem::loads
