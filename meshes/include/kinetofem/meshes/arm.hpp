#pragma once
// Link 2 (the arm carrying the gripper) of the manipulators of SPEC §1/§2:
// the arm of the lever-chain manipulator (with the chain roller 2' on A) or
// the coupler AB of the lever manipulator (bores A and B in one hub plate).
//
// Frame (metres): origin at the centre of pin bore A (the joint with lever
// 1); pin axes along Z; the part is symmetric about z = 0. In the design
// position the mechanism's x axis is this x axis, so the points of link 2 are
// A = (0, 0), C = (-c, 0), H = (-c, h) and, for the coupler, B = (d_B, 0)
// (d_B = r of SPEC §2).
//
//   hub, with_roller    roller: disc of radius r, |z| <= e_roller/2, and a
//                       boss of diameter D, |z| <= L/2, both about A
//   hub, coupler        stadium |z| <= L/2: bosses of diameter D about A and
//                       B joined by their tangent planes |y| <= D/2
//   arm plate           -c <= x <= 0, |y| <= w/2, |z| <= t/2
//   gripper bracket     |x + c| <= w_bracket/2, -w/2 <= y <= h - t_mount,
//                       |z| <= t_bracket/2
//   mounting pad        |x + c| <= l_mount/2, h - t_mount <= y <= h,
//                       |z| <= w_mount/2; its face y = h is the gripper mount
//   bores               diameter d_bore through the bosses at A (and B)
//
// In the roller variant the arm plate enters the roller through its rim, so
// the rim is a cylinder face with a window at the plate (angles
// 180 deg +- asin(w/2r) about +x): the chain's wrap arc must avoid it (see
// meshes/geometry/README.md, section "Link 2").
//
// The geometry is meshes/geometry/arm.geo (OpenCASCADE), compiled into the
// library (arm_geometry_text(), geometry_text.hpp); mesh_arm passes these
// dimensions to it as the ONELAB parameters "Arm/<name>" (names in
// arm.cpp). Defaults and the design reasons for them: meshes/geometry/README.md.
//
// Sets of the mesh (physical groups of arm.geo):
//   element set + node set "arm"      the whole part
//   face set + node set "bore_A"      the cylindrical bore surface at A
//   face set + node set "bore_B"      the bore at B (coupler only)
//   face set + node set "roller_rim"  the roller's outer cylinder, where the
//                                     chain wraps (roller variant only)
//   face set + node set "gripper_mount" the pad face y = h (normal +Y)
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

struct ArmDimensions {
  bool with_roller = true;          // true: lever-chain arm (roller); false: lever coupler (bore B)
  double length_m = 0.350;          // c = |AC| (SPEC §1 example)
  double gripper_offset_m = 0.100;  // h: y of the gripper mount face, through H (SPEC §1 example)
  double roller_radius_m = 0.075;     // r, roller radius (roller variant only; SPEC §1 example)
  double roller_thickness_m = 0.030;  // e_roller, roller thickness along z (roller variant only)
  double bore_b_offset_m = 0.075;     // d_B = x of bore B (coupler only; = r of SPEC §2)
  double arm_depth_m = 0.080;         // w, arm plate depth along y
  double arm_thickness_m = 0.025;     // t, arm plate thickness along z
  double bore_diameter_m = 0.040;     // pin bore diameter (A and B)
  double boss_diameter_m = 0.090;     // D, boss outer diameter
  double boss_length_m = 0.050;       // L, boss length along z
  double bracket_width_m = 0.080;     // gripper bracket width along x
  double bracket_thickness_m = 0.025; // gripper bracket thickness along z
  double mount_length_m = 0.080;      // mounting pad length along x
  double mount_width_m = 0.060;       // mounting pad width along z
  double mount_thickness_m = 0.015;   // mounting pad thickness along y

  // Throws Error naming the dimension unless all used dimensions are
  // positive and: d_bore < D; t <= L (the bore cutter would notch a thicker
  // plate); h >= w/2 + t_mount (the pad sits on or above the arm);
  // c - max(w_bracket, l_mount)/2 > the hub radius (r with the roller, D/2
  // without: bracket and pad clear of the hub); with the roller r > D/2 and
  // e_roller < L; without it d_B >= D/2 and d_B > d_bore.
  void validate() const;

  // Exact volume of the solid, m^3 (all pieces are prisms and cylinders and
  // validate() excludes every overlap the formula does not count):
  //   V = V_hub - n_bores pi rb^2 L + w c t - t_overlap
  //       + w_bracket t_bracket (h - t_mount + w/2) - (w_bracket/2) w min(t, t_bracket)
  //       + l_mount t_mount w_mount,
  // rb = d_bore/2, R = D/2;
  //   roller:  V_hub = pi r^2 e_roller + pi R^2 (L - e_roller), n_bores = 1,
  //            t_overlap = min(t, e) S(r)/2 + (t - min(t, e)) S(R)/2, e = e_roller;
  //   coupler: V_hub = L (pi R^2 + 2 R d_B), n_bores = 2, t_overlap = t S(R)/2;
  // S(rho) = area of the disc of radius rho within the strip |y| <= w/2
  //        = 2 (a sqrt(rho^2 - a^2) + rho^2 asin(a/rho)), a = w/2 < rho;
  //        = pi rho^2 otherwise.
  // (t_overlap is the part of the plate inside the hub: half of S on x <= 0.)
  double volume_m3() const;
};

// The defaults above for the lever-chain arm / the lever coupler with the
// mechanism's c, h and r (SPEC §1 and §2 notation, m): the chain arm takes
// roller_radius_m = r, the coupler bore_b_offset_m = r.
ArmDimensions lever_chain_arm(double c_m, double h_m, double r_m);
ArmDimensions lever_coupler(double c_m, double h_m, double r_m);

// Meshes link 2; throws Error for invalid dimensions or options, or if Gmsh
// fails.
fem::Mesh mesh_arm(const ArmDimensions& dimensions, const MeshOptions& options);

}  // namespace kinetofem::meshes
