#pragma once
// The three load-carrying links of the spherical-coordinate manipulator of
// SPEC §5 as parametric steel parts, sized by the SPEC §5 rules, each meshed
// in its own BODY frame (metres) for a stage that puts the spatial multibody
// loads (pair reactions, drive efforts, inertia) on them.
//
// The SPEC gives only l1 (arm), l2 (sleeve), d2 (sleeve diameter), the
// heights z_A, z_B, the tilt range and the masses m1/m2/m3; every other
// dimension is a design choice made by SphericalPartRules (defaults, reasons
// and the numbers of variants A-E: docs/spherical_manipulator_parts.md). The
// wall thickness of each part is chosen so that the steel part's mass equals
// the variant's m1/m2/m3 where a wall between the rules' limits gets there;
// else the limit is taken and `wall_rule` says which (the mass then differs
// from the target; `mass_kg()` is the part's real mass).
//
// Body frames (all three parallel to the world frame of
// spherical_manipulator.hpp at q = (phi10, phi21, l_BM) = (0, 0, l_BM), so a
// pose's rotation is R_z(phi10) for the column and R_z(phi10) R_y(-phi21) for
// the sleeve and the arm):
//
//   column (link 1)  origin on the floor on the base rotation axis, z up (the
//     axis of pair 1-0), y along the tilt pin (pair 2-1), x towards the arm.
//       floor flange   disc radius R_f = d0/2, 0 <= z <= t_f
//       tube           outer radius R1, wall t1, t_f/2 <= z <= z_top, closed
//                      by the flange and by a top plate z_top - t_top .. z_top
//                      (a sealed cavity t_f <= z <= z_top - t_top, r <= R1 - t1)
//       bearing seat   collar radius R1 + h_c, |z - z_seat| <= h_seat/2
//       fork           two lugs y_in <= |y| <= y_in + t_c: |x| <= w/2,
//                      z_top <= z <= z_B, rounded by radius w/2 about the pin
//                      axis, bored d_pin on the pin axis (x, z) = (0, z_B)
//
//                 lug  ___         ___   lug         view along -x
//                     |(o)|  pin  |(o)|  <- z_B      (o) bore d_pin
//                     |   |       |   |
//        top plate  +-+---+-------+---+-+  <- z_top
//           collar [|                   |]  <- z_seat (pair_10)
//           tube    |                   |
//        +----------+-------------------+----------+  <- t_f
//        +---------------------------------------- +  z = 0 (foundation)
//
//   sleeve (link 2)  origin at B on the tilt pin axis, x along the arm axis
//     towards M, y along the tilt pin.
//       tube           outer diameter d2, |x| <= l2/2
//       guide lands    bore D_g (= the arm's outer diameter) over l_g at each
//                      end: l2/2 - l_g <= |x| <= l2/2
//       relief bore    radius d2/2 - t2 between the lands (t2 the wall)
//       trunnions      shoulder diameter d_s from the tube out to |y| = y_in,
//                      journal diameter d_pin over y_in <= |y| <= y_in + t_c,
//                      axis the y axis (they sit in the column's bores)
//
//   arm (link 3)  origin at the gripper point M on the front end face, x along
//     the arm axis pointing FORWARD (out of the sleeve, towards the payload),
//     so the arm lies in -l1 <= x <= 0 and its frame is the sleeve's moved by
//     l_BM along x (no rotation between them).
//       tube           outer diameter D3 = D_g, wall t3, -l1 <= x <= 0, open at
//                      the rear end
//       end plate      the front -t_p <= x <= 0 is solid (it closes the tube)
//       slide          x_s0 <= x <= x_s1: the length that can be in the sleeve
//                      for l_BM in [r_Mmin, r_Mmax]:
//                      x_s0 = -r_Mmax - l2/2, x_s1 = -r_Mmin + l2/2
//
// Sets of the meshes (physical groups of the .geo texts; face set + node set
// each, the element set named after the part):
//   column  "column"; "foundation" the flange's bottom face z = 0 (normal -z);
//           "pair_10" the collar's cylinder R1 + h_c; "pair_21" the two bores
//           of the fork (cylinders of diameter d_pin about (x, z) = (0, z_B)).
//   sleeve  "sleeve"; "pair_21" the two journal cylinders (diameter d_pin
//           about the y axis, y_in <= |y| <= y_in + t_c); "pair_32_front" and
//           "pair_32_rear" the guide lands' bores (diameter D_g about the x
//           axis, at x > 0 and x < 0).
//   arm     "arm"; "slide" the outer cylinder over x_s0 <= x <= x_s1;
//           "gripper_mount" the front end face x = 0 (normal +x).
// The mating faces share their sizes: column bores = sleeve journals
// (d_pin, y_in .. y_in + t_c), sleeve lands = arm diameter (D_g = D3).
//
// The geometries are the OpenCASCADE .geo files meshes/geometry/
// spherical_column.geo, spherical_sleeve.geo, spherical_arm.geo, compiled
// into the library (the *_geometry_text() functions below); mesh_spherical_part
// passes the dimensions as the ONELAB parameters "Column/<name>",
// "Sleeve/<name>", "Arm3/<name>" (names in spherical_parts.cpp).
//
// The mapping from a sized mech::SphericalDesign to SphericalPartSizing is in
// pipeline/spherical_part_sizing.hpp: meshes/ does not depend on mechanisms/.
#include <string_view>

#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

// The SPEC §5 sizes of one manipulator (SI: m, rad, kg).
struct SphericalPartSizing {
  double arm_length_m = 0.0;       // l1 = r_Mmax + 0.5 l2 + 0.1 m
  double sleeve_length_m = 0.0;    // l2 = (0.2..0.5) l1
  double sleeve_diameter_m = 0.0;  // d2 = (0.2..0.4) l2
  double base_diameter_m = 0.0;    // d0, the floor flange's diameter
  double height_a_m = 0.0;         // z_A, the base rotation's bearing
  double height_b_m = 0.0;         // z_B, the tilt pin
  double tilt_max_rad = 0.0;       // +-phi2: the sleeve must clear the column
  double reach_min_m = 0.0;        // r_Mmin, r_Mmax: the range of l_BM the arm
  double reach_max_m = 0.0;        //   slides over
  double column_mass_kg = 0.0;     // m1, m2, m3: the wall thickness targets
  double sleeve_mass_kg = 0.0;
  double arm_mass_kg = 0.0;

  void validate() const;  // throws Error naming the bad size
};

// Design choices the SPEC leaves open (ratios are dimensionless). Reasons:
// docs/spherical_manipulator_parts.md.
struct SphericalPartRules {
  double density_kg_m3 = 7850.0;         // steel
  double arm_diameter_ratio = 0.6;       // D3 / d2 (= guide bore / sleeve diameter)
  double guide_length_ratio = 0.5;       // l_g / D3 (each guide land)
  double pin_diameter_ratio = 0.25;      // d_pin / d2 (tilt pin, trunnion journal)
  double shoulder_diameter_ratio = 1.3;  // d_s / d_pin
  double shoulder_gap_ratio = 0.05;      // (y_in - d2/2) / d2: sleeve to fork cheek
  double cheek_thickness_ratio = 0.6;    // t_c / d_pin (journal length)
  double lug_width_ratio = 2.5;          // w / d_pin
  double end_plate_ratio = 0.1;          // t_p / D3
  double flange_thickness_m = 0.020;     // t_f
  double top_plate_thickness_m = 0.025;  // t_top
  double seat_length_m = 0.050;          // h_seat, bearing seat height
  double seat_collar_m = 0.010;          // h_c, collar radial height
  double lug_margin_m = 0.010;           // R1 beyond the lugs' outer corners
  double tilt_clearance_m = 0.010;       // sleeve to column top at full tilt
  double min_wall_m = 0.004;             // stated minimum wall (all parts)
  double max_wall_fraction = 0.5;        // column and arm wall <= this x outer radius
  double min_relief_m = 0.002;           // sleeve: relief bore >= guide bore + 2 x this

  void validate() const;
};

// Which limit set a wall when the mass target could not be met.
enum class WallRule {
  MassMet,      // the wall gives the target mass
  MinimumWall,  // even min_wall_m is heavier than the target
  MaximumWall,  // even the thickest sensible wall is lighter than the target
};
std::string_view wall_rule_name(WallRule rule);

struct SphericalColumnDimensions {
  double flange_radius_m = 0.0;         // R_f
  double flange_thickness_m = 0.0;      // t_f
  double outer_radius_m = 0.0;          // R1
  double wall_m = 0.0;                  // t1
  double top_m = 0.0;                   // z_top
  double top_plate_thickness_m = 0.0;   // t_top
  double seat_height_m = 0.0;           // z_seat (centre of pair_10)
  double seat_length_m = 0.0;           // h_seat
  double seat_collar_m = 0.0;           // h_c
  double pin_height_m = 0.0;            // z_B
  double pin_diameter_m = 0.0;          // d_pin (bores)
  double cheek_inner_y_m = 0.0;         // y_in
  double cheek_thickness_m = 0.0;       // t_c
  double lug_width_m = 0.0;             // w
  double target_mass_kg = 0.0;          // m1
  WallRule wall_rule = WallRule::MassMet;

  void validate() const;  // throws Error naming the dimension
  // V = pi R_f^2 t_f + pi R1^2 (z_top - t_f) - pi (R1 - t1)^2 (z_top - t_top - t_f)
  //   + pi ((R1 + h_c)^2 - R1^2) h_seat
  //   + 2 t_c (w (z_B - z_top) + pi w^2 / 8 - pi d_pin^2 / 4)
  double volume_m3() const;
};

struct SphericalSleeveDimensions {
  double length_m = 0.0;              // l2
  double outer_diameter_m = 0.0;      // d2
  double wall_m = 0.0;                // t2 (between the lands)
  double guide_diameter_m = 0.0;      // D_g
  double guide_length_m = 0.0;        // l_g
  double pin_diameter_m = 0.0;        // d_pin (journals)
  double shoulder_diameter_m = 0.0;   // d_s
  double journal_start_y_m = 0.0;     // y_in
  double journal_length_m = 0.0;      // t_c
  double target_mass_kg = 0.0;        // m2
  WallRule wall_rule = WallRule::MassMet;

  void validate() const;
  // V = pi r2^2 l2 - pi (D_g/2)^2 2 l_g - pi (r2 - t2)^2 (l2 - 2 l_g)
  //   + 2 (pi a^2 y_in - J(a, r2)) + 2 pi (d_pin/2)^2 t_c,
  // r2 = d2/2, a = d_s/2; J(a, r) = integral over |z| <= a of
  // 2 sqrt(a^2 - z^2) sqrt(r^2 - z^2) dz is the shoulder's volume inside the
  // tube's outer cylinder (an elliptic integral: evaluated to 1e-15 relative by
  // the trapezoidal rule in z = a sin(theta), exponentially convergent).
  double volume_m3() const;
};

struct SphericalArmDimensions {
  double length_m = 0.0;               // l1
  double outer_diameter_m = 0.0;       // D3
  double wall_m = 0.0;                 // t3
  double end_plate_thickness_m = 0.0;  // t_p
  double slide_from_m = 0.0;           // x_s0 (< 0)
  double slide_to_m = 0.0;             // x_s1 (< 0)
  double target_mass_kg = 0.0;         // m3
  WallRule wall_rule = WallRule::MassMet;

  void validate() const;
  // V = pi R3^2 l1 - pi (R3 - t3)^2 (l1 - t_p), R3 = D3/2.
  double volume_m3() const;
};

struct SphericalPartDimensions {
  SphericalColumnDimensions column;
  SphericalSleeveDimensions sleeve;
  SphericalArmDimensions arm;
  double density_kg_m3 = 7850.0;

  void validate() const;  // each part, and that the mating sizes agree
};

enum class SphericalPart { Column, Sleeve, Arm };
// "column", "sleeve", "arm": the element set of the part's mesh.
std::string_view spherical_part_name(SphericalPart part);
double spherical_part_volume_m3(SphericalPart part, const SphericalPartDimensions& dimensions);
// density x volume, kg.
double spherical_part_mass_kg(SphericalPart part, const SphericalPartDimensions& dimensions);

// The parts of a sized manipulator. The column's top is as high as the
// sleeve tilted by +-phi2 allows (clearance tilt_clearance_m):
//   z_top = z_B - (d2/2) / cos(phi2) - R1 tan(phi2) - clearance,
// the bearing seat centred at z_A if it fits below the top plate, else at
// z_top - h_seat. Throws Error if the sizes or rules give an impossible part
// (message naming the dimension).
SphericalPartDimensions spherical_part_dimensions(const SphericalPartSizing& sizing,
                                                  const SphericalPartRules& rules = {});

// Meshes one part in its body frame; throws Error for invalid dimensions or
// options, or if Gmsh fails. The arm's elements are at most 3 walls long
// whatever options.element_size_m says: its tube wall of about 5 mm meshed
// with elements many times longer than it is thick gives TET10 too flat for
// Gmsh's high-order untangling (variant B failed at 30 mm).
fem::Mesh mesh_spherical_part(SphericalPart part, const SphericalPartDimensions& dimensions,
                              const MeshOptions& options);

// The texts of meshes/geometry/spherical_{column,sleeve,arm}.geo (embedded at
// build time, as geometry_text.hpp's).
std::string_view spherical_column_geometry_text();
std::string_view spherical_sleeve_geometry_text();
std::string_view spherical_arm_geometry_text();

}  // namespace kinetofem::meshes
