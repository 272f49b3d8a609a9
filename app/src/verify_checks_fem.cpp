// `kinetofem verify`: the FEM core and the load transfer against exact
// solutions. The references, models and computations shared with
// tests/verification/ live in the verification library (patch_test.hpp,
// lame_cylinder.hpp, direct_solvers.hpp, accelerated_link.hpp): the patch
// tests of the four element types on distorted meshes, the Lamé thick
// cylinder on a structured HEX20 quarter annulus, CHOLMOD against Eigen's
// SimplicialLDLT, and the accelerated link (meshed by Gmsh from the compiled-in
// verification/geometry/beam_link.geo). The bar in uniaxial tension
// (verification/geometry/bar.geo) is checked here only.
#include <algorithm>
#include <numbers>
#include <string>
#include <vector>

#include "kinetofem/app/verify.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/geometry_text.hpp"
#include "kinetofem/solver/element_library.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/verification/accelerated_link.hpp"
#include "kinetofem/verification/direct_solvers.hpp"
#include "kinetofem/verification/lame_cylinder.hpp"
#include "kinetofem/verification/persson_pin.hpp"
#include "kinetofem/verification/patch_test.hpp"
#include "kinetofem/verification/verification_geometry.hpp"

namespace kinetofem::app {

namespace {

namespace fem = kinetofem::fem;
namespace kv = kinetofem::verification;
using fem::ElementType;
using fem::Index;

std::vector<CheckRow> patch_test(ElementType type) {
  // The distorted box of the tests (3 x 3 x 3 cells, corners moved 20 %,
  // curved edges but for TET10), u = A x + b prescribed on the boundary.
  const kv::PatchErrors errors = kv::displacement_patch_test(kv::distorted_box(type));
  require(errors.interior_nodes > 0, "patch test mesh has no interior node");
  const std::string name = fem::name_of(type);
  const char* why = "exact in the element's span: round-off, 1e-10";
  return {compare_absolute("patch test " + name + ", distorted, interior u", "u = A x + b", "1", 0.0,
                           errors.displacement, kv::kPatchTolerance, why),
          compare_absolute("patch test " + name + ", distorted, Gauss-point stress", "sigma = D eps(A)", "1", 0.0,
                           errors.gauss_stress, kv::kPatchTolerance, why)};
}

std::vector<CheckRow> patch_tests(const CheckContext&) {
  std::vector<CheckRow> rows;
  for (ElementType type : fem::all_element_types)
    for (auto& row : patch_test(type)) rows.push_back(std::move(row));
  return rows;
}

std::vector<CheckRow> bar_tension(const CheckContext&) {
  // verification/geometry/bar.geo (as tests/data/cases/bar_tension): bar
  // 100 x 20 x 20 mm, x0 face held in x, origin in x, y, z, corner
  // (0, 20, 0) mm in z (statically determinate), 10 kN on the x1 face. Exact: sigma_xx = F/A = 25 MPa,
  // u = sigma/E (x, -nu y, -nu z), linear: TET10 reproduces it exactly.
  meshes::MeshOptions options;
  options.element_size_m = 0.01;
  options.order = 2;
  fem::FeModel model;
  model.mesh = meshes::mesh_geometry_text("bar.geo", kv::bar_geometry_text(), options);
  model.material = fem::IsotropicMaterial{"steel", 200e9, 0.3, 7850.0};
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  model.supports = {{"x0", model.mesh.node_set("x0"), {true, false, false}, zero},
                    {"origin", model.mesh.node_set("origin"), {true, true, true}, zero},
                    {"corner_y", model.mesh.node_set("corner_y"), {false, false, true}, zero}};
  const double force = 10e3, area = 0.02 * 0.02, length = 0.1, E = 200e9, nu = 0.3;
  const double sigma = force / area;
  fem::LoadCase load;
  load.tractions = {{"x1", Eigen::Vector3d(sigma, 0, 0)}};
  const Log log = Log::quiet();
  fem::LinearStaticAnalysis analysis(model, log);
  const fem::DisplacementField u = analysis.solve({load}).at(0);
  double u_error = 0.0, u_end = 0.0;
  for (Index n = 0; n < model.mesh.node_count(); ++n) {
    const Eigen::Vector3d x = model.mesh.nodes.row(n).transpose();
    const Eigen::Vector3d exact = sigma / E * Eigen::Vector3d(x[0], -nu * x[1], -nu * x[2]);
    u_error = std::max(u_error, (u.row(n).transpose() - exact).norm());
    u_end = std::max(u_end, u(n, 0));
  }
  const auto gauss = fem::gauss_point_stress(model.mesh, model.material, u);
  double s_max = 0.0;
  for (Index p = 0; p < gauss.stress_pa.rows(); ++p) s_max = std::max(s_max, gauss.stress_pa(p, 0));
  const double u_exact = force * length / (E * area);
  // Linear exact field, straight-sided TET10: round-off; 1e-9 relative leaves
  // room for the solver's residual check (1e-8 bound, ~1e-14 measured).
  const char* why = "linear field, straight TET10: round-off, 1e-9";
  return {compare_relative("bar in tension: end displacement u_x(L)", "u = F L / (E A)", "mm", u_exact * 1e3,
                           u_end * 1e3, 1e-9, why),
          compare_absolute("bar in tension: max nodal |u - u_exact| / u(L)", "u = sigma/E (x, -nu y, -nu z)", "1", 0.0,
                           u_error / u_exact, 1e-9, why),
          compare_relative("bar in tension: max Gauss-point sigma_xx", "sigma = F / A", "MPa", sigma * 1e-6,
                           s_max * 1e-6, 1e-9, why)};
}

std::vector<CheckRow> lame_cylinder(const CheckContext&) {
  const kv::LameBoreResult r = kv::solve_lame_cylinder({});
  const char* why = "discretisation, 6 x 12 HEX20: 1 %, worst bore node";
  return {compare_relative("Lamé cylinder, p = 100 MPa: u_r at the bore", "Lamé, plane strain", "mm", r.u_exact_m * 1e3,
                           r.u_worst_m * 1e3, kv::kLameTolerance, why),
          compare_relative("Lamé cylinder: hoop stress at the bore (nodal)", "Lamé, sigma_tt(a)", "MPa",
                           r.hoop_exact_pa * 1e-6, r.hoop_worst_pa * 1e-6, kv::kLameTolerance, why)};
}

std::vector<CheckRow> cholmod_vs_ldlt(const CheckContext&) {
  const kv::LameModel m = kv::lame_model({});
  const kv::DirectSolverComparison c = kv::compare_cholmod_with_ldlt(m.model, m.load);
  return {compare_absolute("CHOLMOD vs Eigen SimplicialLDLT, Lamé system", "same K u = f, independent solver", "1",
                           0.0, c.relative_difference, kv::kDirectSolverTolerance, "round-off, 1e-10 relative")};
}

std::vector<CheckRow> accelerated_link(const CheckContext&) {
  const kv::AcceleratedLinkResult r = kv::solve_accelerated_link(kv::beam_link_mesh());
  require(r.top_nodes > 0 && r.bottom_nodes > 0, "no mid-span nodes on the link's extreme fibres");
  // The +y fibre is in compression (accelerated_link.hpp).
  const char* why = "beam theory at L/h = 15: 2 %";
  return {compare_relative("accelerated link: mid-span sigma_xx, +y fibre", "simply supported beam, M c / I", "MPa",
                           -r.beam_stress_pa * 1e-6, r.top_pa * 1e-6, kv::kBeamTheoryTolerance, why),
          compare_relative("accelerated link: mid-span sigma_xx, -y fibre", "simply supported beam, M c / I", "MPa",
                           r.beam_stress_pa * 1e-6, r.bottom_pa * 1e-6, kv::kBeamTheoryTolerance, why)};
}

std::vector<CheckRow> persson_pin(const CheckContext&) {
  const Log log = Log::quiet();
  const kv::PerssonPlate plate(log);
  const char* why = "a 20 R plate, 192 corners around the hole (half-angle within half a spacing): 5 %";
  std::vector<CheckRow> rows;
  for (const double clearance : {0.0, 15e-6}) {
    const kv::PerssonPinResult r = plate.solve(clearance, 1000.0);
    const std::string what = clearance == 0 ? "elastic pin in its hole, line-to-line" : "elastic pin, 15 um clearance";
    rows.push_back(compare_relative(what + ": peak contact pressure", "Persson, p(0) (docs/contact.md)", "MPa",
                                    r.reference_peak_pa * 1e-6, r.peak_pa * 1e-6, kv::kPerssonTolerance, why));
    rows.push_back(compare_relative(what + ": contact half-angle", "Persson, E* dR / P", "deg",
                                    r.reference_half_angle_rad * 180 / std::numbers::pi,
                                    r.half_angle_rad * 180 / std::numbers::pi, kv::kPerssonTolerance, why));
  }
  return rows;
}

}  // namespace

std::vector<Check> fem_checks() {
  return {
      {"fem.patch_tests", "FEM", true, patch_tests},
      {"fem.bar_tension", "FEM", true, bar_tension},
      {"fem.lame_cylinder", "FEM", true, lame_cylinder},
      {"fem.cholmod_vs_ldlt", "FEM", true, cholmod_vs_ldlt},
      {"loads.accelerated_link", "load transfer", true, accelerated_link},
      {"contact.persson_pin", "load transfer", true, persson_pin},
  };
}

}  // namespace kinetofem::app
