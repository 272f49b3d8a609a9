#pragma once
// Spherical-coordinate 3-DoF manipulator of SPEC §5 (source 003, TMM course
// project): sizing, straight-line motion of the gripper point M with the
// trapezoidal speed law, inverse kinematics, inverse dynamics by the
// kinetostatic method (Newton-Euler, from the gripper link back to the base,
// 3D rigid bodies), and a CVODES forward-dynamics cross-check.
//
// World frame: origin on the floor on the vertical axis of pair 1-0, z up (m).
// Links and pairs (joint coordinates q = (phi10, phi21, l_BM), rad, rad, m):
//   link 1 (column) turns about z by phi10 in pair 1-0, reference point
//       A = (0, 0, z_A) (height of joint A);
//   link 2 (sleeve) tilts by phi21 about the horizontal axis through
//       B = (0, 0, z_B), axis -e_phi (phi21 > 0 lifts the arm); its centre of mass
//       is at B (the middle of the prismatic pair);
//   link 3 (arm) slides along the sleeve; M = B + l_BM e_r is the gripper point at
//       the arm's front end; the arm's centre of mass is at mid-length,
//       S3 = B + (l_BM - L/2) e_r, L the arm length. The payload is a point mass at M.
// Unit vectors: e_r = (cos phi21 cos phi10, cos phi21 sin phi10, sin phi21),
//   e_phi = (-sin phi10, cos phi10, 0), e_theta = e_phi x e_r... written out:
//   e_theta = (-sin phi21 cos phi10, -sin phi21 sin phi10, cos phi21).
// Inverse kinematics (SPEC §5): l_BM = |M - B|, phi21 = asin((zM - zB)/l_BM),
//   phi10 = atan2(yM, xM). Rates from the spherical components of M' and M'':
//   l' = M'.e_r, phi21' = M'.e_theta / l, phi10' = M'.e_phi / (l cos phi21);
//   a_r = l'' - l phi21'^2 - l phi10'^2 cos^2,  a_theta = l phi21'' + 2 l' phi21' + l phi10'^2 sin cos,
//   a_phi = l phi10'' cos + 2 l' phi10' cos - 2 l phi10' phi21' sin.
// Angular velocities: w1 = phi10' z, w2 = w3 = phi10' z - phi21' e_phi;
//   alpha2 = phi10'' z - phi21'' e_phi + phi21' phi10' e_h, e_h = (cos phi10, sin phi10, 0).
// Kinetostatics: for link k with the pair to its inner neighbour at P_k and to
// the outer one at P_{k+1}, the load (F_k, M_k about P_k) of the inner link on k:
//   F_k = F_{k+1} + m_k (a_Sk - g)
//   M_k = M_{k+1} + (P_{k+1} - P_k) x F_{k+1} + (S_k - P_k) x m_k (a_Sk - g) + I_k alpha_k + w_k x I_k w_k
// (the payload is added to link 3 at M). Drive efforts: F32d = F_3 . e_r (N),
// M21d = M_2 . (-e_phi), M10d = M_1 . z (N m); the rest of each load is the pair's
// reaction. Drive power P = F32d l' + M21d phi21' + M10d phi10'.
#include <array>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/motion_law.hpp"

namespace kinetofem::mech {

// One row of the SPEC §5 data table (SI: m, rad, kg, m/s).
struct SphericalVariant {
  char name = 'A';
  double r_max_m = 0.0, r_min_m = 0.0;  // service zone radii
  double tilt_max_rad = 0.0;            // arm tilt +-phi2
  double height_b_m = 0.0, height_a_m = 0.0;
  double base_rotation_max_rad = 0.0;   // +-phi1
  double m1_kg = 0.0, m2_kg = 0.0, m3_kg = 0.0;
  double speed_mps = 0.0;               // steady speed of M
  double k_accel = 0.0, k_decel = 0.0;  // kP, kT
};

// Variants A-E of SPEC §5.
const std::array<SphericalVariant, 5>& spherical_variants();
const SphericalVariant& spherical_variant(char name);  // throws for an unknown name

// Sizing choices inside the source's ranges (SPEC §5).
struct SphericalSizingOptions {
  double sleeve_ratio = 0.3;            // l2 = (0.2..0.5) l1
  double sleeve_diameter_ratio = 0.3;   // d2 = (0.2..0.4) l2
  double base_diameter_ratio = 1.75;    // d0 = (1.5..2) l_A
  double margin_m = 0.1;                // l1 = r_Mmax + 0.5 l2 + margin
};

// A sized manipulator with its mass data. Inertias (kg m^2, principal, about the
// centre of mass): arm transverse m3 L^2/12 (as the source's kinetostatics) and
// axial 0 (slender); sleeve transverse 0.1 m2 l2^2 (the source's I_S rule), axial 0;
// column about z 0.1 m1 (d0/2)^2 (the source neglects it; an assumption, editable).
struct SphericalDesign {
  SphericalVariant variant;
  double payload_kg = 0.0;
  double arm_length_m = 0.0;       // l1 of SPEC §5 (the sliding arm)
  double sleeve_length_m = 0.0;    // l2
  double sleeve_diameter_m = 0.0;  // d2
  double base_diameter_m = 0.0;    // d0
  double arm_inertia_transverse = 0.0, arm_inertia_axial = 0.0;
  double sleeve_inertia_transverse = 0.0, sleeve_inertia_axial = 0.0;
  double column_inertia_z = 0.0;
  double column_com_height_m = 0.0;  // on the axis; only its weight matters
  double gravity_mps2 = 9.80665;
};

SphericalDesign size_spherical_manipulator(const SphericalVariant& variant, double payload_kg,
                                           const SphericalSizingOptions& options = {});

// Joint coordinates q = (phi10, phi21, l_BM) and their derivatives.
struct SphericalJointMotion {
  Eigen::Vector3d q = Eigen::Vector3d::Zero(), qd = Eigen::Vector3d::Zero(), qdd = Eigen::Vector3d::Zero();
};

Eigen::Vector3d spherical_inverse_kinematics(const SphericalDesign& design, const Eigen::Vector3d& m_world);
Eigen::Vector3d spherical_forward_kinematics(const SphericalDesign& design, const Eigen::Vector3d& q);
SphericalJointMotion spherical_joint_motion(const SphericalDesign& design, const Eigen::Vector3d& m,
                                            const Eigen::Vector3d& m_dot, const Eigen::Vector3d& m_ddot);
// Throws naming the joint when q is outside the variant's zone (reach, tilt, base rotation).
void check_service_zone(const SphericalDesign& design, const Eigen::Vector3d& q, double t);

// Straight segment a -> b travelled with the SPEC §5 trapezoidal law.
class StraightLineMotion {
 public:
  StraightLineMotion(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double speed_mps, double k_accel,
                     double k_decel);
  struct Point {
    Eigen::Vector3d m, m_dot, m_ddot;
  };
  Point at(double t) const;
  double duration() const { return law_.duration(); }
  double length() const { return length_; }
  const TrapezoidalLaw& law() const { return law_; }
  std::vector<double> breakpoints() const;  // 0, tP, T - tT, T

 private:
  Eigen::Vector3d a_, direction_;
  double length_;
  TrapezoidalLaw law_;
};

// Load of the inner link on the outer one in a pair, at the pair's reference
// point (world frame), split into the drive effort and the reaction.
struct PairLoad {
  Eigen::Vector3d force_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment_world = Eigen::Vector3d::Zero();
  Eigen::Vector3d point_world = Eigen::Vector3d::Zero();
  double drive = 0.0;  // along the pair's axis: N (slide) or N m
  Eigen::Vector3d reaction_force = Eigen::Vector3d::Zero();   // force less the drive component
  Eigen::Vector3d reaction_moment = Eigen::Vector3d::Zero();  // moment less the drive component
};

struct SphericalDynamics {
  double t = 0.0;
  SphericalJointMotion joints;
  PairLoad pair32, pair21, pair10;  // on link 3 from 2, on 2 from 1, on 1 from the base
  Eigen::Vector3d drive_power_W = Eigen::Vector3d::Zero();  // (M10d phi10', M21d phi21', F32d l')
  double total_power_W = 0.0;
};

// Kinetostatic inverse dynamics at one joint state.
SphericalDynamics spherical_inverse_dynamics(const SphericalDesign& design, const SphericalJointMotion& motion,
                                             double t = 0.0);
// Drive efforts (M10d, M21d, F32d) only.
Eigen::Vector3d spherical_drive_efforts(const SphericalDesign& design, const SphericalJointMotion& motion);

// Inverse dynamics along a straight-line motion at n + 1 equally spaced times
// (breakpoints of the law included); checks the service zone.
struct SphericalRun {
  std::vector<SphericalDynamics> samples;
  Eigen::Vector3d peak_drive = Eigen::Vector3d::Zero();  // max |effort| per drive (M10d, M21d, F32d)
  Eigen::Vector3d peak_power_W = Eigen::Vector3d::Zero();  // required drive power per drive
};
SphericalRun analyse_straight_line(const SphericalDesign& design, const StraightLineMotion& motion, int n);

// Forward dynamics cross-check: the drive efforts of the inverse dynamics along
// the planned motion drive the manipulator, integrated with CVODES from the
// planned initial state (segment by segment between the law's breakpoints, where
// the efforts jump). Returns the joint states at the given times.
struct SphericalForwardResult {
  std::vector<double> times;
  std::vector<SphericalJointMotion> joints;
  double max_path_deviation_m = 0.0;  // max |M_simulated - M_planned| over the times
  long steps = 0;
};
SphericalForwardResult spherical_forward_dynamics(const SphericalDesign& design, const StraightLineMotion& motion,
                                                  const std::vector<double>& times, double relative_tolerance = 1e-10);

}  // namespace kinetofem::mech
