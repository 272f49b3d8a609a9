// The structured meshes the verification tests are built on (tests/support):
// node counts, outward face sets and exact geometry of the mapped meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/verification/box_mesh.hpp"
#include "kinetofem/verification/fe_probes.hpp"
#include "kinetofem/verification/mapped_meshes.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;

class BoxMeshTest : public ::testing::TestWithParam<ElementType> {};

TEST_P(BoxMeshTest, CountsAreaAndOutwardNormals) {
  kv::BoxMeshOptions options;
  options.length_m = {2.0, 1.0, 0.5};
  options.divisions = {4, 3, 2};
  options.type = GetParam();
  options.random_perturbation = 0.2;
  const Mesh mesh = kv::box_mesh(options);
  EXPECT_NO_THROW(mesh.validate());
  EXPECT_NO_THROW(check_element_jacobians(mesh));
  EXPECT_EQ(mesh.node_count(), kv::box_node_count(GetParam(), options.divisions));
  const int per_cell = corner_nodes(GetParam()) == 4 ? 6 : 1;
  EXPECT_EQ(mesh.element_count(), 4 * 3 * 2 * per_cell);
  // Reference: a box's volume (plane faces, straight edges: exact to round-off).
  EXPECT_NEAR(mesh_volume(mesh), 1.0, 1e-12);

  const Eigen::Vector3d L = options.length_m;
  const DisplacementField none = DisplacementField::Zero(mesh.node_count(), 3);
  for (int d = 0; d < 3; ++d)
    for (int side = 0; side < 2; ++side) {
      const std::string name = std::string(1, "xyz"[d]) + char('0' + side);
      const double area = L.prod() / L[d];
      for (int c = 0; c < 3; ++c) {
        const double n_c = kv::face_integral(
            mesh, name, none,
            [c](const Eigen::Vector3d&, const Eigen::Vector3d& n, const Eigen::Vector3d&) {
              return n[c];
            });
        // Reference: int n dA = area * outward unit normal; round-off.
        EXPECT_NEAR(n_c, c == d ? (side ? area : -area) : 0.0, 1e-12) << name << " n_" << c;
      }
      for (Index node : mesh.node_set(name))
        EXPECT_NEAR(mesh.nodes(node, d), side * L[d], 1e-15) << name;
    }
}

INSTANTIATE_TEST_SUITE_P(Elements, BoxMeshTest,
                         ::testing::Values(ElementType::Tet4, ElementType::Tet10, ElementType::Hex8,
                                           ElementType::Hex20),
                         [](const auto& info) { return std::string(name_of(info.param)); });

TEST(MappedMeshes, QuarterAnnulusHex20LiesOnTheArcs) {
  kv::QuarterAnnulusOptions o;
  o.radial_grading = 3.0;
  const Mesh mesh = kv::quarter_annulus_mesh(o);
  EXPECT_NO_THROW(check_element_jacobians(mesh));
  for (Index n : mesh.node_set("bore"))
    EXPECT_NEAR(mesh.nodes.row(n).head<2>().norm(), o.inner_radius_m, 1e-15);
  for (Index n : mesh.node_set("outer"))
    EXPECT_NEAR(mesh.nodes.row(n).head<2>().norm(), o.outer_radius_m, 1e-15);
  for (Index n : mesh.node_set("x0")) EXPECT_EQ(mesh.nodes(n, 0), 0.0);
  for (Index n : mesh.node_set("y0")) EXPECT_EQ(mesh.nodes(n, 1), 0.0);
  // Reference: pi/4 (b^2 - a^2) L. The quadratic edges only interpolate the
  // arcs (nodes on the arc, O(phi^4) area error per cell of angle phi =
  // 11.25 deg, phi^4 = 1.5e-3; measured 3.1e-6): tolerance 1e-5 relative.
  const double exact =
      std::numbers::pi / 4 * (o.outer_radius_m * o.outer_radius_m - o.inner_radius_m * o.inner_radius_m) *
      o.length_m;
  EXPECT_NEAR(mesh_volume(mesh) / exact, 1.0, 1e-5);
}

TEST(MappedMeshes, QuarterPlateWithHoleHasItsEdges) {
  kv::QuarterPlateWithHoleOptions o;
  const Mesh mesh = kv::quarter_plate_with_hole_mesh(o);
  EXPECT_NO_THROW(check_element_jacobians(mesh));
  for (Index n : mesh.node_set("hole"))
    EXPECT_NEAR(mesh.nodes.row(n).head<2>().norm(), o.hole_radius_m, 1e-15);
  for (Index n : mesh.node_set("x1")) EXPECT_NEAR(mesh.nodes(n, 0), o.half_width_m, 1e-15);
  for (Index n : mesh.node_set("y1")) EXPECT_NEAR(mesh.nodes(n, 1), o.half_height_m, 1e-15);
  EXPECT_FALSE(mesh.node_set("x1").empty());
  EXPECT_FALSE(mesh.node_set("y1").empty());
  // Reference: (W H - pi a^2 / 4) t; the hole's quadratic arcs (O(phi^4),
  // as above) err on a small part of the area: tolerance 1e-6 relative.
  const double a = o.hole_radius_m;
  const double exact =
      (o.half_width_m * o.half_height_m - std::numbers::pi * a * a / 4) * o.thickness_m;
  EXPECT_NEAR(mesh_volume(mesh) / exact, 1.0, 1e-6);
}

}  // namespace
}  // namespace kinetofem::fem
