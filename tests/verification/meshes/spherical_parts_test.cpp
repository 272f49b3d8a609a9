// The SPEC §5 manipulator's parts (spherical_parts.hpp) against their exact
// volumes and the variants' masses.
//
// 1. For every variant A-E (SPEC §5 table, sized as spherical_manipulator.hpp
//    sizes them: l2 = 0.3 l1, d2 = 0.3 l2, d0 = 1.75 z_A), the mass rule meets
//    m1/m2/m3 (steel, 7850 kg/m^3) with walls between the stated limits.
// 2. The TET10 meshes of variant A converge to the exact volume as the element
//    size halves and the elements per circle double (30 mm, 16 -> 15 mm, 32;
//    the arm's size is at most 3 walls, 15 mm, already, so for it the circle
//    count refines): the difference is the interpolation of the
//    curved faces, so it must shrink; a wrong volume formula (a missing
//    shoulder, a wrong land length) would leave a constant difference. The
//    reference's shoulder term is an elliptic integral: its own accuracy
//    (1e-15) is far below what is measured. Measured: column 1.7e-7 ->
//    6.7e-9, sleeve 1.2e-5 -> 7.0e-7, arm 3.2e-6 -> -1.6e-6 (the mesher's
//    noise on the thin wall).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "kinetofem/meshes/spherical_parts.hpp"
#include "kinetofem/solver/assembly.hpp"

namespace kinetofem::meshes {
namespace {

constexpr double pi = std::numbers::pi;

struct Variant {
  char name;
  double r_max, r_min, tilt_deg, z_b, z_a, m1, m2, m3;
};
// SPEC §5 data table.
constexpr Variant kVariants[] = {
    {'A', 2.2, 1.2, 25, 0.7, 0.5, 300, 120, 50},   {'B', 2.0, 1.0, 20, 0.8, 0.6, 250, 120, 40},
    {'C', 1.8, 0.9, 25, 0.75, 0.55, 200, 100, 40}, {'D', 1.9, 0.9, 24, 0.7, 0.45, 200, 100, 35},
    {'E', 1.8, 0.9, 20, 0.8, 0.5, 200, 100, 35}};

SphericalPartSizing sizing(const Variant& v) {
  SphericalPartSizing s;
  s.arm_length_m = (v.r_max + 0.1) / (1 - 0.5 * 0.3);  // l1 = r_Mmax + 0.5 l2 + 0.1, l2 = 0.3 l1
  s.sleeve_length_m = 0.3 * s.arm_length_m;
  s.sleeve_diameter_m = 0.3 * s.sleeve_length_m;
  s.base_diameter_m = 1.75 * v.z_a;
  s.height_a_m = v.z_a;
  s.height_b_m = v.z_b;
  s.tilt_max_rad = v.tilt_deg * pi / 180;
  s.reach_min_m = v.r_min;
  s.reach_max_m = v.r_max;
  s.column_mass_kg = v.m1;
  s.sleeve_mass_kg = v.m2;
  s.arm_mass_kg = v.m3;
  return s;
}

TEST(SphericalPartsVerification, EveryVariantMeetsItsMasses) {
  for (const Variant& v : kVariants) {
    const SphericalPartDimensions d = spherical_part_dimensions(sizing(v));
    std::printf("variant %c: l1 %.4f l2 %.4f d2 %.4f D3 %.4f m | walls column %.4f sleeve %.4f arm %.4f m | "
                "z_top %.4f z_seat %.4f (z_A %.2f) m\n",
                v.name, d.arm.length_m, d.sleeve.length_m, d.sleeve.outer_diameter_m, d.arm.outer_diameter_m,
                d.column.wall_m, d.sleeve.wall_m, d.arm.wall_m, d.column.top_m, d.column.seat_height_m, v.z_a);
    EXPECT_EQ(d.column.wall_rule, WallRule::MassMet) << v.name;
    EXPECT_EQ(d.sleeve.wall_rule, WallRule::MassMet) << v.name;
    EXPECT_EQ(d.arm.wall_rule, WallRule::MassMet) << v.name;
    EXPECT_NEAR(spherical_part_mass_kg(SphericalPart::Column, d), v.m1, 1e-9 * v.m1) << v.name;
    EXPECT_NEAR(spherical_part_mass_kg(SphericalPart::Sleeve, d), v.m2, 1e-9 * v.m2) << v.name;
    EXPECT_NEAR(spherical_part_mass_kg(SphericalPart::Arm, d), v.m3, 1e-9 * v.m3) << v.name;
  }
}

// 3. Every variant's parts mesh (the geometry holds for all five tables' rows:
//    the seat at z_A in D and E, below it in A-C) with every face set, at the
//    volume within the 2e-5 of the unit tests.
TEST(SphericalPartsVerification, EveryVariantMeshesWithItsFaceSets) {
  MeshOptions options;
  options.element_size_m = 0.03;
  options.order = 2;
  for (const Variant& v : kVariants) {
    const SphericalPartDimensions d = spherical_part_dimensions(sizing(v));
    for (SphericalPart part : {SphericalPart::Column, SphericalPart::Sleeve, SphericalPart::Arm}) {
      const std::string name(spherical_part_name(part));
      const fem::Mesh mesh = mesh_spherical_part(part, d, options);
      EXPECT_NO_THROW(fem::check_element_jacobians(mesh)) << v.name << " " << name;
      const double error = fem::mesh_volume(mesh) / spherical_part_volume_m3(part, d) - 1;
      EXPECT_LE(std::abs(error), 2e-5) << v.name << " " << name;
      std::printf("variant %c %s: %ld TET10, volume error %.2e\n", v.name, name.c_str(), long(mesh.element_count()),
                  error);
      std::vector<std::string> sets;
      switch (part) {
        case SphericalPart::Column: sets = {"foundation", "pair_10", "pair_21"}; break;
        case SphericalPart::Sleeve: sets = {"pair_21", "pair_32_front", "pair_32_rear"}; break;
        case SphericalPart::Arm: sets = {"slide", "gripper_mount"}; break;
      }
      for (const auto& set : sets) {
        ASSERT_TRUE(mesh.face_sets.count(set)) << v.name << " " << name << " " << set;
        EXPECT_GT(fem::surface_area(mesh, mesh.face_set(set)), 0.0) << v.name << " " << name << " " << set;
      }
    }
  }
}

TEST(SphericalPartsVerification, MeshVolumesConvergeToTheExactVolumes) {
  const SphericalPartDimensions d = spherical_part_dimensions(sizing(kVariants[0]));
  for (SphericalPart part : {SphericalPart::Column, SphericalPart::Sleeve, SphericalPart::Arm}) {
    double error[2];
    int k = 0;
    for (const auto& [h, per_circle] : {std::pair{0.03, 16}, {0.015, 32}}) {
      MeshOptions options;
      options.element_size_m = h;
      options.elements_per_circle = per_circle;
      options.order = 2;
      const fem::Mesh mesh = mesh_spherical_part(part, d, options);
      error[k] = fem::mesh_volume(mesh) / spherical_part_volume_m3(part, d) - 1;
      std::printf("%s at %.3f m, %d per circle: %ld TET10, volume error %.3e relative\n",
                  std::string(spherical_part_name(part)).c_str(), h, per_circle, long(mesh.element_count()), error[k]);
      ++k;
    }
    // The finer mesh at most half the coarse error, unless both are at the
    // level of the mesher's own noise (nodes placed within OpenCASCADE's
    // 1e-7 m of the surfaces; seen up to 3.2e-6 on the arm's thin wall at
    // any size, 1.7e-7 on the column), and both within 2e-5.
    EXPECT_LE(std::abs(error[1]), std::max(0.5 * std::abs(error[0]), 3.5e-6)) << spherical_part_name(part);
    EXPECT_LE(std::abs(error[0]), 2e-5) << spherical_part_name(part);
  }
}

}  // namespace
}  // namespace kinetofem::meshes
