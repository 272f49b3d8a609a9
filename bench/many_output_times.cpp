// many_output_times: the cost of a link's stress history against its number
// of output times, on one mesh.
//
//   ./build/bench/many_output_times              # n = 8 (HEX20 box 64 x 8 x 8 cells), 101 and 10001 times
//   ./build/bench/many_output_times 6 101 2001 10001
//
// Model: a steel box 8 m x 1 m x 1 m, 8n x n x n HEX20 cells, on a 3-2-1
// support, loaded by 24 self-equilibrated patterns (equal and opposite
// forces on two nodes along the line through them, so the support carries
// nothing) whose coefficients are sines of different frequencies over the
// output times. analyse_link_over_motion runs the superposition path (one
// factorization, one block solve of the patterns, then every output time's
// von Mises and displacement envelope); a field is written (the step
// callback) at every 100th time, as a case writes a few frames of a long
// motion. Printed per run: the output times, the total and the part after
// the pattern solves (`recovery_s`), and the ratio of each total to the
// first's. The limit of exact per-node envelopes is the products' flops:
// (6 + 3) N x m x 2 per output time, against the fixed factorization.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "kinetofem/core/log.hpp"
#include "kinetofem/loads/link_stress_history.hpp"
#include "kinetofem/loads/load_patterns.hpp"
#include "kinetofem/solver/rigid_body.hpp"
#include "kinetofem/solver/static_analysis.hpp"
#include "kinetofem/testing/box_mesh.hpp"

namespace {

using namespace kinetofem;

// 24 patterns, each a pair of equal and opposite forces (1 kN) on two nodes
// far apart, along the line joining them: in equilibrium by construction.
loads::PatternLoadHistory history(const fem::Mesh& mesh, int times) {
  loads::PatternLoadHistory h;
  h.part = "box";
  const fem::Index nodes = mesh.node_count();
  const int m = 24;
  h.patterns = Eigen::MatrixXd::Zero(3 * nodes, m);
  for (int k = 0; k < m; ++k) {
    const fem::Index a = (fem::Index(k) * 7919) % nodes, b = (fem::Index(k) * 104729 + nodes / 2) % nodes;
    const Eigen::Vector3d d = (mesh.nodes.row(a) - mesh.nodes.row(b)).transpose().normalized() * 1e3;
    h.patterns.block<3, 1>(3 * a, k) += d;
    h.patterns.block<3, 1>(3 * b, k) -= d;
    h.names.push_back("pair_" + std::to_string(k));
  }
  h.coefficients.resize(m, times);
  for (int t = 0; t < times; ++t) {
    const double s = double(t) / double(std::max(times - 1, 1));
    h.times.push_back(s);
    for (int k = 0; k < m; ++k) h.coefficients(k, t) = std::sin(2.0 * M_PI * (k + 1) * s + 0.3 * k);
  }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    int n = 8;
    std::vector<int> counts;
    if (argc > 1) n = std::atoi(argv[1]);
    for (int i = 2; i < argc; ++i) counts.push_back(std::atoi(argv[i]));
    if (counts.empty()) counts = {101, 10001};

    fem::FeModel model;
    {
      testing::BoxMeshOptions options;
      options.length_m = {8.0, 1.0, 1.0};
      options.divisions = {8 * n, n, n};
      options.type = fem::ElementType::Hex20;
      model.mesh = testing::box_mesh(options);
    }
    std::vector<fem::Index> all(size_t(model.mesh.node_count()));
    for (fem::Index i = 0; i < model.mesh.node_count(); ++i) all[size_t(i)] = i;
    model.supports = fem::three_two_one_support(model.mesh, all);
    const Log log = Log::quiet();
    std::printf("# many_output_times: HEX20 box %dx%dx%d cells, %ld nodes, 24 patterns, a field written "
                "every 100th time\n",
                8 * n, n, n, long(model.mesh.node_count()));
    std::printf("%8s %10s %12s %8s %12s\n", "times", "total_s", "recovery_s", "ratio", "peak_vm_MPa");
    double first_total = 0.0;
    for (const int times : counts) {
      const loads::PatternLoadHistory h = history(model.mesh, times);
      loads::LinkStressOptions options;
      options.callback_steps.assign(size_t(times), false);
      for (int t = 0; t < times; t += 100) options.callback_steps[size_t(t)] = true;
      long written = 0;
      Stopwatch clock;
      // A fresh analysis per run: each total includes its own assembly and factorization.
      fem::LinearStaticAnalysis analysis(model, log);
      const loads::LinkEnvelope env = loads::analyse_link_over_motion(
          analysis, h, log, options,
          [&](std::size_t, const fem::DisplacementField&, const fem::NodalStress&) { ++written; });
      const double total = clock.seconds();
      if (first_total == 0.0) first_total = total;
      std::printf("%8d %10.3f %12.3f %8.2f %12.4f\n", times, total, env.recovery_seconds, total / first_total,
                  env.peak_von_mises_pa / 1e6);
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "many_output_times: %s\n", e.what());
    return 1;
  }
}
