#include "kinetofem/verification/mapped_meshes.hpp"

#include <cmath>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/verification/structured_block.hpp"

namespace kinetofem::verification {

fem::Mesh quarter_annulus_mesh(const QuarterAnnulusOptions& o) {
  require(o.inner_radius_m > 0 && o.outer_radius_m > o.inner_radius_m,
          "quarter annulus: need 0 < inner radius ({} m) < outer radius ({} m)", o.inner_radius_m,
          o.outer_radius_m);
  require(o.length_m > 0, "quarter annulus: length {} m must be positive", o.length_m);
  StructuredBlock block;
  const double a = o.inner_radius_m, b = o.outer_radius_m, length = o.length_m;
  block.mapping = [a, b, length](const Eigen::Vector3d& uvw) -> Eigen::Vector3d {
    const double r = a + (b - a) * uvw[0];
    const double theta = 0.5 * std::numbers::pi * uvw[1];
    return {r * std::cos(theta), r * std::sin(theta), length * uvw[2]};
  };
  block.divisions = {o.radial_divisions, o.circumferential_divisions, o.axial_divisions};
  block.type = o.type;
  block.face_names = {"bore", "outer", "y0", "x0", "z0", "z1"};
  block.grading_ratio = {o.radial_grading, 1.0, 1.0};
  fem::Mesh mesh = structured_block_mesh(block);
  // cos(pi/2) is 6e-17, not 0: put the symmetry-plane nodes exactly on x = 0.
  for (fem::Index n : mesh.node_sets.at("x0")) mesh.nodes(n, 0) = 0.0;
  return mesh;
}

fem::Mesh quarter_plate_with_hole_mesh(const QuarterPlateWithHoleOptions& o) {
  const double a = o.hole_radius_m, W = o.half_width_m, H = o.half_height_m, t = o.thickness_m;
  require(a > 0 && W > a && H > a, "plate with hole: need 0 < hole radius ({} m) < W ({} m), H ({} m)",
          a, W, H);
  require(t > 0, "plate with hole: thickness {} m must be positive", t);
  const double theta_c = std::atan2(H, W);
  StructuredBlock block;
  // v in [0, 1/2]: block below the diagonal (rays to x = W); v in [1/2, 1]:
  // block above it (rays to y = H). The kink at v = 1/2 falls on cell
  // boundaries because the arc divisions per block are whole.
  block.mapping = [=](const Eigen::Vector3d& uvw) -> Eigen::Vector3d {
    const double v = uvw[1];
    double theta;
    Eigen::Vector2d outer;
    if (v <= 0.5) {
      theta = 2.0 * v * theta_c;
      outer = {W, W * std::tan(theta)};
    } else {
      theta = theta_c + (2.0 * v - 1.0) * (0.5 * std::numbers::pi - theta_c);
      outer = {H * std::cos(theta) / std::sin(theta), H};
    }
    const Eigen::Vector2d hole(a * std::cos(theta), a * std::sin(theta));
    const Eigen::Vector2d p = hole + uvw[0] * (outer - hole);
    return {p[0], p[1], t * uvw[2]};
  };
  block.divisions = {o.radial_divisions, 2 * o.arc_divisions_per_block, o.thickness_divisions};
  block.type = o.type;
  block.face_names = {"hole", "outer", "y0", "x0", "z0", "z1"};
  block.grading_ratio = {o.radial_grading, 1.0, 1.0};
  fem::Mesh mesh = structured_block_mesh(block);
  for (fem::Index n : mesh.node_sets.at("x0")) mesh.nodes(n, 0) = 0.0;

  // Split the outer boundary into its two straight edges by face centroid.
  fem::FaceBlock x1, y1;
  for (const auto& faces : mesh.face_sets.at("outer")) {
    x1.type = y1.type = faces.type;
    for (fem::Index f = 0; f < faces.size(); ++f) {
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      const auto face = faces.face(f);
      for (fem::Index n : face) centroid += mesh.nodes.row(n).transpose();
      centroid /= double(face.size());
      auto& target = std::abs(centroid[0] - W) < std::abs(centroid[1] - H) ? x1 : y1;
      target.connectivity.insert(target.connectivity.end(), face.begin(), face.end());
    }
  }
  mesh.node_sets["x1"] = fem::nodes_of_faces({x1});
  mesh.node_sets["y1"] = fem::nodes_of_faces({y1});
  mesh.face_sets["x1"] = {std::move(x1)};
  mesh.face_sets["y1"] = {std::move(y1)};
  return mesh;
}

}  // namespace kinetofem::verification
