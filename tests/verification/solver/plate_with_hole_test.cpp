// Plate with a circular hole under remote tension: stress concentration.
//
// Reference (Kirsch 1898; Timoshenko & Goodier sec. 35): the stress field of
// an infinite plate with a hole of radius a under remote tension S,
// kinetofem/verification/kirsch_plate.hpp, 3 S at the hole edge across the
// load. Here the load is along y (x and y swapped, a reflection), so
// sigma_yy(a, 0) = 3 S. To model the infinite plate with a finite one we
// apply the exact Kirsch traction t = sigma n on the outer edges x = W and
// y = H (no finite-width correction). Thin plate (half-thickness 0.1 a, the
// face z = 0 a symmetry plane), quarter model with symmetry supports.
// Checked: nodal recovered sigma_yy / S at the hole nodes on y = 0 within 3 %
// of 3.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/verification/fe_probes.hpp"
#include "kinetofem/verification/kirsch_plate.hpp"
#include "kinetofem/verification/mapped_meshes.hpp"

namespace kinetofem::fem {
namespace {

namespace kv = kinetofem::verification;

TEST(PlateWithHole, StressConcentrationAtHoleEdge) {
  const double a = 0.01, S = 50e6;
  kv::QuarterPlateWithHoleOptions options;
  options.hole_radius_m = a;
  options.half_width_m = 5 * a;
  options.half_height_m = 5 * a;
  options.thickness_m = 0.1 * a;
  options.radial_divisions = 10;
  options.arc_divisions_per_block = 6;
  options.thickness_divisions = 1;
  options.radial_grading = 5.0;
  options.type = ElementType::Hex20;

  FeModel model;
  model.mesh = kv::quarter_plate_with_hole_mesh(options);
  model.material = IsotropicMaterial{"steel", 210e9, 0.3, 7850.0};
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  model.supports = {{"x = 0 symmetry", model.mesh.node_set("x0"), {true, false, false}, zero},
                    {"y = 0 symmetry", model.mesh.node_set("y0"), {false, true, false}, zero},
                    {"mid-plane", model.mesh.node_set("z0"), {false, false, true}, zero}};
  LoadCase load;
  const kv::TractionField kirsch = [&](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
    return Eigen::Vector3d(kv::kirsch_stress_y(x, a, S) * n);
  };
  for (const char* edge : {"x1", "y1"}) {
    auto forces = kv::consistent_face_forces(model.mesh, edge, kirsch);
    load.nodal_forces.insert(load.nodal_forces.end(), forces.begin(), forces.end());
  }

  const Log log = Log::quiet();
  LinearStaticAnalysis analysis(model, log);
  const DisplacementField u = analysis.solve({load}).at(0);
  const NodalStress stress = recover_nodal_stress(model.mesh, model.material, u);

  const auto edge = kv::nodes_where(model.mesh, [a](const Eigen::Vector3d& p) {
    return std::abs(p[1]) < 1e-12 && std::abs(p[0] - a) < 1e-9;
  });
  ASSERT_FALSE(edge.empty());
  for (Index n : edge) {
    const double kt = stress.stress_pa(n, 1) / S;
    std::printf("plate with hole: %lld DoFs, node %lld z = %.4g m: sigma_yy / S = %.4f\n",
                static_cast<long long>(analysis.dofs().free_count()), static_cast<long long>(n),
                model.mesh.nodes(n, 2), kt);
    // Reference: Kirsch, sigma_yy(a, 0) = 3 S; 3 %.
    EXPECT_NEAR(kt, kv::kKirschConcentration, 0.03 * kv::kKirschConcentration);
  }
}

}  // namespace
}  // namespace kinetofem::fem
