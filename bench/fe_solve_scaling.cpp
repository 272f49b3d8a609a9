// fe_solve_scaling — cost of a linear static FE solve against model size.
//
// Model: the cantilever 8:1:1 (box 8 m x 1 m x 1 m, steel, clamped at x = 0,
// end shear traction on x = 8 m), structured 8n x n x n cells of HEX20, TET10
// (six per cell) or HEX8, n chosen so the model has about the requested
// number of DoFs. For each size and element type it times the steps of
// LinearStaticAnalysis one by one (assembly, CHOLMOD analyze / factorize /
// solve, stress recovery) and prints one table row; before the table it
// measures the machine's DGEMM rate (BLAS dgemm on 4000 x 4000 matrices, the
// same BLAS and threads CHOLMOD's supernodal factorization uses), so the
// factorization rate can be read as a fraction of the machine's peak.
//
// Usage: fe_solve_scaling [DOFS ...] [--types hex20,tet10,hex8] [--rhs 20] [--dgemm 4000]
//   DOFS like 50k, 250k, 1M (default 50k 250k 1M). Columns: bench/README.md.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/assembly.hpp"
#include "kinetofem/solver/cholmod_solver.hpp"
#include "kinetofem/solver/dof_map.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/box_mesh.hpp"

extern "C" void dgemm_(const char* transa, const char* transb, const int* m, const int* n,
                       const int* k, const double* alpha, const double* a, const int* lda,
                       const double* b, const int* ldb, const double* beta, double* c,
                       const int* ldc);

namespace {

using namespace kinetofem;
using fem::ElementType;

double peak_rss_gb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) * 1024.0 / 1e9;  // ru_maxrss is in KiB on Linux
}

// Best of three C = A B on n x n matrices, GFLOP/s (2 n^3 flops).
double dgemm_gflops(int n) {
  std::mt19937_64 random(1);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> a(size_t(n) * size_t(n)), b(a.size()), c(a.size(), 0.0);
  for (auto& v : a) v = uniform(random);
  for (auto& v : b) v = uniform(random);
  const double one = 1.0, zero = 0.0;
  double best = 1e300;
  for (int repeat = 0; repeat < 3; ++repeat) {
    const Stopwatch clock;
    dgemm_("N", "N", &n, &n, &n, &one, a.data(), &n, b.data(), &n, &zero, c.data(), &n);
    best = std::min(best, clock.seconds());
  }
  return 2.0 * std::pow(double(n), 3) / best * 1e-9;
}

long long parse_dofs(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  double scale = 1.0;
  if (*end == 'k' || *end == 'K') scale = 1e3, ++end;
  else if (*end == 'm' || *end == 'M') scale = 1e6, ++end;
  require(end != text.c_str() && *end == '\0' && value > 0, "bad DoF count '{}' (e.g. 50k, 1M)",
          text);
  return static_cast<long long>(value * scale);
}

ElementType parse_type(const std::string& text) {
  if (text == "hex20") return ElementType::Hex20;
  if (text == "tet10") return ElementType::Tet10;
  if (text == "hex8") return ElementType::Hex8;
  if (text == "tet4") return ElementType::Tet4;
  fail("unknown element type '{}' (hex20, tet10, hex8, tet4)", text);
}

// Cells across the section n so that 3 x nodes of the 8n x n x n box is
// closest to the target.
int cells_for(ElementType type, long long target_dofs) {
  int best = 1;
  for (int n = 1; n < 2000; ++n) {
    const long long dofs = 3 * testing::box_node_count(type, {8 * n, n, n});
    const long long best_dofs = 3 * testing::box_node_count(type, {8 * best, best, best});
    if (std::llabs(dofs - target_dofs) < std::llabs(best_dofs - target_dofs)) best = n;
    if (dofs > 2 * target_dofs) break;
  }
  return best;
}

void run(ElementType type, long long target_dofs, int block_rhs, double dgemm, const fem::CholmodOptions& cholmod) {
  const int n = cells_for(type, target_dofs);
  fem::Mesh mesh;
  {
    testing::BoxMeshOptions options;
    options.length_m = {8.0, 1.0, 1.0};
    options.divisions = {8 * n, n, n};
    options.type = type;
    mesh = testing::box_mesh(options);
  }
  const fem::IsotropicMaterial steel;
  const std::vector<fem::DisplacementSupport> supports = {
      {"clamp", mesh.node_set("x0"), {true, true, true}, Eigen::Vector3d::Zero()}};
  const fem::DofMap dofs(mesh.node_count(), supports);

  Stopwatch clock;
  const fem::AssembledStiffness K = fem::assemble_stiffness(mesh, steel, dofs);
  const double assembly_s = clock.seconds();

  // Load cases: end shear plus, for the block, the same load turned about x.
  std::vector<fem::LoadCase> cases;
  for (int k = 0; k < block_rhs; ++k) {
    fem::LoadCase load;
    const double angle = 2.0 * M_PI * k / block_rhs;
    load.tractions = {{"x1", 1e6 * Eigen::Vector3d(0.1, std::cos(angle), std::sin(angle))}};
    cases.push_back(load);
  }
  const Eigen::MatrixXd f = fem::assemble_external_forces(mesh, steel, cases);
  Eigen::MatrixXd rhs(dofs.free_count(), block_rhs);
  for (fem::Index d = 0; d < dofs.dof_count(); ++d)
    if (dofs.equation(d) >= 0) rhs.row(dofs.equation(d)) = f.row(d);

  fem::CholmodSolver solver(cholmod);
  clock.restart();
  solver.analyze(K.free_free);
  const double analyze_s = clock.seconds();
  clock.restart();
  solver.factorize(K.free_free);
  const double factorize_s = clock.seconds();
  clock.restart();
  const Eigen::MatrixXd x1 = solver.solve(rhs.col(0));
  const double solve1_s = clock.seconds();
  clock.restart();
  const Eigen::MatrixXd xb = solver.solve(rhs);
  const double solve_block_s = clock.seconds();
  const fem::CholmodStatistics stats = solver.statistics();

  fem::DisplacementField u(mesh.node_count(), 3);
  const Eigen::VectorXd full = dofs.expand(x1.col(0));
  for (fem::Index node = 0; node < mesh.node_count(); ++node)
    u.row(node) = full.segment<3>(3 * node).transpose();
  clock.restart();
  const fem::NodalStress stress = fem::recover_nodal_stress(mesh, steel, u);
  const double stress_s = clock.seconds();

  const double gflops = stats.factorization_flops / factorize_s * 1e-9;
  std::printf("%-6s %4d %9lld %8.2f %8.2f %8.2f %9.4f %9.4f %10.3e %10.3e %10.3e %7.1f %8.2f %8.1f %6.2f %6.1f\n",
              fem::name_of(type), n, static_cast<long long>(dofs.free_count()), assembly_s,
              analyze_s, factorize_s, solve1_s, solve_block_s / block_rhs,
              double(stats.matrix_nonzeros), stats.factor_nonzeros, stats.factorization_flops,
              gflops, stress_s, dgemm, gflops / dgemm, peak_rss_gb());
  std::fflush(stdout);
  (void)stress;
}

}  // namespace

int main(int argc, char** argv) {
  kinetofem::return_freed_memory_to_the_system();  // as the program does (core/process_memory.hpp)
  try {
    std::vector<long long> sizes;
    std::vector<ElementType> types = {ElementType::Hex20, ElementType::Tet10, ElementType::Hex8};
    int block_rhs = 20, dgemm_n = 4000;
    fem::CholmodOptions cholmod;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      auto value = [&]() -> std::string {
        require(i + 1 < argc, "option {} needs a value", arg);
        return argv[++i];
      };
      if (arg == "--types") {
        types.clear();
        std::string list = value();
        for (size_t start = 0; start <= list.size();) {
          const size_t comma = std::min(list.find(',', start), list.size());
          types.push_back(parse_type(list.substr(start, comma - start)));
          start = comma + 1;
        }
      } else if (arg == "--rhs") {
        block_rhs = std::max(1, std::atoi(value().c_str()));
      } else if (arg == "--dgemm") {
        dgemm_n = std::max(100, std::atoi(value().c_str()));
      } else if (arg == "--relax") {
        // CHOLMOD's relaxed amalgamation: nrelax0,nrelax1,nrelax2:zrelax0,zrelax1,zrelax2
        const std::string v = value();
        require(std::sscanf(v.c_str(), "%d,%d,%d:%lf,%lf,%lf", &cholmod.relax_columns[0], &cholmod.relax_columns[1],
                            &cholmod.relax_columns[2], &cholmod.relax_zero_fraction[0],
                            &cholmod.relax_zero_fraction[1], &cholmod.relax_zero_fraction[2]) == 6,
                "--relax {}: expected N0,N1,N2:Z0,Z1,Z2", v);
      } else if (arg == "-h" || arg == "--help") {
        std::printf("usage: fe_solve_scaling [DOFS ...] [--types hex20,tet10,hex8] [--rhs 20] "
                    "[--dgemm 4000] [--relax N0,N1,N2:Z0,Z1,Z2]\n");
        return 0;
      } else {
        sizes.push_back(parse_dofs(arg));
      }
    }
    if (sizes.empty()) sizes = {50'000, 250'000, 1'000'000};

    const double dgemm = dgemm_gflops(dgemm_n);
    std::printf("# fe_solve_scaling: cantilever 8:1:1, clamped, end shear; DGEMM %dx%d: %.1f "
                "GFLOP/s; block of %d right-hand sides; CHOLMOD relaxed amalgamation %d,%d,%d:%g,%g,%g\n",
                dgemm_n, dgemm_n, dgemm, block_rhs, cholmod.relax_columns[0], cholmod.relax_columns[1],
                cholmod.relax_columns[2], cholmod.relax_zero_fraction[0], cholmod.relax_zero_fraction[1],
                cholmod.relax_zero_fraction[2]);
    std::printf("%-6s %4s %9s %8s %8s %8s %9s %9s %10s %10s %10s %7s %8s %8s %6s %6s\n", "type",
                "n", "DoFs", "asm_s", "anal_s", "fact_s", "solve1_s", "blkRHS_s", "nnz(K)",
                "nnz(L)", "flops", "GF/s", "stress_s", "dgemmGF", "ratio", "RSS_GB");
    for (long long target : sizes)
      for (ElementType type : types) {
        try {
          run(type, target, block_rhs, dgemm, cholmod);
        } catch (const Error& error) {
          std::printf("%-6s ~%lld DoFs: skipped: %s\n", fem::name_of(type), target, error.what());
          std::fflush(stdout);
        }
      }
    // The machine may have been busier at the start: measure DGEMM again.
    std::printf("# DGEMM %dx%d after the runs: %.1f GFLOP/s\n", dgemm_n, dgemm_n,
                dgemm_gflops(dgemm_n));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fe_solve_scaling: %s\n", error.what());
    return 1;
  }
  return 0;
}
