#include "kinetofem/verification/box_mesh.hpp"

#include <cmath>
#include <numbers>

#include "kinetofem/core/error.hpp"
#include "kinetofem/verification/structured_block.hpp"

namespace kinetofem::verification {

fem::Mesh box_mesh(const BoxMeshOptions& options) {
  for (int d = 0; d < 3; ++d)
    require(options.length_m[d] > 0 && std::isfinite(options.length_m[d]),
            "box mesh: length[{}] = {} m must be positive", d, options.length_m[d]);
  StructuredBlock block;
  const Eigen::Vector3d length = options.length_m;
  block.mapping = [length](const Eigen::Vector3d& uvw) -> Eigen::Vector3d {
    return uvw.cwiseProduct(length);
  };
  block.divisions = options.divisions;
  block.type = options.type;
  block.face_names = {"x0", "x1", "y0", "y1", "z0", "z1"};
  block.grading_ratio = options.grading_ratio;
  block.random_perturbation = options.random_perturbation;
  block.mid_node_perturbation = options.mid_node_perturbation;
  block.seed = options.seed;
  fem::Mesh mesh = structured_block_mesh(block);
  if (options.smooth_map)
    for (Eigen::Index n = 0; n < mesh.nodes.rows(); ++n)
      mesh.nodes.row(n) = options.smooth_map(mesh.nodes.row(n).transpose()).transpose();
  return mesh;
}

std::function<Eigen::Vector3d(const Eigen::Vector3d&)> sine_warp(const Eigen::Vector3d& length_m,
                                                                 double amplitude) {
  return [length_m, amplitude](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    double bump = amplitude;
    for (int d = 0; d < 3; ++d) bump *= std::sin(std::numbers::pi * x[d] / length_m[d]);
    // Different weights per direction so the warp is not a pure stretch along
    // the diagonal.
    const Eigen::Vector3d weight(1.0, -0.7, 0.4);
    return x + bump * weight.cwiseProduct(length_m);
  };
}

std::int64_t box_node_count(fem::ElementType type, const std::array<int, 3>& divisions) {
  const std::int64_t nx = divisions[0], ny = divisions[1], nz = divisions[2];
  switch (type) {
    case fem::ElementType::Hex8:
    case fem::ElementType::Tet4: return (nx + 1) * (ny + 1) * (nz + 1);
    case fem::ElementType::Hex20:
      return (nx + 1) * (ny + 1) * (nz + 1) + nx * (ny + 1) * (nz + 1) +
             (nx + 1) * ny * (nz + 1) + (nx + 1) * (ny + 1) * nz;
    case fem::ElementType::Tet10: return (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1);
  }
  return 0;
}

}  // namespace kinetofem::verification
