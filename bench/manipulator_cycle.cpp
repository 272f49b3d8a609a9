// Benchmark: the full motion-to-stress cycle of a manipulator case at a
// chosen mesh size — meshing, dynamics, per link: assembly, analysis,
// factorization, block solves over all output times, stress recovery — with
// DoFs, nnz(L), factor memory, flops and the peak memory of the process.
//
//   bench/manipulator_cycle [CASE.toml] [element_size_mm ...] [--set KEY=VALUE ...]
//   e.g. build/bench/manipulator_cycle cases/lever_chain_manipulator/case.toml 8 4 3
//        build/bench/manipulator_cycle cases/lever_manipulator/case.toml 3.2 --set vibration.enabled=false
//   --set: case keys overridden as by `kinetofem run --set`, after the mesh size.
//
// Each size runs in a child process so its peak memory (ru_maxrss) is its own.
#include <dlfcn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/app/case_file.hpp"
#include "kinetofem/app/manipulator_job.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/dense_product.hpp"

namespace {

// Best of three C = A B on n x n matrices through the program's BLAS, GFLOP/s
// (2 n^3 flops): the rate the factorizations are measured against.
double dgemm_gflops(int n) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Random(n, n), b = Eigen::MatrixXd::Random(n, n);
  Eigen::MatrixXd c(n, n);
  double best = 1e300;
  for (int repeat = 0; repeat < 3; ++repeat) {
    const kinetofem::Stopwatch clock;
    kinetofem::fem::blas_product(a, b, c);
    best = std::min(best, clock.seconds());
  }
  return 2.0 * std::pow(double(n), 3) / best * 1e-9;
}

// OpenBLAS's kernel (its openblas_get_corename), or "unknown" for another BLAS.
std::string blas_kernel() {
  using CoreName = char* (*)();
  const auto f = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  return f ? std::string(f()) : std::string("unknown");
}

double peak_rss_gb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / (1024.0 * 1024.0);  // ru_maxrss is in KiB on Linux
}

int run_one(const std::string& case_path, double size_mm, double dgemm_gf_s, const std::vector<std::string>& overrides) {
  using namespace kinetofem::app;
  CaseFile base = CaseFile::load(case_path, manipulator_schema());
  std::string text = base.text();
  // Replace the mesh size: append an override table is not valid TOML (the
  // table exists), so rewrite the key's line.
  const std::string key = "element_size_mm";
  const auto at = text.find(key);
  if (at == std::string::npos) kinetofem::fail("{}: no mesh.element_size_mm line to override", case_path);
  const auto end = text.find('\n', at);
  text.replace(at, end - at, key + " = " + std::to_string(size_mm));
  const CaseFile c = CaseFile::parse(text, case_path, manipulator_schema(), false, overrides);
  RunOptions options;
  options.output_dir = std::filesystem::temp_directory_path() / "kinetofem_bench_cycle";
  options.quiet = true;
  const ManipulatorSummary s = run_manipulator(c, options);
  for (const auto& l : s.links)
    std::printf("%7.2f %-7s %9ld %8.2f %8.2f %8.2f %9.3f %10.4f %9.2f %10.3e %8.2f %8.1f %6ld\n", size_mm, l.body.c_str(),
                l.dofs, l.assembly_seconds, l.analyze_seconds, l.factorize_seconds, l.solve_seconds,
                l.solve_seconds / double(l.right_hand_sides), l.recovery_seconds, l.factor_nonzeros,
                l.factor_bytes * 1e-9, l.factorization_flops / std::max(l.factorize_seconds, 1e-9) * 1e-9,
                l.right_hand_sides);
  // The elastic assembly against the per-link analysis of the same meshes
  // and output times (issue target: assembly <= 1.2 x per-link).
  double per_link = 0.0;
  for (const auto& l : s.links)
    per_link += l.assembly_seconds + l.analyze_seconds + l.factorize_seconds + l.solve_seconds + l.recovery_seconds;
  if (s.assembly) {
    const auto& st = s.assembly->statistics;
    const double poses = st.pose_seconds() * double(st.poses);
    std::printf("%7.2f %-7s elastic assembly: setup %.2f s (factorizations %.2f s, %ld interface columns), %ld poses "
                "%.2f s (%.1f ms each: loads %.2f, load solves %.2f, system %.2f, recovery %.2f s); total %.2f s vs "
                "per-link analysis %.2f s: ratio %.2f\n",
                size_mm, "all", st.setup_seconds, st.factorize_seconds, st.interface_columns, st.poses, poses,
                1e3 * st.pose_seconds(), st.loads_seconds, st.load_solve_seconds, st.system_seconds, st.recovery_seconds,
                st.setup_seconds + poses, per_link, (st.setup_seconds + poses) / std::max(per_link, 1e-9));
  }
  // The vibration when the case turns it on: its own line, and
  // the cycle's limit ratio below is of the stress pipeline without it.
  double vibration = 0.0;
  if (s.vibration) {
    const auto& v = *s.vibration;
    vibration = v.reduction_seconds + v.modes_seconds + v.response_seconds;
    std::string parts;
    for (const auto& r : v.reductions)
      parts += fmt::format("{}{} {} + {} + {}", parts.empty() ? "" : ", ", r.body, r.boundary, r.modes, r.residual);
    std::printf("%7.2f %-7s vibration: reduction %.2f s (%s coordinates, part modes up to %.0f Hz), %d modes at %zu "
                "poses %.3f s, response %.3f s; first frequency %.3f .. %.3f Hz\n",
                size_mm, "all", v.reduction_seconds, parts.c_str(), v.cutoff_hz, v.modes, v.time_s.size(),
                v.modes_seconds, v.response_seconds, v.lowest_first_hz, v.highest_first_hz);
  }
  std::printf("%7.2f %-7s meshing %.2f s, dynamics %.3f s, whole cycle %.2f s (without the vibration %.2f s), peak "
              "memory %.2f GB\n",
              size_mm, "all", s.meshing_seconds, s.dynamics_seconds, s.total_seconds, s.total_seconds - vibration,
              peak_rss_gb());
  // The limit: every part's factorization flops at the DGEMM rate.
  double flops = 0.0, factorize = 0.0;
  for (const auto& l : s.links) flops += l.factorization_flops, factorize += l.factorize_seconds;
  const double limit = flops / (dgemm_gf_s * 1e9);
  std::printf("%7.2f %-7s factorizations %.4g flops in %.2f s: %.1f GFLOP/s = %.0f %% of DGEMM %.1f GFLOP/s; limit %.2f s, "
              "cycle (without the vibration) / limit %.2f\n",
              size_mm, "all", flops, factorize, flops / std::max(factorize, 1e-9) * 1e-9,
              100.0 * flops / std::max(factorize, 1e-9) / (dgemm_gf_s * 1e9), dgemm_gf_s, limit,
              (s.total_seconds - vibration) / std::max(limit, 1e-9));
  // The aggregate rate: the parts factorized side by side (one BLAS thread
  // each), their flops over the wall time they took together (the
  // target: 60 % of DGEMM). One after the other it is the line above.
  const auto& fr = s.factorization;
  if (fr.side_by_side > 1)
    std::printf("%7.2f %-7s factorizations side by side (%d at a time): %.4g flops in %.2f s wall: %.1f GFLOP/s "
                "together = %.0f %% of DGEMM\n",
                size_mm, "all", fr.side_by_side, fr.flops, fr.seconds, fr.gflops(),
                100.0 * fr.gflops() / dgemm_gf_s);
  else
    std::printf("%7.2f %-7s factorizations one after the other: %s\n", size_mm, "all", fr.why.c_str());
  std::fflush(stdout);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  kinetofem::return_freed_memory_to_the_system();  // as the program does (core/process_memory.hpp)
  const std::string case_path = argc > 1 ? argv[1] : "cases/lever_chain_manipulator/case.toml";
  std::vector<double> sizes;
  std::vector<std::string> overrides;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--set" && i + 1 < argc)
      overrides.push_back(argv[++i]);
    else
      sizes.push_back(std::atof(argv[i]));
  }
  if (sizes.empty()) sizes = {8.0, 5.0};
  std::printf("# manipulator cycle benchmark: %s\n", case_path.c_str());
  for (const auto& o : overrides) std::printf("# --set %s\n", o.c_str());
  const double dgemm = dgemm_gflops(4000);
  std::printf("# BLAS kernel %s, DGEMM (4000 x 4000) %.1f GFLOP/s\n", blas_kernel().c_str(), dgemm);
  std::printf("%7s %-7s %9s %8s %8s %8s %9s %10s %9s %10s %8s %8s %6s\n", "h_mm", "link", "DoFs", "asm_s", "anal_s",
              "fact_s", "solve_s", "s/step", "stress_s", "nnz(L)", "L_GB", "GF/s", "steps");
  std::fflush(stdout);
  for (double size : sizes) {
    const pid_t pid = fork();
    if (pid == 0) {
      try {
        std::_Exit(run_one(case_path, size, dgemm, overrides));
      } catch (const std::exception& e) {
        std::printf("%7.2f failed: %s\n", size, e.what());
        std::fflush(stdout);
        std::_Exit(1);
      }
    }
    int status = 0;
    waitpid(pid, &status, 0);
  }
  return 0;
}
