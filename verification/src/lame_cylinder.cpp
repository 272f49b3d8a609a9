#include "kinetofem/verification/lame_cylinder.hpp"

#include <cmath>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/verification/mapped_meshes.hpp"

namespace kinetofem::verification {

double LameCylinder::radial_displacement_m(double r) const {
  const double a = inner_radius_m, b = outer_radius_m, p = pressure_pa, E = youngs_modulus_pa, nu = poisson_ratio;
  return (1 + nu) * p * a * a / (E * (b * b - a * a)) * ((1 - 2 * nu) * r + b * b / r);
}

double LameCylinder::radial_stress_pa(double r) const {
  const double a = inner_radius_m, b = outer_radius_m;
  return pressure_pa * a * a / (b * b - a * a) * (1 - b * b / (r * r));
}

double LameCylinder::hoop_stress_pa(double r) const {
  const double a = inner_radius_m, b = outer_radius_m;
  return pressure_pa * a * a / (b * b - a * a) * (1 + b * b / (r * r));
}

LameModel lame_model(const LameCylinder& cylinder) {
  QuarterAnnulusOptions options;
  options.inner_radius_m = cylinder.inner_radius_m;
  options.outer_radius_m = cylinder.outer_radius_m;
  options.length_m = 0.02;
  options.radial_divisions = 6;
  options.circumferential_divisions = 12;
  options.axial_divisions = 1;
  options.radial_grading = 2.0;
  options.type = fem::ElementType::Hex20;
  LameModel m;
  m.model.mesh = quarter_annulus_mesh(options);
  m.model.material = fem::IsotropicMaterial{"steel", cylinder.youngs_modulus_pa, cylinder.poisson_ratio, 7850.0};
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const fem::Mesh& mesh = m.model.mesh;
  m.model.supports = {{"y = 0 symmetry", mesh.node_set("y0"), {false, true, false}, zero},
                      {"x = 0 symmetry", mesh.node_set("x0"), {true, false, false}, zero},
                      {"end z0", mesh.node_set("z0"), {false, false, true}, zero},
                      {"end z1", mesh.node_set("z1"), {false, false, true}, zero}};
  m.load.pressures = {{"bore", cylinder.pressure_pa}};
  return m;
}

LameBoreResult solve_lame_cylinder(const LameCylinder& cylinder) {
  const LameModel m = lame_model(cylinder);
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(m.model, log);
  const fem::DisplacementField u = analysis.solve({m.load}).at(0);
  const fem::NodalStress stress = fem::recover_nodal_stress(m.model.mesh, m.model.material, u);

  LameBoreResult result;
  result.free_dofs = analysis.dofs().free_count();
  result.u_exact_m = cylinder.radial_displacement_m(cylinder.inner_radius_m);
  result.hoop_exact_pa = cylinder.hoop_stress_pa(cylinder.inner_radius_m);
  result.u_worst_m = result.u_exact_m;
  result.hoop_worst_pa = result.hoop_exact_pa;
  const auto& bore = m.model.mesh.node_set("bore");
  require(!bore.empty(), "Lamé cylinder: the mesh has no bore nodes");
  result.bore_nodes = bore.size();
  for (fem::Index n : bore) {
    const Eigen::Vector3d x = m.model.mesh.nodes.row(n).transpose();
    const Eigen::Vector3d e_r = Eigen::Vector3d(x[0], x[1], 0.0).normalized();
    const Eigen::Vector3d e_t(-e_r[1], e_r[0], 0.0);
    const double u_r = u.row(n).dot(e_r);
    const auto s = stress.stress_pa.row(n);
    Eigen::Matrix3d sigma;
    sigma << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const double hoop = e_t.dot(sigma * e_t);
    if (std::abs(u_r - result.u_exact_m) > std::abs(result.u_worst_m - result.u_exact_m)) result.u_worst_m = u_r;
    if (std::abs(hoop - result.hoop_exact_pa) > std::abs(result.hoop_worst_pa - result.hoop_exact_pa))
      result.hoop_worst_pa = hoop;
  }
  result.u_error = std::abs(result.u_worst_m / result.u_exact_m - 1.0);
  result.hoop_error = std::abs(result.hoop_worst_pa / result.hoop_exact_pa - 1.0);
  return result;
}

}  // namespace kinetofem::verification
