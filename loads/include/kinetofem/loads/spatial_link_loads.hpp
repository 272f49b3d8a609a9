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
//   * each constant point force of the model on it, at its point;
//   * a prismatic joint's load (with its drive's, an actuator along the
//     slide) as a guide takes it on two bearing lands and a slider on the
//     stations of its slide face (SpatialSlideAttachment).
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
#include "kinetofem/loads/slide_stations.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/solver/fe_model.hpp"

namespace kinetofem::loads {

// A named item of the spatial model that loads the part through a face set.
struct SpatialAttachment {
  std::string name;      // joint or motion drive, point mass, or point force of the model
  std::string face_set;  // of the part's mesh
};

// A prismatic joint whose guide (body_i: a sleeve) bears the slider (body_j:
// an arm) on two lands. The joint's load on the guide (with its motion
// drive's, when one is named), a force F and a moment M about the guide's
// joint point P_i, is split into two land loads at P_i + x h, x = front_m
// and rear_m, h the slide axis: across the axis the two forces that carry
// F's transverse part and M's transverse part (w = M_perp x h,
// F_front = (w - x_rear F_perp) / (x_front - x_rear), F_rear = F_perp - F_front);
// along the axis and about it, half each. The guide takes them through its
// land face sets; the slider takes them reversed through the stations of its
// slide face (slide_stations.hpp, cut along the joint's axis_j from its
// point P_j) that bracket each land, weighted linearly, so the load enters
// where the lands are at each output time and stays a combination of fixed
// patterns.
struct SpatialSlideAttachment {
  std::string joint;                          // a prismatic joint of the model
  std::string drive;                          // its motion drive, or empty
  double front_m = 0.0, rear_m = 0.0;         // land centres along h from P_i (m), different
  std::string front_face_set, rear_face_set;  // the guide's lands
  SlideStations stations;                     // the slider's slide face
};

struct SpatialLinkDefinition {
  std::string body;                             // body name in the spatial model
  const fem::FeModel* model = nullptr;          // mesh in the body frame; not owned
  std::vector<SpatialAttachment> joints;        // joints and motion drives (a drive:
                                                // its load at the joint's points)
  std::vector<SpatialAttachment> point_masses;  // mech::spatial::Body::point_masses of this body
  std::vector<SpatialAttachment> point_forces;  // mech::spatial::Model::point_forces on this body
  bool held_on_foundation = false;              // a part of the ground: no equilibrium check
  std::vector<SpatialSlideAttachment> slides;   // on the guide or on the slider
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
  struct Slide {
    SpatialSlideAttachment attachment;
    int joint = -1, drive = -1;  // into Frame::joints, Frame::drives (-1: none)
    bool guide = true;           // this body is the joint's body_i (else the slider)
    Eigen::Vector3d axis_i = Eigen::Vector3d::UnitX();  // h in the guide's frame (unit)
    int guide_body = -1;
    int front = -1, rear = -1;   // guide: the lands' couplings
    std::vector<int> stations;   // slider: the stations' couplings
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
  std::vector<Slide> slides_;
};

}  // namespace kinetofem::loads
