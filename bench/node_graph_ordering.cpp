// node_graph_ordering — CHOLMOD's METIS ordering (on the DoF matrix's graph)
// against METIS on the mesh's node graph given to CHOLMOD
// (CholmodOptions::Ordering::NodeGraphMetis, node_graph_ordering.hpp), on the
// same assembled K_ff: analysis time (ordering + symbolic factorization),
// nnz(L), flops, numeric factorization time, and the difference of the two
// solutions.
//
// Model: the lever of the lever-chain manipulator (meshes/lever.hpp, SPEC §1
// dimensions, TET10, Gmsh) at each element size given (mm), clamped at bore
// A0, a traction on bore A; `--box DOFS` adds the TET10 cantilever 8:1:1 of
// fe_solve_scaling (structured, e.g. 250k). The two orderings run
// alternately `--repeat` times (default 3) on the same matrix; the table shows
// the fastest run of each, so a machine shared with other jobs spoils the
// ratios as little as it can.
//
// Usage: node_graph_ordering [SIZE_MM ...] [--box DOFS] [--repeat N] [--amd] [--no-cache]
//   e.g. build/bench/node_graph_ordering 8 4
// --amd adds one AMD solve as a round-off reference: how far a third
// elimination order puts the solution from CHOLMOD's METIS one.
// Meshes are cached in $TMPDIR/kinetofem_bench_mesh_cache unless --no-cache.
// Columns: bench/README.md.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/meshes/lever.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/node_graph_ordering.hpp"
#include "kinetofem/testing/box_mesh.hpp"

namespace {

using namespace kinetofem;

struct Run {
  double graph_s = 1e300, metis_s = 1e300, analyze_s = 1e300, factorize_s = 1e300, solve_s = 1e300;
  double nnz_l = 0, flops = 0, residual = 0, rcond = 0;
  std::string ordering;
  Eigen::VectorXd x;
};

double load_average() {
  double one = -1;
  if (FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &one) != 1) one = -1;
    std::fclose(f);
  }
  return one;
}

// One analysis + factorization + solve; keeps the fastest times in `best`.
void run_once(const fem::SymmetricUpperMatrix& K, const Eigen::VectorXd& rhs, const fem::Mesh& mesh,
              const fem::DofMap& dofs, fem::CholmodOptions::Ordering which, Run& best) {
  fem::CholmodOptions options;
  options.ordering = which;
  const bool node_graph = which == fem::CholmodOptions::Ordering::NodeGraphMetis;
  fem::CholmodSolver solver(options);
  Stopwatch clock;
  if (node_graph) {
    fem::NodeGraphOrderingTimes t;
    const fem::GivenOrdering ordering = fem::node_graph_ordering(mesh, dofs, &t);
    solver.analyze(K, ordering);
    best.graph_s = std::min(best.graph_s, t.graph_seconds);
    best.metis_s = std::min(best.metis_s, t.metis_seconds);
  } else {
    solver.analyze(K);
  }
  best.analyze_s = std::min(best.analyze_s, clock.seconds());
  clock.restart();
  solver.factorize(K);
  best.factorize_s = std::min(best.factorize_s, clock.seconds());
  clock.restart();
  const Eigen::MatrixXd x = solver.solve(rhs);
  best.solve_s = std::min(best.solve_s, clock.seconds());
  best.nnz_l = solver.statistics().factor_nonzeros;
  best.flops = solver.statistics().factorization_flops;
  best.ordering = solver.statistics().ordering;
  best.residual = solver.statistics().last_relative_residual;
  best.rcond = solver.statistics().reciprocal_condition;
  best.x = x.col(0);
}

void compare(const std::string& label, const fem::Mesh& mesh, const std::string& clamp,
             const fem::LoadCase& load, double mesh_s, int repeat, bool amd) {
  const fem::IsotropicMaterial steel;
  const std::vector<fem::DisplacementSupport> supports = {
      {"clamp", mesh.node_set(clamp), {true, true, true}, Eigen::Vector3d::Zero()}};
  const fem::DofMap dofs(mesh.node_count(), supports);
  Stopwatch clock;
  const fem::AssembledStiffness K = fem::assemble_stiffness(mesh, steel, dofs);
  const double assembly_s = clock.seconds();
  const Eigen::MatrixXd f = fem::assemble_external_forces(mesh, steel, {load});
  Eigen::VectorXd rhs(dofs.free_count());
  for (fem::Index d = 0; d < dofs.dof_count(); ++d)
    if (dofs.equation(d) >= 0) rhs[dofs.equation(d)] = f(d, 0);

  const double load_before = load_average();
  using Ordering = fem::CholmodOptions::Ordering;
  Run old_run, new_run, amd_run;
  for (int r = 0; r < repeat; ++r) {
    run_once(K.free_free, rhs, mesh, dofs, Ordering::Metis, old_run);
    run_once(K.free_free, rhs, mesh, dofs, Ordering::NodeGraphMetis, new_run);
  }
  // Round-off reference: a third elimination order (AMD), once.
  if (amd) run_once(K.free_free, rhs, mesh, dofs, Ordering::Amd, amd_run);
  const double load_after = load_average();
  const double difference = (new_run.x - old_run.x).norm() / old_run.x.norm();
  const fem::NodeGraph graph = fem::build_node_graph(mesh, dofs);

  std::printf("# %s: %lld nodes, %lld elements, %lld free DoFs, nnz(K) %lld (upper); node graph "
              "%lld vertices, %lld edges; meshing %.2f s, assembly %.2f s; load avg %.2f -> %.2f\n",
              label.c_str(), static_cast<long long>(mesh.node_count()),
              static_cast<long long>(mesh.element_count()),
              static_cast<long long>(dofs.free_count()),
              static_cast<long long>(K.free_free.nonZeros()),
              static_cast<long long>(graph.vertex_count()),
              static_cast<long long>(graph.edge_count()), mesh_s, assembly_s, load_before,
              load_after);
  std::printf("%-20s %8s %8s %8s %12s %12s %8s %8s %9s %9s\n", "ordering", "graph_s", "metis_s",
              "anal_s", "nnz(L)", "flops", "fact_s", "solve_s", "residual", "rcond");
  for (const Run* run : {&old_run, &new_run})
    std::printf("%-20s %8s %8s %8.3f %12.5e %12.5e %8.3f %8.4f %9.1e %9.1e\n", run->ordering.c_str(),
                run == &old_run ? "-" : fmt::format("{:.3f}", run->graph_s).c_str(),
                run == &old_run ? "-" : fmt::format("{:.3f}", run->metis_s).c_str(),
                run->analyze_s, run->nnz_l, run->flops, run->factorize_s, run->solve_s,
                run->residual, run->rcond);
  std::printf("ratio old/new: analysis %.2f, factorization %.2f; new/old: nnz(L) %.4f, flops %.4f; "
              "METIS_NodeND share of the new analysis %.0f %%, of analysis + factorization %.1f %%; "
              "|x_new - x_old| / |x_old| = %.2e (best of %d runs each)\n",
              old_run.analyze_s / new_run.analyze_s, old_run.factorize_s / new_run.factorize_s,
              new_run.nnz_l / old_run.nnz_l, new_run.flops / old_run.flops,
              100.0 * new_run.metis_s / new_run.analyze_s,
              100.0 * new_run.metis_s / (new_run.analyze_s + new_run.factorize_s), difference,
              repeat);
  if (amd)
    std::printf("round-off reference: AMD (nnz(L) %.5e, factorization %.2f s): |x_amd - x_metis| / "
                "|x_metis| = %.2e\n",
                amd_run.nnz_l, amd_run.factorize_s, (amd_run.x - old_run.x).norm() / old_run.x.norm());
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  kinetofem::return_freed_memory_to_the_system();  // as the program does (core/process_memory.hpp)
  try {
    std::vector<double> sizes_mm;
    std::vector<long long> box_dofs;
    int repeat = 3;
    bool cache = true, amd = false;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      auto value = [&]() -> std::string {
        require(i + 1 < argc, "option {} needs a value", arg);
        return argv[++i];
      };
      if (arg == "--box") {
        const std::string v = value();
        char* end = nullptr;
        double dofs = std::strtod(v.c_str(), &end);
        if (*end == 'k' || *end == 'K') dofs *= 1e3;
        else if (*end == 'm' || *end == 'M') dofs *= 1e6;
        require(dofs > 0, "--box {}: expected a DoF count like 250k", v);
        box_dofs.push_back(static_cast<long long>(dofs));
      } else if (arg == "--repeat") {
        repeat = std::max(1, std::atoi(value().c_str()));
      } else if (arg == "--amd") {
        amd = true;
      } else if (arg == "--no-cache") {
        cache = false;
      } else if (arg == "-h" || arg == "--help") {
        std::printf("usage: node_graph_ordering [SIZE_MM ...] [--box DOFS] [--repeat N] [--amd] [--no-cache]\n");
        return 0;
      } else {
        const double mm = std::atof(arg.c_str());
        require(mm > 0, "bad element size '{}' (mm)", arg);
        sizes_mm.push_back(mm);
      }
    }
    if (sizes_mm.empty() && box_dofs.empty()) sizes_mm = {8.0};
    std::printf("# node_graph_ordering: CHOLMOD's METIS (DoF graph) vs METIS on the node graph "
                "(cholmod_l_analyze_p); times: best of %d alternating runs\n", repeat);

    for (double mm : sizes_mm) {
      meshes::MeshOptions options;
      options.element_size_m = mm * 1e-3;
      options.order = 2;
      if (cache) options.cache_dir = std::filesystem::temp_directory_path() / "kinetofem_bench_mesh_cache";
      Stopwatch clock;
      const fem::Mesh mesh = meshes::mesh_lever(meshes::LeverDimensions{}, options);
      const double mesh_s = clock.seconds();
      fem::LoadCase load;
      load.tractions = {{"bore_A", Eigen::Vector3d(2e6, 5e5, 1e5)}};
      compare(fmt::format("lever TET10 {} mm", mm), mesh, "bore_A0", load, mesh_s, repeat, amd);
    }
    for (long long target : box_dofs) {
      int n = 1;
      while (3 * testing::box_node_count(fem::ElementType::Tet10, {8 * (n + 1), n + 1, n + 1}) <= target) ++n;
      testing::BoxMeshOptions options;
      options.length_m = {8.0, 1.0, 1.0};
      options.divisions = {8 * n, n, n};
      options.type = fem::ElementType::Tet10;
      Stopwatch clock;
      const fem::Mesh mesh = testing::box_mesh(options);
      const double mesh_s = clock.seconds();
      fem::LoadCase load;
      load.tractions = {{"x1", Eigen::Vector3d(1e5, 1e6, 0.0)}};
      compare(fmt::format("box TET10 8n x n x n, n = {}", n), mesh, "x0", load, mesh_s, repeat, amd);
    }
  } catch (const std::exception& error) {
    std::fprintf(stderr, "node_graph_ordering: %s\n", error.what());
    return 1;
  }
  return 0;
}
