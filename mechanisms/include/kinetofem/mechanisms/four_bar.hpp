#pragma once
// Planar hinged four-bar A0-A-B-B0 (SPEC §2, the "lever manipulator").
//
// Links: ground A0B0 (length l0), crank/lever A0A (a, the input, absolute angle
// phi from +X), coupler AB (l2, carries coupler points such as C and H), rocker
// B0B (l3). Frame: any fixed planar frame; SI units (m, rad); angles
// counter-clockwise from +X.
//
// Loop closure and its derivatives w.r.t. the input angle phi:
//   Phi(phi) = A(phi) + l2 e(th2) - l3 e(th3) - B0 = 0,  A = A0 + a e(phi)
//   [l2 e'(th2), -l3 e'(th3)] [th2'; th3']  = -A'
//   [l2 e'(th2), -l3 e'(th3)] [th2''; th3''] = -A'' + l2 th2'^2 e(th2) - l3 th3'^2 e(th3)
// with e(t) = (cos t, sin t), e'(t) = (-sin t, cos t). The matrix is singular
// exactly where coupler and rocker are collinear (transmission angle 0 or 180
// deg), i.e. at the limits of assembly.
//
// Position: th2 = atan2(B0 - A) + k acos((l2^2 + |B0 - A|^2 - l3^2)/(2 l2 |B0 - A|)),
// k = +-1 the assembly branch. k is fixed from the design position; along a
// motion inside one assembly interval the configuration stays on that branch
// (branches meet only at the limits, where |cos| = 1), so the branch chosen by
// continuity from the design position is the one with the design's k.
//
// Assembly margin: m(phi) = min(|B0 - A| - |l2 - l3|, l2 + l3 - |B0 - A|) >= 0.
// Limits of assembly are its roots, found by stepping from the design input
// and bisecting each sign change.
#include <cstddef>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/mechanisms/lever_chain.hpp"
#include "kinetofem/mechanisms/path_straightness.hpp"

namespace kinetofem::mech {

enum class GrashofClass {
  crank_rocker,    // s + l < p + q, shortest = input crank: the crank turns fully
  rocker_crank,    // shortest = output rocker: the output turns fully
  double_crank,    // shortest = ground
  double_rocker,   // shortest = coupler (Grashof double rocker)
  change_point,    // s + l = p + q (within 1e-12 relative)
  triple_rocker,   // non-Grashof: s + l > p + q, no link turns fully
};
std::string_view to_string(GrashofClass c);

struct FourBarPose {
  double input_rad = 0.0;
  Eigen::Vector2d a_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d b_m = Eigen::Vector2d::Zero();
  double coupler_angle_rad = 0.0, coupler_d1 = 0.0, coupler_d2 = 0.0;  // th2
  double rocker_angle_rad = 0.0, rocker_d1 = 0.0, rocker_d2 = 0.0;     // th3 (B0->B)
  double transmission_angle_rad = 0.0;  // angle ABB0 in [0, pi]
  std::vector<PointKinematics> coupler_points;  // in the order they were added
};

// Input-angle interval around the design input inside which the linkage
// assembles on its design branch. full_rotation: the crank turns fully.
struct AssemblyRange {
  bool full_rotation = false;
  double lo_rad = 0.0;  // absolute input angles of the limits (lo < design < hi)
  double hi_rad = 0.0;
};

class FourBar {
 public:
  // From the design-position points; the lengths, the design input angle and
  // the branch are taken from them. Throws when a length is zero or the design
  // position is a limit of assembly (coupler and rocker collinear).
  static FourBar from_design_position(const Eigen::Vector2d& a0_m, const Eigen::Vector2d& a_m,
                                      const Eigen::Vector2d& b_m, const Eigen::Vector2d& b0_m);

  // Adds a point fixed to the coupler, given at its design position; returns its index.
  std::size_t add_coupler_point(const Eigen::Vector2d& p_design_m);

  double ground_length_m() const { return (b0_ - a0_).norm(); }
  double crank_length_m() const { return a_len_; }
  double coupler_length_m() const { return l2_; }
  double rocker_length_m() const { return l3_; }
  double design_input_rad() const { return phi_design_; }
  int branch() const { return branch_; }

  GrashofClass grashof() const;
  double assembly_margin_m(double input_rad) const;
  bool can_assemble(double input_rad) const { return assembly_margin_m(input_rad) > 0.0; }

  // Pose on the design branch; throws naming the input when it does not assemble.
  FourBarPose pose(double input_rad) const;
  // pose(design_input + rotation).
  FourBarPose pose_at_rotation(double rotation_rad) const {
    return pose(phi_design_ + rotation_rad);
  }

  // Limits found by steps of step_rad from the design input, then bisection to
  // tol_rad on the assembly margin.
  AssemblyRange assembly_range(double step_rad = 0.25 * 3.141592653589793 / 180.0,
                               double tol_rad = 1e-12) const;

 private:
  FourBar() = default;
  Eigen::Vector2d a0_ = Eigen::Vector2d::Zero();
  Eigen::Vector2d b0_ = Eigen::Vector2d::Zero();
  double a_len_ = 0.0, l2_ = 0.0, l3_ = 0.0;
  double phi_design_ = 0.0;
  double coupler_design_rad_ = 0.0;
  int branch_ = 1;
  std::vector<Eigen::Vector2d> coupler_local_;  // in the coupler frame at A
};

// The four-bar equivalent (up to second derivatives in the design position,
// SPEC §2) to a lever-chain manipulator: A0 = (0,0), A = (0,a), B = (r,a),
// B0 = (r, a - b0); coupler point 0 is C = (-c, a), point 1 is H = (-c, a + h).
// The lever rotation dphi of §1 is the four-bar's rotation from the design input
// (pi/2), and the coupler angle equals §1's arm angle theta = dphi + dpsi.
FourBar make_equivalent_four_bar(const LeverChainGeometry& geometry);

// Side-by-side study of the lever-chain mechanism and its equivalent four-bar
// for the same lever motion dphi in [dphi_lo, dphi_hi] (n samples). Straightness
// of H's path is measured from the horizontal design tangent y = a + h.
struct LeverVsFourBarSample {
  double dphi_rad = 0.0;
  Eigen::Vector2d h_lever_chain_m = Eigen::Vector2d::Zero();
  bool four_bar_assembles = false;
  Eigen::Vector2d h_four_bar_m = Eigen::Vector2d::Zero();      // valid if assembled
  double transmission_angle_four_bar_rad = 0.0;                // valid if assembled
  double transmission_angle_lever_chain_rad = 0.0;             // pi/2 by construction
};
struct LeverVsFourBarStudy {
  std::vector<LeverVsFourBarSample> samples;
  AssemblyRange four_bar_range_dphi;  // limits as lever rotations from design
  HorizontalStraightness h_lever_chain;
  HorizontalStraightness h_four_bar;  // on the assembled part containing dphi = 0
  double h_extent_lever_chain_m = 0.0;
  double h_extent_four_bar_m = 0.0;
  double min_transmission_angle_four_bar_rad = 0.0;  // over assembled samples
  double max_transmission_angle_four_bar_rad = 0.0;
};
LeverVsFourBarStudy compare_lever_chain_with_four_bar(const LeverChainGeometry& geometry,
                                                      double dphi_lo_rad, double dphi_hi_rad,
                                                      std::size_t n, double window_length_m);

}  // namespace kinetofem::mech
