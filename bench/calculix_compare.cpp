// calculix_compare — kinetofem side by side with CalculiX (ccx) on the
// identical problem.
//
// Model: the cantilever 8:1:1 of fe_solve_scaling (box 8 m x 1 m x 1 m, steel,
// clamped at x = 0, shear traction on the end x = 8 m), 8n x n x n cells of
// HEX20 or TET10 (six per cell), n chosen so the model has about the requested
// number of DoFs. Load case k turns the end traction about x by 2 pi k / cases.
// The model goes to ccx through write_calculix_deck (calculix_export.hpp):
// same mesh, material and supports, and the load as the consistent nodal
// forces kinetofem assembles, so both programs solve the same K u = f.
//
// For each model, one after the other in this process:
//   static  one load case. kinetofem: LinearStaticAnalysis (Jacobian check,
//           assembly, CHOLMOD analyze + factorize), solve, nodal stress
//           recovery. ccx: one *STEP (*STATIC, its default solver — SPOOLES in
//           the Debian build), *NODE PRINT U of all nodes, *EL FILE S.
//   cycle   `cases` load cases (default 100). kinetofem: the same analysis,
//           one factorization, all cases as one block solve (and, in a second
//           column, nodal stresses of every case). ccx: one *STEP per case,
//           *NODE PRINT U of the loaded end's nodes (little output, so ccx's
//           time is its solving). With --ccx-steps K < cases ccx runs only the
//           first K steps and its time for all cases is extrapolated:
//           t(all) = t(1 step) + (cases - 1) (t(K) - t(1)) / (K - 1),
//           marked "extrap." in the table.
// ccx runs through std::system with OMP_NUM_THREADS (default 2), its whole
// run timed by a wall clock (reading the deck included; writing the deck is
// not counted for either program). Displacements are compared on every node
// (static) or on the printed nodes for every case (cycle), relative to the
// largest displacement; nodal von Mises stresses (static) relative to the
// largest, over all nodes and away from the clamp's edges (x > 1 m), where
// the stress is singular and the two programs' extrapolations differ most.
//
// Usage: calculix_compare [DOFS ...] [--types hex20,tet10] [--cases 100]
//                         [--ccx-steps K] [--threads 2] [--no-cycle] [--keep DIR]
//   DOFS like 50k, 250k (default 50k 250k). Exit status 0 with "ccx not
//   found" when CalculiX is not installed (apt-get install calculix-ccx).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "kinetofem/core/process_memory.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/core/log.hpp"
#include "kinetofem/solver/calculix_export.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/solver/stress_recovery.hpp"
#include "kinetofem/testing/box_mesh.hpp"

namespace {

using namespace kinetofem;
using fem::ElementType;
namespace fs = std::filesystem;

struct Options {
  std::vector<long long> sizes;
  std::vector<ElementType> types = {ElementType::Hex20, ElementType::Tet10};
  int cases = 100;
  int ccx_steps = 0;  // 0: all cases
  int threads = 2;
  bool cycle = true;
  fs::path keep;      // empty: a temporary folder, removed
};

std::string load_average() {
  std::ifstream in("/proc/loadavg");
  double one = 0, five = 0, fifteen = 0;
  in >> one >> five >> fifteen;
  return fmt::format("{:.2f} {:.2f} {:.2f}", one, five, fifteen);
}

long long parse_dofs(const std::string& text) {
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  double scale = 1.0;
  if (*end == 'k' || *end == 'K') scale = 1e3, ++end;
  else if (*end == 'm' || *end == 'M') scale = 1e6, ++end;
  require(end != text.c_str() && *end == '\0' && value > 0, "bad DoF count '{}' (e.g. 50k, 250k)",
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

std::vector<fem::LoadCase> load_cases(int count) {
  std::vector<fem::LoadCase> cases;
  for (int k = 0; k < count; ++k) {
    fem::LoadCase load;
    const double angle = 2.0 * M_PI * k / count;
    load.name = fmt::format("case{}", k);
    load.tractions = {{"x1", 1e6 * Eigen::Vector3d(0.1, std::cos(angle), std::sin(angle))}};
    cases.push_back(load);
  }
  return cases;
}

// Runs ccx on dir/job.inp; wall seconds of the whole run. Throws with the
// end of ccx's output if it fails.
double run_ccx(const fs::path& dir, const std::string& job, int threads) {
  const std::string command =
      fmt::format("cd '{}' && OMP_NUM_THREADS={} ccx -i {} > {}.log 2>&1", dir.string(), threads,
                  job, job);
  const Stopwatch clock;
  const int status = std::system(command.c_str());
  const double seconds = clock.seconds();
  if (status != 0 || !fs::exists(dir / (job + ".dat"))) {
    std::ifstream log(dir / (job + ".log"));
    std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
    fail("ccx failed on {} (status {}): ...{}", (dir / (job + ".inp")).string(), status,
         text.substr(text.size() > 1500 ? text.size() - 1500 : 0));
  }
  return seconds;
}

// What ccx said about its solver and threads (lines of its log).
std::string ccx_solver_note(const fs::path& log_path) {
  std::ifstream log(log_path);
  std::string line, note;
  while (std::getline(log, line)) {
    if (line.find("SPOOLES") != std::string::npos || line.find("PARDISO") != std::string::npos ||
        line.find("cpu(s) for") != std::string::npos) {
      line.erase(0, line.find_first_not_of(' '));
      if (note.find(line) == std::string::npos) note += (note.empty() ? "" : " | ") + line;
    }
  }
  return note;
}

// max |a - b| over the rows where b is known, over max |a|.
double relative_difference(const fem::DisplacementField& ours, const fem::DisplacementField& theirs,
                           double scale) {
  double worst = 0.0;
  for (Eigen::Index i = 0; i < ours.rows(); ++i)
    if (!std::isnan(theirs(i, 0))) worst = std::max(worst, (ours.row(i) - theirs.row(i)).cwiseAbs().maxCoeff());
  return worst / scale;
}

// kinetofem's steps: assembly, CHOLMOD analyze, factorize, the last solve.
std::string kinetofem_steps(const fem::LinearStaticAnalysis& analysis) {
  const fem::CholmodStatistics& stats = analysis.solver_statistics();
  return fmt::format("kf asm {:.2f} anal {:.2f} fact {:.2f} solve {:.2f} s ({} rhs)",
                     analysis.timings().assembly_seconds, stats.analyze_seconds,
                     stats.factorize_seconds, stats.last_solve_seconds, stats.last_solve_rhs);
}

struct Row {
  std::string model, kind, note;
  long long dofs = 0;
  int cases = 1;
  double kf_s = 0, kf_stress_s = 0, ccx_s = 0, du = 0, dvm_all = 0, dvm_away = 0, vm_kf = 0,
         vm_ccx = 0;
  double target = 0;
  std::string load;
};

void print_row(const Row& r) {
  // The target is judged on the ratio with kinetofem's stress recovery
  // included (ccx computes stresses in every step as well).
  const double ratio = r.ccx_s / r.kf_s, ratio_vm = r.ccx_s / r.kf_stress_s;
  std::printf("%-6s %8lld %-7s %5d %9.2f %9.2f %9.2f %7.1f %7.1f %5.0fx %-4s %9.2e", r.model.c_str(),
              r.dofs, r.kind.c_str(), r.cases, r.kf_s, r.kf_stress_s, r.ccx_s, ratio, ratio_vm,
              r.target, ratio_vm >= r.target ? "met" : "NOT", r.du);
  if (r.kind == "static")
    std::printf(" %8.2e %8.2e %9.4g %9.4g", r.dvm_all, r.dvm_away, r.vm_kf * 1e-6, r.vm_ccx * 1e-6);
  else
    std::printf(" %8s %8s %9s %9s", "-", "-", "-", "-");
  std::printf("  %s  %s\n", r.load.c_str(), r.note.c_str());
  std::fflush(stdout);
}

void compare(ElementType type, long long target_dofs, const Options& options, const fs::path& dir) {
  const int n = cells_for(type, target_dofs);
  fem::FeModel model;
  {
    testing::BoxMeshOptions box;
    box.length_m = {8.0, 1.0, 1.0};
    box.divisions = {8 * n, n, n};
    box.type = type;
    model.mesh = testing::box_mesh(box);
  }
  model.supports = {{"clamp", model.mesh.node_set("x0"), {true, true, true}, Eigen::Vector3d::Zero()}};
  const Log quiet = Log::quiet();
  const std::string tag = fmt::format("{}_{}", fem::name_of(type), n);

  // --- one static load case -------------------------------------------------
  {
    const std::vector<fem::LoadCase> one = load_cases(1);
    fem::CalculixDeckOptions deck;
    deck.heading = "kinetofem calculix_compare static " + tag;
    deck.file_stresses = true;
    Stopwatch clock;
    const std::string job = "static_" + tag;
    fem::write_calculix_deck(model, one, dir / (job + ".inp"), deck);
    const double deck_s = clock.seconds();

    Row row;
    row.model = fem::name_of(type);
    row.kind = "static";
    row.target = 3;
    const std::string load_before = load_average();
    clock.restart();
    fem::LinearStaticAnalysis analysis(model, quiet);
    const std::vector<fem::DisplacementField> u = analysis.solve(one);
    row.kf_s = clock.seconds();
    const fem::NodalStress stress = fem::recover_nodal_stress(model.mesh, model.material, u[0]);
    row.kf_stress_s = clock.seconds();
    row.dofs = analysis.dofs().free_count();

    row.ccx_s = run_ccx(dir, job, options.threads);
    row.load = load_before + " / " + load_average();
    const auto theirs = fem::read_calculix_dat_displacements(dir / (job + ".dat"), model.mesh.node_count());
    require(theirs.size() == 1, "ccx .dat of {} has {} steps, expected 1", job, theirs.size());
    require(!theirs[0].hasNaN(), "ccx .dat of {} lacks some nodes", job);
    row.du = relative_difference(u[0], theirs[0], u[0].cwiseAbs().maxCoeff());

    const auto ccx_stress = fem::read_calculix_frd_stresses(dir / (job + ".frd"), model.mesh.node_count());
    require(ccx_stress.size() == 1, "ccx .frd of {} has {} stress blocks, expected 1", job,
            ccx_stress.size());
    double vm_max = stress.von_mises_pa.maxCoeff(), worst_all = 0, worst_away = 0, ccx_max = 0;
    for (fem::Index i = 0; i < model.mesh.node_count(); ++i) {
      const double vm = fem::von_mises(ccx_stress[0].row(i).transpose());
      ccx_max = std::max(ccx_max, vm);
      const double diff = std::abs(vm - stress.von_mises_pa[i]);
      worst_all = std::max(worst_all, diff);
      if (model.mesh.nodes(i, 0) > 1.0) worst_away = std::max(worst_away, diff);
    }
    row.dvm_all = worst_all / vm_max;
    row.dvm_away = worst_away / vm_max;
    row.vm_kf = vm_max;
    row.vm_ccx = ccx_max;
    row.note = fmt::format("{}; deck {:.1f} s; {}", kinetofem_steps(analysis), deck_s,
                           ccx_solver_note(dir / (job + ".log")));
    print_row(row);
    fs::remove(dir / (job + ".frd"));
    fs::remove(dir / (job + ".dat"));
  }

  // --- the cycle of many load cases ----------------------------------------------
  if (!options.cycle) return;
  const std::vector<fem::LoadCase> cases = load_cases(options.cases);
  const int ccx_steps = options.ccx_steps > 0 ? std::min(options.ccx_steps, options.cases) : options.cases;
  const bool extrapolate = ccx_steps < options.cases;
  Row row;
  row.model = fem::name_of(type);
  row.kind = "cycle";
  row.cases = options.cases;
  row.target = 50;
  const std::string load_before = load_average();
  Stopwatch clock;
  fem::LinearStaticAnalysis analysis(model, quiet);
  const std::vector<fem::DisplacementField> u = analysis.solve(cases);
  row.kf_s = clock.seconds();
  for (const auto& field : u) (void)fem::recover_nodal_stress(model.mesh, model.material, field);
  row.kf_stress_s = clock.seconds();
  row.dofs = analysis.dofs().free_count();

  const std::vector<fem::Index>& probes = model.mesh.node_set("x1");
  fem::CalculixDeckOptions deck;
  deck.print_all_displacements = false;
  deck.printed_nodes = probes;
  const std::string job = "cycle_" + tag;
  const Eigen::MatrixXd forces = fem::assemble_external_forces(model.mesh, model.material, cases);
  clock.restart();
  fem::write_calculix_deck(model, Eigen::MatrixXd(forces.leftCols(ccx_steps)), dir / (job + ".inp"), deck);
  const double deck_s = clock.seconds();
  const double ccx_k_s = run_ccx(dir, job, options.threads);
  row.load = load_before + " / " + load_average();
  const auto theirs = fem::read_calculix_dat_displacements(dir / (job + ".dat"), model.mesh.node_count());
  require(int(theirs.size()) == ccx_steps, "ccx .dat of {} has {} steps, expected {}", job,
          theirs.size(), ccx_steps);
  for (int k = 0; k < ccx_steps; ++k)
    row.du = std::max(row.du, relative_difference(u[size_t(k)], theirs[size_t(k)],
                                                  u[size_t(k)].cwiseAbs().maxCoeff()));
  row.note = fmt::format("{}; deck {:.1f} s; ccx ran {} steps in {:.2f} s",
                         kinetofem_steps(analysis), deck_s, ccx_steps, ccx_k_s);
  if (extrapolate) {
    // One step alone, for the fixed cost (reading the deck, set-up).
    const std::string job1 = job + "_1";
    fem::write_calculix_deck(model, Eigen::MatrixXd(forces.leftCols(1)), dir / (job1 + ".inp"), deck);
    const double ccx_1_s = run_ccx(dir, job1, options.threads);
    const double per_step = (ccx_k_s - ccx_1_s) / std::max(1, ccx_steps - 1);
    row.ccx_s = ccx_1_s + (options.cases - 1) * per_step;
    row.note += fmt::format(", 1 step in {:.2f} s: extrap. {:.2f} s/step", ccx_1_s, per_step);
  } else {
    row.ccx_s = ccx_k_s;
  }
  print_row(row);
  fs::remove(dir / (job + ".dat"));
}

}  // namespace

int main(int argc, char** argv) {
  kinetofem::return_freed_memory_to_the_system();  // as the program does (core/process_memory.hpp)
  try {
    Options options;
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      auto value = [&]() -> std::string {
        require(i + 1 < argc, "option {} needs a value", arg);
        return argv[++i];
      };
      if (arg == "--types") {
        options.types.clear();
        const std::string list = value();
        for (size_t start = 0; start <= list.size();) {
          const size_t comma = std::min(list.find(',', start), list.size());
          options.types.push_back(parse_type(list.substr(start, comma - start)));
          start = comma + 1;
        }
      } else if (arg == "--cases") {
        options.cases = std::max(1, std::atoi(value().c_str()));
      } else if (arg == "--ccx-steps") {
        options.ccx_steps = std::max(0, std::atoi(value().c_str()));
      } else if (arg == "--threads") {
        options.threads = std::max(1, std::atoi(value().c_str()));
      } else if (arg == "--no-cycle") {
        options.cycle = false;
      } else if (arg == "--keep") {
        options.keep = value();
      } else if (arg == "-h" || arg == "--help") {
        std::printf("usage: calculix_compare [DOFS ...] [--types hex20,tet10] [--cases 100] "
                    "[--ccx-steps K] [--threads 2] [--no-cycle] [--keep DIR]\n");
        return 0;
      } else {
        options.sizes.push_back(parse_dofs(arg));
      }
    }
    if (options.sizes.empty()) options.sizes = {50'000, 250'000};

    if (std::system("command -v ccx > /dev/null 2>&1") != 0) {
      std::printf("calculix_compare: ccx not found (apt-get install calculix-ccx); nothing to "
                  "compare\n");
      return 0;
    }

    fs::path dir = options.keep;
    const bool temporary = dir.empty();
    if (temporary) dir = fs::temp_directory_path() / fmt::format("kinetofem_ccx_{}", ::getpid());
    fs::create_directories(dir);

    const char* omp = std::getenv("OMP_NUM_THREADS");
    const char* blas = std::getenv("OPENBLAS_NUM_THREADS");
    std::printf("# calculix_compare: cantilever 8:1:1, clamped, end traction; %d cores online; "
                "kinetofem OMP_NUM_THREADS=%s OPENBLAS_NUM_THREADS=%s; ccx OMP_NUM_THREADS=%d; "
                "load average at start %s; work folder %s\n",
                int(sysconf(_SC_NPROCESSORS_ONLN)), omp ? omp : "(unset)", blas ? blas : "(unset)",
                options.threads, load_average().c_str(), dir.c_str());
    std::printf("%-6s %8s %-7s %5s %9s %9s %9s %7s %7s %6s %-4s %9s %8s %8s %9s %9s  %s  %s\n", "type",
                "DoFs", "run", "cases", "kf_s", "kf+vm_s", "ccx_s", "ratio", "ratioVM", "target", "", "du/umax",
                "dvm_all", "dvm_away", "vmKF_MPa", "vmCCX_MPa", "load avg before / after",
                "notes");
    int failures = 0;
    for (long long target : options.sizes)
      for (ElementType type : options.types) {
        try {
          compare(type, target, options, dir);
        } catch (const Error& error) {
          ++failures;
          std::printf("%-6s ~%lld DoFs: failed: %s\n", fem::name_of(type), target, error.what());
          std::fflush(stdout);
        }
      }
    std::printf("# load average at the end %s\n", load_average().c_str());
    if (temporary) fs::remove_all(dir);
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "calculix_compare: %s\n", error.what());
    return 1;
  }
}
