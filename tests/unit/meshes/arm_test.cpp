// mesh_arm: link 2 of SPEC §1/§2 (lever-chain arm with its roller, lever
// coupler with bores A and B) meshed with TET10 at a coarse size: valid
// elements, the exact volume, the named faces where they belong, parameter
// overrides reaching arm.geo, invalid dimensions named in the error.
#include <cmath>
#include <numbers>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"
#include "kinetofem/meshes/arm.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "mesh_test_helpers.hpp"

namespace kinetofem::meshes {
namespace {

using fem::Index;
constexpr double pi = std::numbers::pi;

// SPEC §1 example: c = 350 mm, h = 100 mm, r = 75 mm.
constexpr double c_spec = 0.350, h_spec = 0.100, r_spec = 0.075;

MeshOptions coarse() {
  MeshOptions options;
  options.element_size_m = 0.02;  // coarse: each variant meshes in about a second
  options.order = 2;
  return options;
}

// Nodes are placed on the OpenCASCADE surfaces: 1e-7 m is its tolerance.
constexpr double on_surface = 1e-7;

// Every node of `name` lies on the cylinder of `radius` about the z axis
// through (x_axis, 0), within |z| <= half_length, and every face's normal
// points away from the axis if `outward`, towards it otherwise (normals point
// out of the material).
void expect_cylinder(const fem::Mesh& mesh, const std::string& name, double x_axis, double radius,
                     double half_length, bool outward) {
  const auto& nodes = mesh.node_set(name);
  ASSERT_FALSE(nodes.empty()) << name;
  for (Index v : nodes) {
    EXPECT_NEAR(std::hypot(mesh.nodes(v, 0) - x_axis, mesh.nodes(v, 1)), radius, on_surface)
        << name << " node " << v;
    EXPECT_LE(std::abs(mesh.nodes(v, 2)), half_length + on_surface) << name << " node " << v;
  }
  const auto& faces = mesh.face_set(name);
  ASSERT_EQ(faces.size(), 1u) << name;
  EXPECT_EQ(faces[0].type, fem::FaceType::Tri6) << name;
  for (Index f = 0; f < faces[0].size(); ++f) {
    const auto face = faces[0].face(f);
    Eigen::Vector3d from_axis = testing::face_centroid(mesh, face, 3);
    from_axis.x() -= x_axis;
    from_axis.z() = 0;
    const double sign = outward ? 1.0 : -1.0;
    EXPECT_GT(sign * testing::face_normal(mesh, face).dot(from_axis), 0.0)
        << name << " face " << f;
  }
}

// The gripper mount: the pad face y = h centred on x = -c, normal +Y, of
// area l_mount x w_mount.
void expect_gripper_mount(const fem::Mesh& mesh, const ArmDimensions& d) {
  const auto& nodes = mesh.node_set("gripper_mount");
  ASSERT_FALSE(nodes.empty());
  for (Index v : nodes) {
    EXPECT_NEAR(mesh.nodes(v, 1), d.gripper_offset_m, on_surface) << "node " << v;
    EXPECT_LE(std::abs(mesh.nodes(v, 0) + d.length_m), d.mount_length_m / 2 + on_surface);
    EXPECT_LE(std::abs(mesh.nodes(v, 2)), d.mount_width_m / 2 + on_surface);
  }
  const auto& faces = mesh.face_set("gripper_mount");
  ASSERT_EQ(faces.size(), 1u);
  for (Index f = 0; f < faces[0].size(); ++f)
    EXPECT_GT(testing::face_normal(mesh, faces[0].face(f)).y(), 0.0) << "face " << f;
  // A flat face is meshed exactly: area to rounding.
  EXPECT_NEAR(fem::surface_area(mesh, faces), d.mount_length_m * d.mount_width_m, 1e-12);
}

// Valid TET10 mesh with one element set "arm" and the volume of
// ArmDimensions::volume_m3.
void expect_valid_mesh(const fem::Mesh& mesh, const ArmDimensions& d) {
  ASSERT_EQ(mesh.blocks.size(), 1u);
  ASSERT_EQ(mesh.blocks[0].type, fem::ElementType::Tet10);
  EXPECT_EQ(mesh.element_sets.at("arm").size(), std::size_t(mesh.element_count()));
  EXPECT_NO_THROW(fem::check_element_jacobians(mesh));
  // Reference: ArmDimensions::volume_m3 (exact solid). The quadratic mesh
  // differs only where its curved faces interpolate the roller, boss and
  // bore cylinders (16 elements per circle: arcs of 22.5 deg); that error was
  // 2e-6 relative at 20 mm, 1e-6 at 8 mm and 2e-7 at 5 mm, so 1e-5.
  EXPECT_NEAR(fem::mesh_volume(mesh) / d.volume_m3(), 1.0, 1e-5);
}

TEST(MeshArm, LeverChainArmOrder2MeshIsValid) {
  const ArmDimensions d = lever_chain_arm(c_spec, h_spec, r_spec);
  const auto mesh = mesh_arm(d, coarse());
  expect_valid_mesh(mesh, d);
  expect_cylinder(mesh, "bore_A", 0.0, d.bore_diameter_m / 2, d.boss_length_m / 2, false);
  expect_cylinder(mesh, "roller_rim", 0.0, d.roller_radius_m, d.roller_thickness_m / 2, true);
  // The rim (not the roller's flat faces): the cylinder 2 pi r e less the
  // window where the plate (t < e) enters it, t * 2 r asin(w / 2r). Curved
  // TRI6 faces interpolating the cylinder: 1e-5 relative, as the volume
  // (1.4e-6 seen).
  const double r = d.roller_radius_m;
  const double rim_area = 2 * pi * r * d.roller_thickness_m -
                          d.arm_thickness_m * 2 * r * std::asin(d.arm_depth_m / (2 * r));
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("roller_rim")) / rim_area, 1.0, 1e-5);
  expect_gripper_mount(mesh, d);
  EXPECT_EQ(mesh.face_sets.count("bore_B"), 0u);
}

TEST(MeshArm, LeverCouplerOrder2MeshIsValid) {
  const ArmDimensions d = lever_coupler(c_spec, h_spec, r_spec);
  const auto mesh = mesh_arm(d, coarse());
  expect_valid_mesh(mesh, d);
  expect_cylinder(mesh, "bore_A", 0.0, d.bore_diameter_m / 2, d.boss_length_m / 2, false);
  expect_cylinder(mesh, "bore_B", r_spec, d.bore_diameter_m / 2, d.boss_length_m / 2, false);
  expect_gripper_mount(mesh, d);
  EXPECT_EQ(mesh.face_sets.count("roller_rim"), 0u);
  // Bore B is the joint with the rocker at B = (r, 0) of SPEC §2.
  EXPECT_EQ(d.bore_b_offset_m, r_spec);
}

TEST(MeshArm, DimensionsReachTheGeometryFile) {
  ArmDimensions d = lever_chain_arm(0.30, 0.12, 0.085);
  d.roller_thickness_m = 0.02;  // thinner than the plate: the plate crosses the roller's faces
  d.arm_thickness_m = 0.03;
  d.boss_length_m = 0.06;
  d.mount_length_m = 0.10;
  const auto mesh = mesh_arm(d, coarse());
  // Plane faces are meshed exactly: the pad spans -c - l_mount/2 .. , its
  // top is y = h; the roller reaches x = r (up to the chord of the coarse
  // mesh: 1 mm).
  EXPECT_NEAR(mesh.nodes.col(0).minCoeff(), -d.length_m - d.mount_length_m / 2, 1e-9);
  EXPECT_NEAR(mesh.nodes.col(1).maxCoeff(), d.gripper_offset_m, 1e-9);
  EXPECT_NEAR(mesh.nodes.col(0).maxCoeff(), d.roller_radius_m, 1e-3);
  EXPECT_NEAR(mesh.nodes.col(2).maxCoeff(), d.boss_length_m / 2, 1e-9);
  expect_valid_mesh(mesh, d);
  expect_cylinder(mesh, "roller_rim", 0.0, d.roller_radius_m, d.roller_thickness_m / 2, true);
  // The plate (t > e) cuts the rim over its whole height: the rim is the
  // cylinder less the arc 2 asin(w / 2r). 1e-5 relative as above.
  const double r = d.roller_radius_m;
  const double rim_area =
      (2 * pi - 2 * std::asin(d.arm_depth_m / (2 * r))) * r * d.roller_thickness_m;
  EXPECT_NEAR(fem::surface_area(mesh, mesh.face_set("roller_rim")) / rim_area, 1.0, 1e-5);
  expect_gripper_mount(mesh, d);

  ArmDimensions coupler = lever_coupler(0.40, 0.09, 0.10);
  coupler.boss_diameter_m = 0.10;
  coupler.bore_diameter_m = 0.045;
  const auto coupler_mesh = mesh_arm(coupler, coarse());
  // The hub reaches x = d_B + D/2 (boss circle: 1 mm as above).
  EXPECT_NEAR(coupler_mesh.nodes.col(0).maxCoeff(), 0.10 + 0.05, 1e-3);
  expect_valid_mesh(coupler_mesh, coupler);
  expect_cylinder(coupler_mesh, "bore_B", 0.10, 0.0225, coupler.boss_length_m / 2, false);
  expect_gripper_mount(coupler_mesh, coupler);
}

TEST(MeshArm, VolumeFormulaOfTheDefaults) {
  // The README's numbers (m): r = 0.075, e = 0.030, D = 0.090, L = 0.050,
  // d = 0.040, w = 0.080, t = 0.025, c = 0.350, h = 0.100, bracket 0.080 x
  // 0.025, pad 0.080 x 0.015 x 0.060. S(rho) = disc of radius rho within
  // |y| <= 0.04.
  auto s = [](double rho) {
    return 2 * (0.04 * std::sqrt(rho * rho - 0.04 * 0.04) + rho * rho * std::asin(0.04 / rho));
  };
  const double plate = 0.08 * 0.35 * 0.025;
  const double bracket = 0.08 * 0.025 * (0.1 - 0.015 + 0.04) - 0.04 * 0.08 * 0.025;
  const double pad = 0.08 * 0.015 * 0.06;
  const double chain = pi * 0.075 * 0.075 * 0.03 + pi * 0.045 * 0.045 * 0.02 -
                       pi * 0.02 * 0.02 * 0.05 + plate - 0.025 * s(0.075) / 2 + bracket + pad;
  const double coupler = 0.05 * (pi * 0.045 * 0.045 + 2 * 0.045 * 0.075) -
                         2 * pi * 0.02 * 0.02 * 0.05 + plate - 0.025 * s(0.045) / 2 + bracket +
                         pad;
  EXPECT_NEAR(lever_chain_arm(c_spec, h_spec, r_spec).volume_m3(), chain, 1e-15);
  EXPECT_NEAR(lever_coupler(c_spec, h_spec, r_spec).volume_m3(), coupler, 1e-15);
  EXPECT_NEAR(ArmDimensions{}.volume_m3(), chain, 1e-15);  // the default is the chain arm
}

// Throws Error whose message names `dimension`.
void expect_named_error(const ArmDimensions& d, const std::string& dimension) {
  try {
    d.validate();
    ADD_FAILURE() << "no error for " << dimension;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(dimension), std::string::npos) << error.what();
  }
}

TEST(MeshArm, InvalidDimensionsThrowNamingTheDimension) {
  const ArmDimensions chain = lever_chain_arm(c_spec, h_spec, r_spec);
  const ArmDimensions coupler = lever_coupler(c_spec, h_spec, r_spec);
  ArmDimensions d = chain;
  d.mount_width_m = -0.06;
  expect_named_error(d, "mount_width_m");
  d = chain;
  d.arm_depth_m = std::nan("");
  expect_named_error(d, "arm_depth_m");
  d = chain;
  d.bore_diameter_m = 0.1;  // wider than the boss
  expect_named_error(d, "bore_diameter_m");
  d = chain;
  d.arm_thickness_m = 0.06;  // thicker than the boss is long
  expect_named_error(d, "arm_thickness_m");
  d = chain;
  d.gripper_offset_m = 0.03;  // pad inside the arm plate
  expect_named_error(d, "gripper_offset_m");
  d = chain;
  d.length_m = 0.1;  // bracket on the roller
  expect_named_error(d, "length_m");
  d = chain;
  d.roller_radius_m = 0.04;  // inside the boss
  expect_named_error(d, "roller_radius_m");
  d = chain;
  d.roller_thickness_m = 0.05;  // not thinner than the boss
  expect_named_error(d, "roller_thickness_m");
  d = coupler;
  d.bore_b_offset_m = 0.03;  // bores merge
  expect_named_error(d, "bore_b_offset_m");
  d = coupler;
  d.roller_radius_m = -1;  // not used by the coupler
  EXPECT_NO_THROW(d.validate());
  d = chain;
  d.bore_b_offset_m = -1;  // not used by the chain arm
  EXPECT_NO_THROW(d.validate());
  // mesh_arm checks before it starts Gmsh.
  d = chain;
  d.length_m = 0.1;
  EXPECT_THROW(mesh_arm(d, coarse()), Error);
}

}  // namespace
}  // namespace kinetofem::meshes
