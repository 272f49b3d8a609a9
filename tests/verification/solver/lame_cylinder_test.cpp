// Lame thick-walled cylinder under internal pressure, plane strain.
//
// Reference (Lame; e.g. Timoshenko & Goodier sec. 33), inner radius a, outer
// b, internal pressure p, plane strain (u_z = 0):
//   u_r(r)      = (1 + nu) p a^2 / (E (b^2 - a^2)) * ((1 - 2 nu) r + b^2 / r)
//   sigma_rr(r) = p a^2 / (b^2 - a^2) * (1 - b^2 / r^2)
//   sigma_tt(r) = p a^2 / (b^2 - a^2) * (1 + b^2 / r^2)
// so at the bore u_r(a) = (1 + nu) p a ((1 - 2 nu) a^2 + b^2) / (E (b^2 - a^2))
// and sigma_tt(a) = p (a^2 + b^2) / (b^2 - a^2).
// Model: quarter annulus (HEX20, mid-edge nodes on the arcs), symmetry
// supports u_y = 0 on y = 0 and u_x = 0 on x = 0, u_z = 0 on both end faces,
// pressure on the bore. Checked at every bore node: radial displacement and
// the nodal recovered hoop stress, each within 1 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/mapped_meshes.hpp"

namespace kinetofem::fem {
namespace {

TEST(LameCylinder, BoreDisplacementAndHoopStress) {
  const double a = 0.1, b = 0.2, p = 100e6, E = 210e9, nu = 0.3;
  testing::QuarterAnnulusOptions options;
  options.inner_radius_m = a;
  options.outer_radius_m = b;
  options.length_m = 0.02;
  options.radial_divisions = 6;
  options.circumferential_divisions = 12;
  options.axial_divisions = 1;
  options.radial_grading = 2.0;
  options.type = ElementType::Hex20;

  FeModel model;
  model.mesh = testing::quarter_annulus_mesh(options);
  model.material = IsotropicMaterial{"steel", E, nu, 7850.0};
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  model.supports = {{"y = 0 symmetry", model.mesh.node_set("y0"), {false, true, false}, zero},
                    {"x = 0 symmetry", model.mesh.node_set("x0"), {true, false, false}, zero},
                    {"end z0", model.mesh.node_set("z0"), {false, false, true}, zero},
                    {"end z1", model.mesh.node_set("z1"), {false, false, true}, zero}};
  LoadCase load;
  load.pressures = {{"bore", p}};

  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const DisplacementField u = analysis.solve({load}).at(0);
  const NodalStress stress = recover_nodal_stress(model.mesh, model.material, u);

  const double u_bore = (1 + nu) * p * a * ((1 - 2 * nu) * a * a + b * b) / (E * (b * b - a * a));
  const double hoop_bore = p * (a * a + b * b) / (b * b - a * a);
  double worst_u = 0.0, worst_hoop = 0.0;
  const auto& bore = model.mesh.node_set("bore");
  ASSERT_FALSE(bore.empty());
  for (Index n : bore) {
    const Eigen::Vector3d x = model.mesh.nodes.row(n).transpose();
    const Eigen::Vector3d e_r = Eigen::Vector3d(x[0], x[1], 0.0).normalized();
    const Eigen::Vector3d e_t(-e_r[1], e_r[0], 0.0);
    const double u_r = u.row(n).dot(e_r);
    const auto s = stress.stress_pa.row(n);
    Eigen::Matrix3d sigma;
    sigma << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
    const double hoop = e_t.dot(sigma * e_t);
    worst_u = std::max(worst_u, std::abs(u_r / u_bore - 1.0));
    worst_hoop = std::max(worst_hoop, std::abs(hoop / hoop_bore - 1.0));
  }
  std::printf("Lame: %lld DoFs, %zu bore nodes, max relative error u_r(a) %.2e, sigma_tt(a) %.2e\n",
              static_cast<long long>(analysis.dofs().free_count()), bore.size(), worst_u,
              worst_hoop);
  // Reference: Lame u_r(a) (header); 1 % at every bore node.
  EXPECT_LT(worst_u, 0.01);
  // Reference: Lame sigma_tt(a) = p (a^2 + b^2)/(b^2 - a^2), nodal recovered; 1 %.
  EXPECT_LT(worst_hoop, 0.01);
}

}  // namespace
}  // namespace kinetofem::fem
