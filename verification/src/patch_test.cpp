#include "kinetofem/verification/patch_test.hpp"

#include <algorithm>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/verification/box_mesh.hpp"
#include "kinetofem/verification/fe_probes.hpp"

namespace kinetofem::verification {

Eigen::Vector3d patch_box_length() { return {1.0, 0.8, 0.6}; }

fem::IsotropicMaterial patch_material() { return fem::IsotropicMaterial{"steel", 210e9, 0.3, 7850.0}; }

fem::Mesh distorted_box(fem::ElementType type, bool curved) {
  BoxMeshOptions options;
  options.length_m = patch_box_length();
  options.divisions = {3, 3, 3};
  options.type = type;
  options.random_perturbation = 0.2;
  options.seed = 7;
  if (curved) {
    options.mid_node_perturbation = 0.1;
    options.smooth_map = sine_warp(patch_box_length(), 0.05);
  }
  return box_mesh(options);
}

fem::Mesh distorted_box(fem::ElementType type) { return distorted_box(type, type != fem::ElementType::Tet10); }

Eigen::Matrix3d patch_field_gradient() {
  Eigen::Matrix3d A;
  A << 1.0e-3, -0.4e-3, 0.7e-3,  //
      0.3e-3, -0.6e-3, 0.2e-3,   //
      -0.5e-3, 0.9e-3, 0.8e-3;
  return A;
}

Eigen::Vector3d patch_field_offset() { return {2e-4, -1e-4, 3e-4}; }

fem::Vector6d voigt_strain(const Eigen::Matrix3d& A) {
  fem::Vector6d e;
  e << A(0, 0), A(1, 1), A(2, 2), A(0, 1) + A(1, 0), A(1, 2) + A(2, 1), A(2, 0) + A(0, 2);
  return e;
}

PatchErrors displacement_patch_test(const fem::Mesh& mesh) {
  fem::check_element_jacobians(mesh);
  fem::FeModel model;
  model.mesh = mesh;
  model.material = patch_material();
  const Eigen::Matrix3d A = patch_field_gradient();
  const Eigen::Vector3d b = patch_field_offset();
  auto exact = [&](const Eigen::Vector3d& x) -> Eigen::Vector3d { return A * x + b; };
  model.supports = prescribe_field(model.mesh, model.mesh.node_set("boundary"), exact);

  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve({fem::LoadCase{}}).at(0);

  PatchErrors errors;
  const auto& boundary = model.mesh.node_set("boundary");
  double scale = 0.0;
  for (fem::Index n = 0; n < model.mesh.node_count(); ++n) {
    const Eigen::Vector3d ue = exact(model.mesh.nodes.row(n).transpose());
    scale = std::max(scale, ue.norm());
    if (std::binary_search(boundary.begin(), boundary.end(), n)) continue;
    ++errors.interior_nodes;
    errors.displacement = std::max(errors.displacement, (u.row(n).transpose() - ue).norm());
  }
  errors.displacement /= scale;

  const fem::Vector6d sigma = model.material.elasticity_matrix() * voigt_strain(A);
  const auto gauss = fem::gauss_point_stress(model.mesh, model.material, u);
  for (fem::Index p = 0; p < gauss.stress_pa.rows(); ++p)
    errors.gauss_stress = std::max(errors.gauss_stress, (gauss.stress_pa.row(p).transpose() - sigma).norm());
  errors.gauss_stress /= sigma.norm();
  const auto nodal = fem::recover_nodal_stress(model.mesh, model.material, u);
  for (fem::Index n = 0; n < nodal.stress_pa.rows(); ++n)
    errors.nodal_stress = std::max(errors.nodal_stress, (nodal.stress_pa.row(n).transpose() - sigma).norm());
  errors.nodal_stress /= sigma.norm();
  return errors;
}

}  // namespace kinetofem::verification
