// amg_scaling — the iterative solve path (AMG-preconditioned CG, hypre) on
// large models: the cantilever 8:1:1 of fe_solve_scaling (TET10 or HEX20 box,
// clamped on x = 0, end shear + torsion + self-weight load cases) at a given
// DoF count, solved through LinearStaticAnalysis with the solver method of
// the command line (default auto: CHOLMOD's symbolic analysis decides). See
// bench/README.md.
//
//   amg_scaling [SIZE=2.5M] [--type tet10|hex20] [--rhs N=1] [--method auto|iterative|direct] [--rbm]
//   --rbm: the rigid rotations as AMG interpolation vectors (AmgOptions::rigid_body_modes)
#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/box_mesh.hpp"

using namespace kinetofem;
using namespace kinetofem::fem;

namespace {

double peak_rss_gb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0 * 1e-9;  // ru_maxrss is in KiB on Linux
}

double parse_size(const std::string& text) {
  double scale = 1.0;
  std::string digits = text;
  if (!digits.empty() && (digits.back() == 'k' || digits.back() == 'K')) scale = 1e3;
  if (!digits.empty() && (digits.back() == 'm' || digits.back() == 'M')) scale = 1e6;
  if (scale != 1.0) digits.pop_back();
  return std::stod(digits) * scale;
}

}  // namespace

int main(int argc, char** argv) {
  kinetofem::return_freed_memory_to_the_system();  // as the program does (core/process_memory.hpp)
  double target = 2.5e6;
  ElementType type = ElementType::Tet10;
  int rhs = 1;
  std::string method = "auto";
  bool rigid_body_modes = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--type" && i + 1 < argc) {
      const std::string t = argv[++i];
      type = t == "hex20" ? ElementType::Hex20 : ElementType::Tet10;
    } else if (arg == "--rhs" && i + 1 < argc) {
      rhs = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--method" && i + 1 < argc) {
      method = argv[++i];
    } else if (arg == "--rbm") {
      rigid_body_modes = true;
    } else {
      target = parse_size(arg);
    }
  }
  // n cells across the section, 8n along: the DoF count closest to the target.
  int n = 1;
  for (int k = 1; k < 200; ++k)
    if (std::abs(3.0 * double(testing::box_node_count(type, {8 * k, k, k})) - target) <
        std::abs(3.0 * double(testing::box_node_count(type, {8 * n, n, n})) - target))
      n = k;

  const Log log;
  Stopwatch total;
  FeModel model;
  testing::BoxMeshOptions box;
  box.length_m = Eigen::Vector3d(8.0, 1.0, 1.0);
  box.divisions = {8 * n, n, n};
  box.type = type;
  model.mesh = testing::box_mesh(box);
  model.material = IsotropicMaterial{"steel", 210e9, 0.3, 7850.0};
  model.supports = {{"clamp", model.mesh.node_set("x0"), {true, true, true},
                     Eigen::Vector3d::Zero()}};
  std::vector<LoadCase> cases;
  for (int k = 0; k < rhs; ++k) {
    LoadCase load;
    load.name = "case " + std::to_string(k);
    load.tractions = {{"x1", Eigen::Vector3d(1e5 * k, -1e6, 2e5 * (k % 3))}};
    load.gravity_m_s2 = Eigen::Vector3d(0, 0, -9.81 * (k % 2));
    cases.push_back(load);
  }
  const double mesh_seconds = total.seconds();
  std::printf("# amg_scaling: %s box 8n x n x n, n = %d, %lld nodes, target %.3g DoFs, method %s%s, "
              "%ld cores online\n",
              name_of(type), n, static_cast<long long>(model.mesh.node_count()), target,
              method.c_str(), rigid_body_modes ? ", rigid-body modes as interpolation vectors" : "",
              sysconf(_SC_NPROCESSORS_ONLN));
  std::fflush(stdout);

  StaticSolverOptions options;
  options.method = method == "direct"      ? LinearSolverMethod::Direct
                   : method == "iterative" ? LinearSolverMethod::Iterative
                                           : LinearSolverMethod::Auto;
  options.iterative.rigid_body_modes = rigid_body_modes;
  try {
    LinearStaticAnalysis analysis(model, log, options);
    const auto u = analysis.solve(cases);
    double u_max = 0.0;
    for (const auto& field : u) u_max = std::max(u_max, field.cwiseAbs().maxCoeff());
    const CholmodStatistics& direct = analysis.solver_statistics();
    std::printf("\n%-6s %9s %7s %7s %9s %9s %6s %6s %9s %9s %10s %10s %8s\n", "type", "DoFs",
                "mesh_s", "asm_s", "solver", "factorGB", "levels", "opCx", "setup_s", "iters",
                "solve/rhs", "residual", "RSS_GB");
    if (const AmgStatistics* amg = analysis.iterative_statistics()) {
      std::printf("%-6s %9lld %7.1f %7.1f %9s %9.3g %6d %6.2f %9.1f %9d %10.1f %10.2e %8.2f\n",
                  name_of(type), static_cast<long long>(amg->equations), mesh_seconds,
                  analysis.timings().assembly_seconds, "AMG-PCG", direct.factor_bytes * 1e-9,
                  amg->levels, amg->operator_complexity, amg->setup_seconds, amg->max_iterations(),
                  amg->last_solve_seconds / double(rhs), amg->max_relative_residual(),
                  peak_rss_gb());
    } else {
      std::printf("%-6s %9lld %7.1f %7.1f %9s %9.3g %6s %6s %9.1f %9s %10.2f %10.2e %8.2f\n",
                  name_of(type), static_cast<long long>(direct.equations), mesh_seconds,
                  analysis.timings().assembly_seconds, "CHOLMOD", direct.factor_bytes * 1e-9, "-",
                  "-", direct.analyze_seconds + direct.factorize_seconds, "-",
                  direct.last_solve_seconds / double(rhs), direct.last_relative_residual,
                  peak_rss_gb());
    }
    std::printf("# max |u| %.4g m; wall %.1f s\n", u_max, total.seconds());
  } catch (const std::exception& error) {
    std::printf("# failed: %s (peak RSS %.2f GB)\n", error.what(), peak_rss_gb());
    return 1;
  }
  return 0;
}
