#include "kinetofem/verification/accelerated_link.hpp"

#include <cmath>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/geometry_text.hpp"
#include "kinetofem/solver/couplings.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/verification/verification_geometry.hpp"

namespace kinetofem::verification {

double AcceleratedLink::beam_stress_pa(double rho) const {
  const double L = span_m, e = overhang_m, h = depth_m, t = thickness_m;
  const double q = rho * h * t * acceleration_mps2;
  const double M_mid = 0.5 * q * (L + 2 * e) * L / 2 - q * (L / 2 + e) * (L / 2 + e) / 2;
  const double I = t * h * h * h / 12.0;
  return M_mid * (h / 2) / I;
}

fem::Mesh beam_link_mesh() {
  meshes::MeshOptions options;
  options.element_size_m = 0.006;
  options.order = 2;
  return meshes::mesh_geometry_text("beam_link.geo", beam_link_geometry_text(), options);
}

AcceleratedLinkResult solve_accelerated_link(const fem::Mesh& mesh, const AcceleratedLink& link) {
  fem::FeModel model;
  model.mesh = mesh;
  const double a = link.acceleration_mps2, L = link.span_m, h = link.depth_m;
  std::vector<fem::Index> all(std::size_t(model.mesh.node_count()));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = fem::Index(i);
  model.supports = fem::three_two_one_support(model.mesh, all);
  const fem::RigidBodyMotionLoads inertia(model.mesh, model.material);
  Eigen::VectorXd f = inertia.forces(Eigen::Vector3d::Zero(), Eigen::Vector3d(0, a, 0), Eigen::Vector3d::Zero(),
                                     Eigen::Vector3d::Zero());
  const Eigen::Vector3d reaction(0, 0.5 * inertia.mass_kg() * a, 0);
  fem::DistributingCoupling(model.mesh, "bore_1").add(reaction, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), f);
  fem::DistributingCoupling(model.mesh, "bore_2").add(reaction, Eigen::Vector3d::Zero(), Eigen::Vector3d(L, 0, 0), f);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const auto u = analysis.solve_forces(f);
  const fem::NodalStress s = fem::recover_nodal_stress(model.mesh, model.material, u.at(0));

  AcceleratedLinkResult result;
  result.beam_stress_pa = link.beam_stress_pa(model.material.density_kg_m3);
  for (fem::Index i = 0; i < model.mesh.node_count(); ++i) {
    const auto x = model.mesh.nodes.row(i);
    if (std::abs(x[0] - 0.5 * L) > 0.004) continue;
    if (std::abs(x[1] - 0.5 * h) < 1e-9) result.top_pa += s.stress_pa(i, 0), ++result.top_nodes;
    if (std::abs(x[1] + 0.5 * h) < 1e-9) result.bottom_pa += s.stress_pa(i, 0), ++result.bottom_nodes;
  }
  if (result.top_nodes > 0) result.top_pa /= result.top_nodes;
  if (result.bottom_nodes > 0) result.bottom_pa /= result.bottom_nodes;
  return result;
}

}  // namespace kinetofem::verification
