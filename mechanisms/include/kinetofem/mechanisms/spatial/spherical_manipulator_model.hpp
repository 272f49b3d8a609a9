#pragma once
// The SPEC §5 spherical-coordinate 3-DoF manipulator (closed form:
// spherical_manipulator.hpp) as a spatial::Model, driven so that its gripper
// point M travels a StraightLineMotion, and the map from a frame of its run
// back to the closed form's quantities (SphericalDynamics), so that the
// spatial multibody core and the closed-form kinetostatics can be compared
// quantity by quantity.
//
// Usage:
//   const spatial::System system(spatial::spherical_manipulator_model(design, motion));
//   const spatial::Results run = spatial::run_kinematics(system, times);
//   const SphericalDynamics d = spatial::spherical_dynamics(run.frames[k]);
//   const spatial::ClosedFormComparison c = spatial::compare_with_closed_form(design, motion, run);
//
// World frame (as the closed form): origin on the floor on the column axis,
// z up (m). q = (phi10, phi21, l_BM); e_r, e_theta, e_phi the spherical unit
// vectors at (phi10, phi21) and e_h = (cos phi10, sin phi10, 0)
// (spherical_manipulator.hpp).
//
// Bodies and their frames. A later stage meshes the parts in these frames, so
// they are drawn the way a designer draws the parts: the column along its own
// z, sleeve and arm along their own x.
//   "ground"  fixed, the world frame; point "A" = (0, 0, z_A).
//   "column"  link 1. Origin on the floor on the column axis; z along the axis
//             (up), x horizontal towards the arm (e_h), y = e_phi, so its
//             rotation is R_z(phi10). Points "A" = (0, 0, z_A) (pair 1-0) and
//             "B" = (0, 0, z_B) (pair 2-1). Mass m1, centre of mass
//             (0, 0, column_com_height_m); inertia diag(I_t, I_t, column_inertia_z),
//             I_t = 0.1 m1 z_B^2 (the source's I_S rule over the column height;
//             the closed form has none: the column turns about its own axis of
//             symmetry, where I_t does not enter the loads).
//   "sleeve"  link 2. Origin at B, the middle of the sleeve; x along the arm
//             axis e_r, y = e_phi (the tilt axis is -y), z = e_theta. The sleeve
//             spans x in [-l2/2, l2/2], diameter d2. Point "B" = origin. Mass m2,
//             centre of mass at B; inertia diag(axial, transverse, transverse).
//   "arm"     link 3. Origin at the arm's rear end; x = e_r towards M, y = e_phi,
//             z = e_theta, so the arm spans x in [0, L] (L = arm_length_m) and
//             its frame is the sleeve's shifted by l_BM - L along x. Points
//             "rear" = origin, "S3" = (L/2, 0, 0) (its centre of mass, as the
//             closed form's S3 = B + (l_BM - L/2) e_r), "M" = (L, 0, 0) (the
//             gripper point). Mass m3, inertia diag(axial, transverse,
//             transverse) about S3; the payload is the point mass "payload"
//             at M (no rotary inertia).
// A zero axial inertia of sleeve or arm (the closed form's slender bars) is
// replaced by kSlenderAxialInertiaFraction times the transverse one
// (as_modelled): the spatial core needs a positive definite inertia (it works
// in the mass metric). The fraction is a compromise: the loads change by about
// that fraction times the transverse inertia's share of them (up to 2e-10 of
// the largest moment for SPEC §5 variant A without payload), while a smaller
// fraction makes the mass metric ill-conditioned: the index-1 solve's
// acceleration residual grows as 1/fraction, and the core refuses some frames
// at 1e-10 and all at 1e-11 (residual above 1e-6 of its scale).
//
// Joints (body_i - body_j, axes and references in the bodies' frames):
//   "pair_10"  revolute   ground "A" - column "A", axis z, reference x on both:
//              its angle is phi10.
//   "pair_21"  revolute   column "B" - sleeve "B", axis -y (= -e_phi, the
//              closed form's tilt axis), reference x on both: its angle is phi21
//              (phi21 > 0 lifts the arm).
//   "pair_32"  prismatic  sleeve "B" - arm "M", axis x (e_r) on both, no
//              rotation about it: its translation h_i . (M - B) is l_BM.
// Drives (spatial::MotionDrive, initial = 0 so that each row holds the
// closed-form joint coordinate itself, not a change of it):
//   "M10d"  rotation of pair_10 = phi10(t)   (torque N m about z on the column)
//   "M21d"  rotation of pair_21 = phi21(t)   (torque N m about -e_phi on the sleeve)
//   "F32d"  translation of pair_32 = l_BM(t) (force N along e_r on the arm, at M)
// The efforts carry the closed form's names and signs.
#include <algorithm>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "kinetofem/mechanisms/motion_law.hpp"
#include "kinetofem/mechanisms/spatial/model.hpp"
#include "kinetofem/mechanisms/spatial/results.hpp"
#include "kinetofem/mechanisms/spherical_manipulator.hpp"

namespace kinetofem::mech::spatial {

// Names of the model's bodies, points, joints and drives (see above).
namespace spherical_names {
inline constexpr std::string_view ground = "ground", column = "column", sleeve = "sleeve", arm = "arm";
inline constexpr std::string_view point_a = "A", point_b = "B", point_m = "M", point_s3 = "S3", point_rear = "rear";
inline constexpr std::string_view payload = "payload";
inline constexpr std::string_view pair_10 = "pair_10", pair_21 = "pair_21", pair_32 = "pair_32";
inline constexpr std::string_view drive_10 = "M10d", drive_21 = "M21d", drive_32 = "F32d";
}  // namespace spherical_names

// Axial inertia given to a slender sleeve or arm whose design has none, as a
// fraction of its transverse inertia (see above).
inline constexpr double kSlenderAxialInertiaFraction = 1e-8;

// One joint coordinate of the closed-form inverse kinematics along a straight
// line (spherical_joint_motion): k = 0 phi10 (rad), 1 phi21 (rad), 2 l_BM (m),
// with its first and second time derivatives. The value is the coordinate
// itself, not its change from t = 0 (unlike the rise-from-zero laws of
// motion_law.hpp): a drive on it takes initial = 0. Outside [0, duration] M
// dwells at a or b, and so does the coordinate. Copies design and motion.
class SphericalJointLaw final : public MotionLaw {
 public:
  SphericalJointLaw(const SphericalDesign& design, const StraightLineMotion& motion, int coordinate);
  MotionState at(double t) const override;
  double stroke() const override;
  double duration() const override { return motion_.duration(); }
  std::string describe() const override;

 private:
  SphericalDesign design_;
  StraightLineMotion motion_;
  int coordinate_;
};

// The design with the inertias the model takes: a zero axial inertia of
// sleeve or arm replaced as above; the rest as given.
SphericalDesign as_modelled(const SphericalDesign& design);

// The manipulator of `design` (as_modelled) with its payload, assembled at the motion's
// start (t = 0) and driven along it. characteristic_length_m = arm length;
// gravity (0, 0, -design.gravity_mps2).
Model spherical_manipulator_model(const SphericalDesign& design, const StraightLineMotion& motion);

// The closed form's quantities from a frame of a run of that model: joint
// motion from the drives (s, s', s''); for each pair the load of the inner
// link on the outer one at the closed form's reference point (pair32 and
// pair21 at B, pair10 at A), its drive effort (the drive's multiplier) and its
// reaction (the joint's constraint load, moved to that point); drive powers.
// Throws if the frame lacks a body, joint or drive of the model.
SphericalDynamics spherical_dynamics(const Frame& frame);

// Largest differences between a run of the model and the closed-form
// kinetostatics (spherical_inverse_dynamics at the closed-form joint motion of
// each frame's time), each relative to the largest closed-form value of its
// kind over the run: per drive (M10d, M21d, F32d), the torques relative to the
// larger drive torque, the force to the largest drive force (so a drive idle
// on the line, M10d of a motion in a vertical plane, is measured against the
// tilt torque); reaction forces and reaction moments (every component of the
// three pairs, relative to the largest reaction force or moment magnitude).
struct ClosedFormComparison {
  Eigen::Vector3d drive = Eigen::Vector3d::Zero();
  double reaction_force = 0.0;
  double reaction_moment = 0.0;
  double largest() const { return std::max({drive.maxCoeff(), reaction_force, reaction_moment}); }
};
// What a run may differ from the closed form and still count as agreeing
// (largest()): the formulations agree to ~1e-13 and the slender bars' axial
// inertia (above) moves the loads by up to ~2e-10.
inline constexpr double kClosedFormAgreement = 1e-8;
ClosedFormComparison compare_with_closed_form(const SphericalDesign& design, const StraightLineMotion& motion,
                                              const Results& run);

}  // namespace kinetofem::mech::spatial
