#pragma once
// SpatialLinkLoads — the loads on one part's FE model at an output time of a
// spatial mechanism's motion (mech::spatial::Frame), as coefficients of the
// part's fixed load patterns (load_patterns.hpp), so the stress over the
// motion is one block solve of the patterns and a product per output time
// (link_stress_history.hpp, PatternLoadHistory).
//
// Frames and units: the part's mesh is in its body's frame of the spatial
// model (origin and axes of mech::spatial::Body; m), so its stiffness is the
// same at every output time. Everything below is turned into that frame by
// the body's rotation R (body -> world) at the frame: a world vector v is
// R^T v there; SI throughout.
//
// At time t the part carries, in its body frame:
//   * the load of every joint and motion drive attached to it (the full 3D
//     reaction of mech::spatial::JointState / DriveState: a force at the joint
//     point and a moment about it), through a distributing coupling on the
//     attachment's face set;
//   * its own d'Alembert inertia and weight, the affine body force
//     rho (g - a_O - alpha x r - omega x (omega x r)), a_O the body frame
//     origin's acceleration, omega and alpha its angular velocity and
//     acceleration (all turned into the body frame);
//   * each point mass it carries (gripper, casting), the force m (g - a_P) at
//     the mass's point and, for a mass with rotary inertia J (body axes), the
//     moment -(J alpha + omega x J omega), through its mount face;
//   * each constant point force of the model on it, at its point.
// Unlike the planar LinkLoads, nothing is missing out of a plane: the spatial
// reactions are complete, so the loads are in equilibrium by themselves when
// the model's body has the FE mesh's mass properties
// (assign_mass_properties); coefficients_at checks it and throws an Error
// naming the part and the time when the resultant force or moment exceeds
// `equilibrium_tolerance` of the loads' magnitude, unless the part is held on
// a foundation (the ground's parts: the foundation takes the resultant).
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/loads/link_loads.hpp"
#include "kinetofem/loads/load_patterns.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::loads {

// A named item of the spatial model that loads the part through a face set.
struct SpatialAttachment {
  std::string name;      // joint or motion drive, point mass, or point force of the model
  std::string face_set;  // of the part's mesh
};

struct SpatialLinkDefinition {
  std::string body;                             // body name in the spatial model
  const fem::FeModel* model = nullptr;          // mesh in the body frame; not owned
  std::vector<SpatialAttachment> joints;        // joints and motion drives (a drive:
                                                // its load at the joint's points)
  std::vector<SpatialAttachment> point_masses;  // mech::spatial::Body::point_masses of this body
  std::vector<SpatialAttachment> point_forces;  // mech::spatial::Model::point_forces on this body
  bool held_on_foundation = false;              // a part of the ground: no equilibrium check
};

// Mass, centre of mass and inertia tensor (about the centre of mass, body
// axes) of a spatial body from an FE model in its body frame; the body's
// point masses stay as they are.
void assign_mass_properties(mech::spatial::Body& body, const fem::FeModel& model);

class SpatialLinkLoads {
 public:
  // Throws Error naming the part when the body, a joint or drive, a point
  // mass, a point force or a face set is missing, or an attachment does not
  // act on the body.
  SpatialLinkLoads(const SpatialLinkDefinition& link, const mech::spatial::Model& model,
                   double equilibrium_tolerance = 1e-6);

  const std::string& body() const { return link_.body; }
  int pattern_count() const { return patterns_.count(); }
  std::vector<std::string> pattern_names() const { return patterns_.names(); }
  Eigen::MatrixXd pattern_forces() const { return patterns_.forces(); }

  // c(t) with the equilibrium check (out_of_plane_* stay zero).
  LinkLoadCoefficients coefficients_at(const mech::spatial::Frame& frame) const;
  // The nodal forces P c(t) (3 N, N, body frame).
  Eigen::VectorXd loads_at(const mech::spatial::Frame& frame) const;
  // Every frame's coefficients as the stress stage takes them.
  PatternLoadHistory history(const std::vector<mech::spatial::Frame>& frames) const;

 private:
  using Vector6d = LoadPatterns::Vector6d;
  struct State {
    LoadPatterns::BodyForce body_force;
    std::vector<Vector6d> coupling;
    double equilibrium_residual = 0.0;
  };
  State state_at(const mech::spatial::Frame& frame) const;

  struct Constraint {
    std::string name;
    bool drive = false;  // a motion drive (else a joint)
    int index = -1;      // into Frame::joints or Frame::drives
    bool on_i = false;   // this body is the block's body_i
    int coupling = -1;
  };
  struct Mass {
    std::string name;
    double mass_kg = 0.0;
    Eigen::Vector3d position_body = Eigen::Vector3d::Zero();
    Eigen::Matrix3d inertia_kgm2 = Eigen::Matrix3d::Zero();  // about its centre, body axes
    int coupling = -1;
  };
  struct Force {
    std::string name;
    Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
    Eigen::Vector3d point_body = Eigen::Vector3d::Zero();
    int coupling = -1;
  };
  SpatialLinkDefinition link_;
  LoadPatterns patterns_;
  int body_index_ = -1;
  Eigen::Vector3d gravity_world_ = Eigen::Vector3d::Zero();
  double tolerance_;
  std::vector<Constraint> constraints_;
  std::vector<Mass> masses_;
  std::vector<Force> forces_;
};

}  // namespace kinetofem::loads
