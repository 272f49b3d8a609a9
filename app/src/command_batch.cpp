// `kinetofem batch CASES... --jobs N [-o DIR] [--set KEY=VALUE]`: the
// subcommand and its MPI glue. This file is built into the kinetofem
// executable only (app/CMakeLists.txt), so that the library and the unit
// tests do not depend on MPI.
//
// MPI is initialised only when the program was started by OpenMPI's mpirun
// (OMPI_COMM_WORLD_SIZE in the environment): started alone, the batch runs
// serially without touching MPI (no singleton start-up of an MPI runtime).
#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "kinetofem/app/batch.hpp"
#include "kinetofem/app/commands.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::app {

namespace {

// MPI_COMM_WORLD for the batch; MPI_Init on construction, MPI_Finalize on destruction.
class MpiComm final : public BatchComm {
 public:
  MpiComm() {
    check(MPI_Init(nullptr, nullptr), "MPI_Init");
    check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
    check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
  }
  ~MpiComm() override { MPI_Finalize(); }
  MpiComm(const MpiComm&) = delete;
  MpiComm& operator=(const MpiComm&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }

  std::vector<std::string> gather(const std::string& mine) const override {
    int length = int(mine.size());
    std::vector<int> lengths(rank_ == 0 ? size_ : 0), offsets(lengths.size(), 0);
    check(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Gather");
    std::string all;
    if (rank_ == 0) {
      for (int r = 1; r < size_; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
      all.resize(std::size_t(offsets.back() + lengths.back()));
    }
    check(MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
                      MPI_COMM_WORLD),
          "MPI_Gatherv");
    std::vector<std::string> out;
    for (int r = 0; rank_ == 0 && r < size_; ++r) out.push_back(all.substr(offsets[r], lengths[r]));
    return out;
  }

  // An error on one rank would leave the others waiting in gather(): abort them all.
  [[noreturn]] void abort_all(const std::string& message) const {
    std::fprintf(stderr, "kinetofem: error (rank %d): %s\n", rank_, message.c_str());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
    std::exit(1);
  }

 private:
  static void check(int rc, const char* function) {
    if (rc != MPI_SUCCESS) fail("{} failed (MPI error code {})", function, rc);
  }
  int rank_ = 0, size_ = 1;
};

bool started_by_mpirun() { return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr; }

}  // namespace

void add_batch_command(CLI::App& app, CommandContext& context) {
  auto options = std::make_shared<BatchOptions>();
  auto* batch = app.add_subcommand(
      "batch", "Run many cases and sweeps, each in its own process; skip runs whose results are up to date");
  batch->add_option("cases", options->cases, "Case files (TOML); a case with [sweep] gives one run per point")
      ->required();
  batch->add_option("-j,--jobs", options->jobs,
                    fmt::format("Runs at once (on each MPI rank); at most {} per hardware thread", kJobsPerThread))
      ->capture_default_str()
      ->check(CLI::Validator(
          [](const std::string& text) {
            // CLI11's own range check would print the limit of a double (309 digits).
            std::size_t end = 0;
            long n = 0;
            try {
              n = std::stol(text, &end);
            } catch (const std::exception&) {
              end = 0;
            }
            if (end == text.size() && n >= 1) return std::string();
            return fmt::format("must be a whole number of runs at once, 1 or more, not {}", text);
          },
          "INT >= 1"));
  batch->add_option("-o,--output-dir", options->output_dir, "Directory for results, logs and the summary table")
      ->capture_default_str();
  batch->add_option("--set", options->overrides,
                    "Override a case key in every run: KEY=VALUE, the value in TOML (20, \"hex\", [0, 1, 0]); "
                    "repeatable")
      ->allow_extra_args(false);
  batch->add_flag("--trust-part-files", options->trust_part_files,
                  "Start every run with --trust-part-files: their .geo part files may run programs, exit, write "
                  "files and read outside the case folder (a trust decision; docs/robustness.md)");
  batch->add_flag("--force", options->force, "Rerun every run, also those up to date");
  batch->add_flag("-q,--quiet", options->quiet, "No progress lines and no table on the terminal (the table is still written)");
  batch->add_flag("-v,--verbose", options->verbose,
                  "Start every run with --verbose: its log also holds each solve's statistics");
  batch->callback([options, &context] {
    std::vector<BatchRow> rows;
    if (started_by_mpirun()) {
      const MpiComm comm;
      try {
        rows = run_batch(*options, comm);
      } catch (const std::exception& e) {
        if (comm.size() > 1) comm.abort_all(e.what());
        throw;
      }
    } else {
      rows = run_batch(*options, BatchComm());
    }
    std::size_t failed = 0;
    for (const auto& row : rows) failed += row.status == RunStatus::Failed;
    if (failed > 0) std::fprintf(stderr, "kinetofem: batch: %zu of %zu runs failed\n", failed, rows.size());
    context.exit_code = failed > 0 ? 1 : 0;
  });
}

}  // namespace kinetofem::app
