// spherical_part_dimensions and mesh_spherical_part: the column, sleeve and
// arm of the SPEC §5 manipulator sized for variant A, meshed with TET10 at a
// coarse size: the SPEC sizing rules, the mass rule, valid meshes of the
// analytic volume, every face set where the header puts it, the mating sizes,
// the column clear of the tilted sleeve, the wall limits and bad inputs named.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/spherical_parts.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;
constexpr double pi = std::numbers::pi;

// SPEC §5 variant A with the sizing of spherical_manipulator.hpp written out
// here (k = l2/l1 = 0.3, d2/l2 = 0.3, d0 = 1.75 z_A, margin 0.1 m):
// l1 = (r_Mmax + 0.1) / (1 - 0.5 k).
SphericalPartSizing variant_a() {
  SphericalPartSizing s;
  s.arm_length_m = (2.2 + 0.1) / (1 - 0.5 * 0.3);
  s.sleeve_length_m = 0.3 * s.arm_length_m;
  s.sleeve_diameter_m = 0.3 * s.sleeve_length_m;
  s.base_diameter_m = 1.75 * 0.5;
  s.height_a_m = 0.5;
  s.height_b_m = 0.7;
  s.tilt_max_rad = 25 * pi / 180;
  s.reach_min_m = 1.2;
  s.reach_max_m = 2.2;
  s.column_mass_kg = 300;
  s.sleeve_mass_kg = 120;
  s.arm_mass_kg = 50;
  return s;
}

MeshOptions coarse() {
  MeshOptions options;
  options.element_size_m = 0.03;  // coarse: each part meshes in seconds
  options.order = 2;
  return options;
}

// Nodes are placed on the OpenCASCADE surfaces: 1e-7 m is its tolerance.
constexpr double on_surface = 1e-7;

// The quadratic mesh differs from the solid only where its curved faces
// interpolate cylinders (16 elements per circle). Measured at 30 mm for
// variant A: column 1.7e-7, sleeve 1.2e-5 (the trunnion shoulders' saddle
// curves on the tube), arm 3.2e-6 (meshed at 3 walls, 15 mm, whatever the
// size asked) relative; the first two shrink with the element size
// (tests/verification/meshes/spherical_parts_test.cpp); 2e-5.
constexpr double volume_tolerance = 2e-5;

// Face areas: TRI6 faces interpolate the cylinders and the circular edges of
// the flat discs and annuli; measured worst 5e-5 relative (the gripper
// mount's disc at 30 mm), so 1e-4.
constexpr double area_tolerance = 1e-4;

double radius_about_x(const fem::Mesh& m, Index v) { return std::hypot(m.nodes(v, 1), m.nodes(v, 2)); }

// Face set `name` exists, is one TRI6 block, and every face's normal points
// out of the material as `outward(centroid, normal)` says.
template <class Outward>
void expect_faces(const fem::Mesh& mesh, const std::string& name, Outward outward) {
  ASSERT_TRUE(mesh.face_sets.count(name)) << name;
  const auto& faces = mesh.face_set(name);
  ASSERT_EQ(faces.size(), 1u) << name;
  ASSERT_GT(faces[0].size(), 0) << name;
  EXPECT_EQ(faces[0].type, fem::FaceType::Tri6) << name;
  ASSERT_FALSE(mesh.node_set(name).empty()) << name;
  for (Index f = 0; f < faces[0].size(); ++f) {
    const auto face = faces[0].face(f);
    EXPECT_TRUE(outward(testing::face_centroid(mesh, face, 3), testing::face_normal(mesh, face)))
        << name << " face " << f;
  }
}

void expect_valid_part(const fem::Mesh& mesh, SphericalPart part, const SphericalPartDimensions& d) {
  const std::string name(spherical_part_name(part));
  ASSERT_EQ(mesh.blocks.size(), 1u);
  ASSERT_EQ(mesh.blocks[0].type, fem::ElementType::Tet10);
  EXPECT_EQ(mesh.element_sets.at(name).size(), std::size_t(mesh.element_count()));
  EXPECT_NO_THROW(fem::check_element_jacobians(mesh));
  const double volume = fem::mesh_volume(mesh);
  std::printf("%s: %ld nodes, %ld elements, mesh volume %.9g m^3, analytic %.9g m^3 (rel. error %.2e), "
              "mass %.4f kg\n",
              name.c_str(), long(mesh.node_count()), long(mesh.element_count()), volume,
              spherical_part_volume_m3(part, d), volume / spherical_part_volume_m3(part, d) - 1,
              d.density_kg_m3 * volume);
  EXPECT_NEAR(volume / spherical_part_volume_m3(part, d), 1.0, volume_tolerance);
}

TEST(SphericalParts, VariantADimensionsFollowTheSpecRules) {
  const SphericalPartSizing s = variant_a();
  const SphericalPartDimensions d = spherical_part_dimensions(s);
  // SPEC §5: l1 = r_Mmax + 0.5 l2 + 0.1 m.
  EXPECT_NEAR(d.arm.length_m, 2.2 + 0.5 * d.sleeve.length_m + 0.1, 1e-12);
  EXPECT_NEAR(d.sleeve.length_m, 0.3 * d.arm.length_m, 1e-12);
  EXPECT_NEAR(d.sleeve.outer_diameter_m, 0.3 * d.sleeve.length_m, 1e-12);
  EXPECT_EQ(d.column.pin_height_m, 0.7);
  EXPECT_EQ(d.column.flange_radius_m, 0.875 / 2);
  // The mass rule: every wall gives the variant's mass (kg) to bisection accuracy.
  EXPECT_EQ(d.column.wall_rule, WallRule::MassMet);
  EXPECT_EQ(d.sleeve.wall_rule, WallRule::MassMet);
  EXPECT_EQ(d.arm.wall_rule, WallRule::MassMet);
  EXPECT_NEAR(spherical_part_mass_kg(SphericalPart::Column, d), 300.0, 1e-9);
  EXPECT_NEAR(spherical_part_mass_kg(SphericalPart::Sleeve, d), 120.0, 1e-9);
  EXPECT_NEAR(spherical_part_mass_kg(SphericalPart::Arm, d), 50.0, 1e-9);
  std::printf("walls: column %.4f m, sleeve %.4f m, arm %.4f m; column top %.4f m, seat at %.4f m\n",
              d.column.wall_m, d.sleeve.wall_m, d.arm.wall_m, d.column.top_m, d.column.seat_height_m);
  // The arm's wall by hand from its mass: pi (R^2 - (R - t)^2) (l1 - t_p) + pi R^2 t_p = m3 / rho.
  const double r3 = d.arm.outer_diameter_m / 2, tp = d.arm.end_plate_thickness_m, l1 = d.arm.length_m;
  const double ri = std::sqrt(r3 * r3 - (50.0 / 7850 - pi * r3 * r3 * tp) / (pi * (l1 - tp)));
  EXPECT_NEAR(d.arm.wall_m, r3 - ri, 1e-12);
  // The mating sizes.
  EXPECT_EQ(d.sleeve.guide_diameter_m, d.arm.outer_diameter_m);
  EXPECT_EQ(d.column.pin_diameter_m, d.sleeve.pin_diameter_m);
  EXPECT_EQ(d.column.cheek_inner_y_m, d.sleeve.journal_start_y_m);
  // The slide: the arm's length in the sleeve for l_BM = r_Mmax .. r_Mmin.
  EXPECT_NEAR(d.arm.slide_from_m, -2.2 - d.sleeve.length_m / 2, 1e-12);
  EXPECT_NEAR(d.arm.slide_to_m, -1.2 + d.sleeve.length_m / 2, 1e-12);
  // Variant A's B is only 0.2 m above A: the tilted sleeve pushes the top
  // below A, and the seat goes as high as it can.
  EXPECT_LT(d.column.top_m, 0.5);
  EXPECT_NEAR(d.column.seat_height_m, d.column.top_m - d.column.seat_length_m, 1e-12);
}

TEST(SphericalParts, SeatAtHeightAWhereTheSleeveLeavesRoom) {
  SphericalPartSizing s = variant_a();
  s.height_b_m = 0.9;  // B 0.4 m above A
  const SphericalPartDimensions d = spherical_part_dimensions(s);
  EXPECT_EQ(d.column.seat_height_m, 0.5);
}

TEST(SphericalParts, ColumnMeshAndFaces) {
  const SphericalPartDimensions d = spherical_part_dimensions(variant_a());
  const auto& c = d.column;
  const auto mesh = mesh_spherical_part(SphericalPart::Column, d, coarse());
  expect_valid_part(mesh, SphericalPart::Column, d);
  EXPECT_NEAR(d.density_kg_m3 * fem::mesh_volume(mesh), 300.0, 300.0 * volume_tolerance);

  // foundation: the flange's bottom disc z = 0, normal -z, area pi R_f^2 (flat: exact).
  expect_faces(mesh, "foundation", [](const Eigen::Vector3d&, const Eigen::Vector3d& n) { return n.z() < 0; });
  for (Index v : mesh.node_set("foundation")) EXPECT_NEAR(mesh.nodes(v, 2), 0.0, on_surface);
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("foundation")) / (pi * c.flange_radius_m * c.flange_radius_m),
              1.0, area_tolerance);

  // pair_10: the collar's cylinder about z, radius R1 + h_c, centred at z_seat.
  const double rc = c.outer_radius_m + c.seat_collar_m;
  expect_faces(mesh, "pair_10", [](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
    return n.x() * x.x() + n.y() * x.y() > 0;
  });
  for (Index v : mesh.node_set("pair_10")) {
    EXPECT_NEAR(std::hypot(mesh.nodes(v, 0), mesh.nodes(v, 1)), rc, on_surface) << v;
    EXPECT_LE(std::abs(mesh.nodes(v, 2) - c.seat_height_m), c.seat_length_m / 2 + on_surface) << v;
  }
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("pair_10")) / (2 * pi * rc * c.seat_length_m), 1.0, area_tolerance);

  // pair_21: the two bores, axis along y through (x, z) = (0, z_B), normals
  // towards the axis, both lugs.
  const double y_out = c.cheek_inner_y_m + c.cheek_thickness_m;
  expect_faces(mesh, "pair_21", [&](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
    return n.x() * x.x() + n.z() * (x.z() - c.pin_height_m) < 0;
  });
  int positive = 0, negative = 0;
  for (Index v : mesh.node_set("pair_21")) {
    EXPECT_NEAR(std::hypot(mesh.nodes(v, 0), mesh.nodes(v, 2) - c.pin_height_m), c.pin_diameter_m / 2, on_surface);
    const double y = std::abs(mesh.nodes(v, 1));
    EXPECT_GE(y, c.cheek_inner_y_m - on_surface);
    EXPECT_LE(y, y_out + on_surface);
    (mesh.nodes(v, 1) > 0 ? positive : negative)++;
  }
  EXPECT_GT(positive, 0);
  EXPECT_GT(negative, 0);
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("pair_21")) / (2 * pi * c.pin_diameter_m * c.cheek_thickness_m),
              1.0, area_tolerance);
}

TEST(SphericalParts, ColumnClearsTheSleeveAtFullTilt) {
  const SphericalPartSizing s = variant_a();
  const SphericalPartDimensions d = spherical_part_dimensions(s);
  const auto mesh = mesh_spherical_part(SphericalPart::Column, d, coarse());
  // The sleeve (radius r2, |y| <= r2) tilted by +-phi2 about the pin reaches
  // down to z_B - r2/cos(phi2) - |x| tan(phi2): every column node below it
  // by the clearance (10 mm), the lugs (|y| > r2) aside.
  const double r2 = d.sleeve.outer_diameter_m / 2, phi = s.tilt_max_rad;
  double nearest = 1e9;
  for (Index v = 0; v < mesh.node_count(); ++v) {
    if (std::abs(mesh.nodes(v, 1)) > r2) continue;
    const double lowest_sleeve = s.height_b_m - r2 / std::cos(phi) - std::abs(mesh.nodes(v, 0)) * std::tan(phi);
    nearest = std::min(nearest, lowest_sleeve - mesh.nodes(v, 2));
  }
  EXPECT_GE(nearest, 0.010 - on_surface);
  // ... and not by more: the top plate is as high as the tilt allows (its
  // rim, up to the chord of the coarse mesh).
  EXPECT_LT(nearest, 0.012);
}

TEST(SphericalParts, SleeveMeshAndFaces) {
  const SphericalPartDimensions d = spherical_part_dimensions(variant_a());
  const auto& s = d.sleeve;
  const auto mesh = mesh_spherical_part(SphericalPart::Sleeve, d, coarse());
  expect_valid_part(mesh, SphericalPart::Sleeve, d);
  EXPECT_NEAR(d.density_kg_m3 * fem::mesh_volume(mesh), 120.0, 120.0 * volume_tolerance);
  // The tube spans |x| <= l2/2 (flat ends: exact), centred on B.
  EXPECT_NEAR(mesh.nodes.col(0).minCoeff(), -s.length_m / 2, 1e-9);
  EXPECT_NEAR(mesh.nodes.col(0).maxCoeff(), s.length_m / 2, 1e-9);
  EXPECT_NEAR(mesh.nodes.col(1).maxCoeff(), s.journal_start_y_m + s.journal_length_m, 1e-9);

  // pair_21: the journals, axis the y axis, on both sides.
  expect_faces(mesh, "pair_21", [](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
    return n.x() * x.x() + n.z() * x.z() > 0;
  });
  int positive = 0, negative = 0;
  for (Index v : mesh.node_set("pair_21")) {
    EXPECT_NEAR(std::hypot(mesh.nodes(v, 0), mesh.nodes(v, 2)), s.pin_diameter_m / 2, on_surface);
    const double y = std::abs(mesh.nodes(v, 1));
    EXPECT_GE(y, s.journal_start_y_m - on_surface);
    EXPECT_LE(y, s.journal_start_y_m + s.journal_length_m + on_surface);
    (mesh.nodes(v, 1) > 0 ? positive : negative)++;
  }
  EXPECT_GT(positive, 0);
  EXPECT_GT(negative, 0);

  // pair_32_front / _rear: the guide lands, diameter D_g about the x axis,
  // normals towards the axis, over l_g at x > 0 / x < 0.
  for (const auto& [name, sign] : {std::pair{"pair_32_front", 1.0}, {"pair_32_rear", -1.0}}) {
    expect_faces(mesh, name, [](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
      return n.y() * x.y() + n.z() * x.z() < 0;
    });
    for (Index v : mesh.node_set(name)) {
      EXPECT_NEAR(radius_about_x(mesh, v), s.guide_diameter_m / 2, on_surface) << name;
      EXPECT_GE(sign * mesh.nodes(v, 0), s.length_m / 2 - s.guide_length_m - on_surface) << name;
      EXPECT_LE(sign * mesh.nodes(v, 0), s.length_m / 2 + on_surface) << name;
    }
    EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set(name)) / (pi * s.guide_diameter_m * s.guide_length_m), 1.0,
                area_tolerance)
        << name;
  }
}

TEST(SphericalParts, ArmMeshAndFaces) {
  const SphericalPartDimensions d = spherical_part_dimensions(variant_a());
  const auto& a = d.arm;
  const auto mesh = mesh_spherical_part(SphericalPart::Arm, d, coarse());
  expect_valid_part(mesh, SphericalPart::Arm, d);
  EXPECT_NEAR(d.density_kg_m3 * fem::mesh_volume(mesh), 50.0, 50.0 * volume_tolerance);
  // M at the origin on the front face; the arm behind it along -x.
  EXPECT_NEAR(mesh.nodes.col(0).maxCoeff(), 0.0, 1e-9);
  EXPECT_NEAR(mesh.nodes.col(0).minCoeff(), -a.length_m, 1e-9);

  // slide: the outer cylinder over x_s0..x_s1 only (not the bore, not the
  // piece boundaries), normals away from the axis, area pi D3 (x_s1 - x_s0).
  expect_faces(mesh, "slide", [](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
    return n.y() * x.y() + n.z() * x.z() > 0;
  });
  for (Index v : mesh.node_set("slide")) {
    EXPECT_NEAR(radius_about_x(mesh, v), a.outer_diameter_m / 2, on_surface);
    EXPECT_GE(mesh.nodes(v, 0), a.slide_from_m - on_surface);
    EXPECT_LE(mesh.nodes(v, 0), a.slide_to_m + on_surface);
  }
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("slide")) /
                  (pi * a.outer_diameter_m * (a.slide_to_m - a.slide_from_m)),
              1.0, area_tolerance);

  // gripper_mount: the front disc x = 0, normal +x, area pi D3^2 / 4.
  expect_faces(mesh, "gripper_mount", [](const Eigen::Vector3d&, const Eigen::Vector3d& n) { return n.x() > 0; });
  for (Index v : mesh.node_set("gripper_mount")) EXPECT_NEAR(mesh.nodes(v, 0), 0.0, on_surface);
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("gripper_mount")) /
                  (pi * a.outer_diameter_m * a.outer_diameter_m / 4),
              1.0, area_tolerance);
}

TEST(SphericalParts, WallLimitsWhenTheMassCannotBeMet) {
  SphericalPartSizing s = variant_a();
  s.arm_mass_kg = 5;        // lighter than a 4 mm wall
  s.sleeve_mass_kg = 1000;  // heavier than the thickest wall that leaves a relief
  const SphericalPartDimensions d = spherical_part_dimensions(s);
  EXPECT_EQ(d.arm.wall_rule, WallRule::MinimumWall);
  EXPECT_EQ(d.arm.wall_m, SphericalPartRules{}.min_wall_m);
  EXPECT_GT(spherical_part_mass_kg(SphericalPart::Arm, d), 5.0);
  EXPECT_EQ(d.sleeve.wall_rule, WallRule::MaximumWall);
  EXPECT_LT(spherical_part_mass_kg(SphericalPart::Sleeve, d), 1000.0);
  EXPECT_NEAR(d.sleeve.outer_diameter_m / 2 - d.sleeve.wall_m,
              d.sleeve.guide_diameter_m / 2 + SphericalPartRules{}.min_relief_m, 1e-12);
  EXPECT_EQ(d.column.wall_rule, WallRule::MassMet);
}

// Throws Error whose message names `what`.
template <class F>
void expect_named_error(F f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error for " << what;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(what), std::string::npos) << error.what();
  }
}

TEST(SphericalParts, BadInputsThrowNamingTheSize) {
  SphericalPartSizing s = variant_a();
  s.sleeve_mass_kg = 0;
  expect_named_error([&] { spherical_part_dimensions(s); }, "sleeve_mass_kg");
  s = variant_a();
  s.arm_length_m = 2.5;  // shorter than r_Mmax + l2/2
  expect_named_error([&] { spherical_part_dimensions(s); }, "arm_length_m");
  s = variant_a();
  s.height_b_m = 0.45;  // B below A
  expect_named_error([&] { spherical_part_dimensions(s); }, "height_a_m");
  s = variant_a();
  s.tilt_max_rad = 65 * pi / 180;  // no room for the column under the tilted sleeve
  expect_named_error([&] { spherical_part_dimensions(s); }, "tilt_max_rad");
  SphericalPartRules rules;
  rules.arm_diameter_ratio = 0.97;  // guide lands thinner than the minimum wall
  expect_named_error([&] { spherical_part_dimensions(variant_a(), rules); }, "arm_diameter_ratio");
  SphericalPartDimensions d = spherical_part_dimensions(variant_a());
  d.arm.outer_diameter_m *= 1.01;  // no longer fits the guide lands
  expect_named_error([&] { mesh_spherical_part(SphericalPart::Arm, d, coarse()); }, "guide_diameter_m");
}

}  // namespace
}  // namespace kinetofem::meshes
