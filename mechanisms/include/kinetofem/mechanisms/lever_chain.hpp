#pragma once
// Lever-chain manipulator (SPEC §1; source: seeds/001, Slavkov, Savchev, Galabov).
//
// The casting extractor's primary chain is lever 1 (A0A = a, pivot A0 on the
// frame) and arm 2 (hinged at A, carries C and the gripper point H). Arm 2 is
// driven by a flexible link 3 (chain, belt, rope) hinged to the frame at B0 and
// wrapped on a roller 2' of radius r fixed to arm 2 at A.
//
// Frame and units: origin at A0, Y parallel to the die-casting machine axis,
// X horizontal; SI units (m, rad). In the design position (dphi = 0) lever 1
// lies on +Y, the free straight chain is parallel to it at distance r:
//
//        C=(-c,a)     A=(0,a)  B=(r,a)         H = C + h*(-sin th, cos th)
//          o-----------o--------o  tangent      C = A - c*(cos th, sin th)
//                      |        |  point        th = dphi + dpsi (arm 2 angle)
//                 lever 1 (a)   | chain b0
//                      |        o B0=(r, a-b0)
//                      o A0=(0,0)
//
// Design-position geometry:
//   (1) b0 = a c / (c + r)        (2) l0 = sqrt((a - b0)^2 + r^2)
//   (3) alpha0 = arccos(r / l0)   B0 = l0 (cos alpha0, sin alpha0) = (r, a - b0)
// Position function of the control mechanism (input dphi, counter-clockwise
// positive; output dpsi = rotation of roller/arm 2 relative to lever 1):
//   (6) d = sqrt(l0^2 + a^2 - 2 l0 a sin(alpha0 - dphi))     = |A B0|
//   (5) b = sqrt(d^2 - r^2)                                   free chain length
//   (7) beta = atan(b / r) + asin(l0 cos(alpha0 - dphi) / d)  (beta0 = pi/2)
//   (4) dpsi = (b0 - b)/r - beta0 + beta
// The asin term of (7) is the angle, in lever 1's frame, between -Y and the
// vector A->B0; it is evaluated as atan2(l0 cos u, a - l0 sin u), u = alpha0 - dphi,
// which equals the asin wherever (7) is valid (l0 < a) and stays continuous
// otherwise.
//
// Derivatives w.r.t. dphi are derived analytically from (4)-(7) and (12), (15);
// the source's printed transfer functions (9)-(11), (13), (14), (16), (17) use
// the inverted input -dphi and have sign errors (SPEC §1 warning), so they are
// not used. Useful closed forms (N = l0 sin u, M = l0 cos u):
//   d d' = a M,   b b' = d d',   (atan2 term)' = (a N - l0^2)/d^2,
//   (atan2 term)'' = -a M (a^2 - l0^2)/d^4,   (atan(b/r))' = r b'/d^2.
//
// Published trajectory range (documented choice, see lever_chain_published_range):
// the source (fig. 4) gives horizontal extents 1230 mm (C, h = 0) and 1270 mm
// (H, h = 100 mm) but not the lever range. Over dphi in [+86 deg, +inf) C and
// H pass their leftmost points (x_C = -788.7 mm, x_H = -733.7 mm), so any upper
// limit >= 86 deg gives the same left end; the right end then fixes the lower
// limit: 1230 mm for C needs dphi_min = -73.1 deg and 1270 mm for H needs
// -72.8 deg (x moves about 16 mm per degree there). One lower limit, -73 deg,
// reproduces both numbers to within their printed precision (C 1228.5 mm,
// H 1272.8 mm; two published numbers, one unknown), so the drawn range is taken as
// dphi in [-73 deg, +90 deg] (lever from 73 deg clockwise of +Y to horizontal).
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace kinetofem::mech {

// A point of a one-DOF mechanism and its first and second derivatives with
// respect to the input angle (m, m/rad, m/rad^2).
struct PointKinematics {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  Eigen::Vector2d d1 = Eigen::Vector2d::Zero();
  Eigen::Vector2d d2 = Eigen::Vector2d::Zero();
};

// Velocity and acceleration of a point for input rate dphi_dot (rad/s) and
// input acceleration dphi_ddot (rad/s^2), SPEC (18)-(20):
//   v = dphi_dot P',  a = dphi_dot^2 P'' + dphi_ddot P',
//   speed = dphi_dot S' with S' = |P'|,
//   tangential acceleration = dphi_dot^2 S'' + dphi_ddot S' with S'' = P'.P''/|P'|
//   (the arc length's second derivative; the source's (20) prints |P''| instead,
//   which is neither the tangential nor the total acceleration).
struct PointMotion {
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
  Eigen::Vector2d acceleration_mps2 = Eigen::Vector2d::Zero();
  double speed_mps = 0.0;                   // signed: dphi_dot * |P'|
  double tangential_acceleration_mps2 = 0.0;
};
PointMotion point_motion(const PointKinematics& k, double dphi_dot_radps,
                         double dphi_ddot_radps2);

struct LeverChainGeometry {
  double a_m = 0.0;          // lever 1, |A0 A|
  double r_m = 0.0;          // roller radius
  double c_m = 0.0;          // |A C| along arm 2
  double h_m = 0.0;          // offset of H from C, perpendicular to arm 2
  double b0_m = 0.0;         // (1) free chain length in the design position
  double l0_m = 0.0;         // (2) frame length |A0 B0|
  double alpha0_rad = 0.0;   // (3) angle of A0B0 with X
  Eigen::Vector2d b0_point_m = Eigen::Vector2d::Zero();  // B0 = (r, a - b0)
};

// Builds the design-position geometry (1)-(3). Throws unless a, c, r > 0 and
// h >= 0 (finite).
LeverChainGeometry make_lever_chain_geometry(double a_m, double c_m, double h_m, double r_m);

// The published example of SPEC §1 (a = 500, c = 350, h = 100, r = 75 mm):
// the default dimensions of every case type built on the lever-chain
// geometry (manipulator, lever_chain_kinematics, four_bar_study).
struct LeverChainExample {
  static constexpr double a_m = 0.500, c_m = 0.350, h_m = 0.100, r_m = 0.075;
};

// Synthesis of the primary chain (SPEC §1, source fig. 2). Given the design and
// final positions H0, Hf of H and the lever rotation phi_of between them:
// Hf1 = R(-phi_of) Hf (Hf seen from lever 1), A = (0, a) is the point of the Y
// axis equidistant from H0 and Hf1 (the perpendicular bisector of H0-Hf1, slope
// k_m = (x_H0 - x_Hf1)/(y_Hf1 - y_H0), crosses Y at y_A = y_M - k_m x_M);
// c = -x_H0, h = y_H0 - a (the source prints k_m with '+' signs and
// h = x_H0 - x_A, both misprints: with (12), (15) at dphi = 0, H0 = (-c, a + h)).
struct PrimaryChainSynthesis {
  double a_m = 0.0;
  double c_m = 0.0;
  double h_m = 0.0;
  Eigen::Vector2d hf_in_lever_frame_m = Eigen::Vector2d::Zero();  // Hf1
  Eigen::Vector2d midpoint_m = Eigen::Vector2d::Zero();           // M
};
PrimaryChainSynthesis synthesize_primary_chain(const Eigen::Vector2d& h0_m,
                                               const Eigen::Vector2d& hf_m,
                                               double phi_of_rad);
// The synthesis followed by (1)-(3) for the chosen roller radius.
LeverChainGeometry synthesize_lever_chain(const Eigen::Vector2d& h0_m,
                                          const Eigen::Vector2d& hf_m, double phi_of_rad,
                                          double r_m);

// State of the control mechanism (frame 0 - chain 3 - roller 2', relative to
// lever 1) and its derivatives w.r.t. dphi.
struct LeverChainCtm {
  double d_m = 0.0, d_d1 = 0.0, d_d2 = 0.0;          // |A B0|
  double b_m = 0.0, b_d1 = 0.0, b_d2 = 0.0;          // free chain length
  double beta_rad = 0.0, beta_d1 = 0.0, beta_d2 = 0.0;  // chain angle, lever frame
  double dpsi_rad = 0.0, dpsi_d1 = 0.0, dpsi_d2 = 0.0;  // (4) and derivatives
};

struct LeverChainPose {
  double dphi_rad = 0.0;
  LeverChainCtm ctm;
  double theta_rad = 0.0, theta_d1 = 0.0, theta_d2 = 0.0;  // arm 2: dphi + dpsi
  double chain_angle_rad = 0.0;  // absolute angle of the free chain B->B0 with X
  PointKinematics a;             // (0,a) rotated by dphi
  PointKinematics c;             // (12)
  PointKinematics h;             // (15)
  PointKinematics tangent_point; // B: last contact point on the roller (moves on it)
};

class LeverChain {
 public:
  explicit LeverChain(const LeverChainGeometry& geometry);

  const LeverChainGeometry& geometry() const { return geometry_; }

  // True when the chain can be tangent to the roller: d(dphi) > r.
  bool can_assemble(double dphi_rad) const;
  // (4)-(7) and derivatives. Throws naming dphi when d <= r.
  LeverChainCtm ctm(double dphi_rad) const;
  // Full pose with points A, B, C, H and derivatives. Throws as ctm().
  LeverChainPose pose(double dphi_rad) const;

 private:
  LeverChainGeometry geometry_;
};

// Positions of C and H over n samples (n >= 2) of dphi in [dphi_lo, dphi_hi].
struct LeverChainPath {
  std::vector<double> dphi_rad;
  std::vector<Eigen::Vector2d> c_m;
  std::vector<Eigen::Vector2d> h_m;
};
LeverChainPath sample_lever_chain_path(const LeverChain& mechanism, double dphi_lo_rad,
                                       double dphi_hi_rad, std::size_t n);

// The lever range over which the source's fig. 4 trajectories are drawn
// (documented above): dphi in [-73 deg, +90 deg].
struct LeverRange {
  double lo_rad;
  double hi_rad;
};
LeverRange lever_chain_published_range();

}  // namespace kinetofem::mech
