// Faults: a run under an address-space limit (RLIMIT_AS, `ulimit -v 450000`)
// too small for the BLAS threads' buffers and the factor must end, within a
// time limit, with a one-line error that names the limit and the need (or
// finish on the iterative solver), never hang in the BLAS library's retries,
// die of a signal or print a raw std::bad_alloc.
// Reference: factor_memory_limit_bytes (solver/cholmod_solver.hpp) and
// memory_available_to_process (core/process_memory.hpp).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "run_program.hpp"

namespace fs = std::filesystem;
using kinetofem::test::Program;
using kinetofem::test::ProgramResult;

namespace {

// The program under test is built like this test. The sanitizers' shadow
// memory needs terabytes of address space, so an instrumented program cannot
// start under the limit ("ReserveShadowMemoryRange failed"). GCC defines
// __SANITIZE_ADDRESS__; clang (the sanitizer tree's compiler) answers only
// __has_feature.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

const fs::path kFaults = fs::path(ROBUSTNESS_DATA_DIR) / "faults";
// Enough to start the program with two BLAS threads (about 0.36 GB mapped), too
// little for their level-3 buffers (64 MiB each) on top.
constexpr long long kLimitBytes = 450000LL * 1024;

ProgramResult run_limited(const std::vector<std::string>& extra, const std::string& case_file, const fs::path& temp) {
  ::setenv("OPENBLAS_NUM_THREADS", "2", 1);  // the start-up's memory must not depend on the machine's cores
  ::setenv("OMP_NUM_THREADS", "2", 1);
  std::vector<std::string> args = {KINETOFEM_EXE, "run", (kFaults / case_file).string(), "-o",
                                   (temp / "out").string()};
  args.insert(args.end(), extra.begin(), extra.end());
  Program program(args, {.working_dir = kFaults, .capture_dir = temp, .address_space_limit_bytes = kLimitBytes});
  return program.wait(120.0);
}

TEST(MemoryLimit, DirectSolverUnderAnAddressSpaceLimitIsAnErrorNamingIt) {
  if (kSanitized) GTEST_SKIP() << "sanitizers need the address space";
  const fs::path temp = kinetofem::test::fresh_temp_dir("rlimit-as-direct");
  const auto r = run_limited({"--set", "solver.method=direct"}, "fe_static.toml", temp);
  ASSERT_FALSE(r.timed_out) << "hung under RLIMIT_AS: " << r.describe();
  EXPECT_TRUE(r.exited && r.exit_code == 1) << r.describe();
  EXPECT_NE(r.err.find("kinetofem: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Cholesky factor"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("RLIMIT_AS"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(temp / "out" / "r.h5"));
  if (!HasFailure()) fs::remove_all(temp);
}

TEST(MemoryLimit, MotionRunUnderAnAddressSpaceLimitEndsWithAClearErrorOrFinishes) {
  if (kSanitized) GTEST_SKIP() << "sanitizers need the address space";
  const fs::path temp = kinetofem::test::fresh_temp_dir("rlimit-as-motion");
  const auto r = run_limited({}, "manipulator.toml", temp);
  ASSERT_FALSE(r.timed_out) << "hung under RLIMIT_AS: " << r.describe();
  ASSERT_TRUE(r.exited) << r.describe();
  if (r.exit_code != 0) {
    EXPECT_EQ(r.exit_code, 1) << r.describe();
    EXPECT_NE(r.err.find("kinetofem: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("RLIMIT_AS"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("bad_alloc"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(temp / "out" / "r.h5"));
  }
  if (!HasFailure()) fs::remove_all(temp);
}

}  // namespace
