#include "kinetofem/pipeline/part_factorization.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>

#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/blas_threads.hpp"

namespace kinetofem::pipeline {

namespace {

// Factorizes analyses[k] for every k on `threads` threads; the first error is
// rethrown here with its part named, after every thread has finished.
void factorize_side_by_side(const std::vector<std::unique_ptr<SupportedPart>>& supported,
                            const std::vector<Part>& parts, int threads) {
  std::atomic<std::size_t> next{0};
  std::vector<std::exception_ptr> errors(parts.size());
  const auto work = [&] {
    for (std::size_t k = next++; k < parts.size(); k = next++) {
      try {
        supported[k]->analysis().factorize();
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (auto& thread : pool) thread.join();
  for (std::size_t k = 0; k < parts.size(); ++k) {
    if (!errors[k]) continue;
    try {
      std::rethrow_exception(errors[k]);
    } catch (const Error& e) {
      fail("part '{}': {}", parts[k].body(), e.what());
    }
  }
}

}  // namespace

std::vector<std::unique_ptr<SupportedPart>> factorize_parts(const std::vector<Part>& parts,
                                                            const fem::StaticSolverOptions& solver, const Log& log,
                                                            PartFactorizationReport* report) {
  PartFactorizationReport r;
  fem::StaticSolverOptions analysed_only = solver;
  analysed_only.defer_factorization = true;
  std::vector<std::unique_ptr<SupportedPart>> supported;
  int direct_parts = 0;
  for (const auto& part : parts) {
    supported.push_back(std::make_unique<SupportedPart>(part, analysed_only, log));
    const fem::LinearStaticAnalysis& analysis = supported.back()->analysis();
    if (analysis.uses_iterative_solver()) continue;
    ++direct_parts;
    r.predicted_factor_bytes += analysis.solver_statistics().factor_bytes;
  }
  r.limit_bytes = fem::factor_memory_limit_bytes(solver.direct);
  const int hardware = std::max(1, int(std::thread::hardware_concurrency()));
  const int allowed = solver.concurrent_parts > 0 ? solver.concurrent_parts : hardware;
  if (direct_parts < 2)
    r.why = direct_parts == 1 ? "one part on the direct solver" : "no part on the direct solver";
  else if (allowed < 2)
    r.why = "solver.concurrent_parts = 1";
  else if (r.predicted_factor_bytes > r.limit_bytes)
    r.why = fmt::format("their factors ({:.3g} GB together) exceed the {:.3g} GB limit together",
                        r.predicted_factor_bytes * 1e-9, r.limit_bytes * 1e-9);
  else
    r.side_by_side = std::min(allowed, direct_parts);

  if (r.side_by_side < 2) {
    // A linkage without FE parts has nothing to factorize: nothing to say.
    if (!parts.empty()) log.info("factorization: one part after the other ({})", r.why);
  } else {
    r.why = fmt::format("{} parts, factors {:.3g} GB together within the {:.3g} GB limit", direct_parts,
                        r.predicted_factor_bytes * 1e-9, r.limit_bytes * 1e-9);
    log.info("factorization: {} parts side by side, one BLAS thread each ({})", r.side_by_side, r.why);
    Stopwatch clock;
    {
      const fem::BlasThreadLimit one_each(1);
      factorize_side_by_side(supported, parts, r.side_by_side);
    }
    r.seconds = clock.seconds();
    for (const auto& s : supported)
      if (!s->analysis().uses_iterative_solver()) r.flops += s->analysis().solver_statistics().factorization_flops;
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const fem::LinearStaticAnalysis& a = supported[k]->analysis();
      if (a.uses_iterative_solver()) continue;
      log.info("  part '{}': factorization {:.2f} s, {:.1f} GFLOP/s on one BLAS thread", parts[k].body(),
               a.solver_statistics().factorize_seconds, a.solver_statistics().factorize_gflops());
    }
    log.info("  factorizations side by side: {:.2f} s wall, {:.4g} flops, {:.1f} GFLOP/s together", r.seconds,
             r.flops, r.gflops());
  }
  if (report) *report = r;
  return supported;
}

}  // namespace kinetofem::pipeline
