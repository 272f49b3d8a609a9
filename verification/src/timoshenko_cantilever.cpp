#include "kinetofem/verification/timoshenko_cantilever.hpp"

#include <cmath>

#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/verification/box_mesh.hpp"
#include "kinetofem/verification/fe_probes.hpp"

namespace kinetofem::verification {

double TimoshenkoCantilever::beam_deflection_m() const {
  const double E = youngs_modulus_pa, G = E / 2.0, L = length_m;
  return load_n * L * L * L / (3.0 * E * second_moment_m4()) +
         load_n * L / (shear_coefficient() * G * thickness_m * depth_m);
}

CantileverSolution solve_cantilever(const TimoshenkoCantilever& beam, fem::ElementType type,
                                    int refinement) {
  const Stopwatch clock;
  const double c = 0.5 * beam.depth_m, I = beam.second_moment_m4(), L = beam.length_m;
  const double P = beam.load_n;
  fem::FeModel model;
  BoxMeshOptions options;
  options.length_m = {L, beam.depth_m, beam.thickness_m};
  options.divisions = {8 * refinement, 2 * refinement, refinement};
  options.type = type;
  options.smooth_map = [c](const Eigen::Vector3d& x) -> Eigen::Vector3d {
    return {x[0], x[1] - c, x[2]};
  };
  model.mesh = box_mesh(options);
  model.material = fem::IsotropicMaterial{"nu = 0", beam.youngs_modulus_pa, 0.0, 7850.0};

  auto wall_node = [&](double y) {
    const auto nodes = nodes_where(model.mesh, [y](const Eigen::Vector3d& p) {
      return std::abs(p[0]) < 1e-12 && std::abs(p[1] - y) < 1e-12 && std::abs(p[2]) < 1e-12;
    });
    require(nodes.size() == 1, "cantilever: no unique wall node at y = {} m", y);
    return nodes[0];
  };
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  model.supports = {{"wall roller", model.mesh.node_set("x0"), {false, true, false}, zero},
                    {"z symmetry", model.mesh.node_set("z0"), {false, false, true}, zero},
                    {"wall x", {wall_node(0.0), wall_node(c)}, {true, false, false}, zero}};

  fem::LoadCase load_case;
  const TractionField traction = [=](const Eigen::Vector3d& x, const Eigen::Vector3d& n) {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    s(0, 0) = -P * (L - x[0]) * x[1] / I;
    s(0, 1) = s(1, 0) = P * (c * c - x[1] * x[1]) / (2.0 * I);
    return Eigen::Vector3d(s * n);
  };
  for (const char* face : {"x0", "x1"}) {
    auto forces = consistent_face_forces(model.mesh, face, traction);
    load_case.nodal_forces.insert(load_case.nodal_forces.end(), forces.begin(), forces.end());
  }

  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const fem::DisplacementField u = analysis.solve({load_case}).at(0);

  CantileverSolution result;
  result.free_dofs = analysis.dofs().free_count();
  for (const auto& f : load_case.nodal_forces)
    result.compliance_nm += f.force_n.dot(u.row(f.node).transpose());
  const double area = beam.depth_m * beam.thickness_m;
  auto mean_uy = [&](const char* face) {
    return face_integral(model.mesh, face, u,
                         [](const Eigen::Vector3d&, const Eigen::Vector3d&,
                            const Eigen::Vector3d& v) { return v[1]; }) /
           area;
  };
  const double wall_rotation =
      -face_integral(model.mesh, "x0", u,
                     [](const Eigen::Vector3d& x, const Eigen::Vector3d&,
                        const Eigen::Vector3d& v) { return v[0] * x[1]; }) /
      I;
  result.deflection_m = mean_uy("x1") - mean_uy("x0") - wall_rotation * L;
  result.solve_seconds = clock.seconds();
  return result;
}

}  // namespace kinetofem::verification
