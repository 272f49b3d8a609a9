// return_freed_memory_to_the_system (core/process_memory.hpp): a freed large
// block leaves the resident memory again after the allocator policy that
// libsuperlu_dist leaves behind (M_MMAP_MAX 0, M_TRIM_THRESHOLD -1).
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <memory>
#include <string>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "kinetofem/core/process_memory.hpp"

namespace kinetofem {
namespace {

double resident_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;  // kB
  return -1.0;
}

// Resident memory given back by freeing a touched block of `bytes`.
double returned_by_free(std::size_t bytes) {
  auto block = std::make_unique<char[]>(bytes);
  std::memset(block.get(), 1, bytes);
  const double with = resident_bytes();
  block.reset();
  return with - resident_bytes();
}

TEST(ProcessMemory, AFreedLargeBlockLeavesTheResidentMemory) {
#if !defined(__GLIBC__)
  GTEST_SKIP() << "glibc's allocator only";
#else
  ASSERT_GT(resident_bytes(), 0.0) << "no /proc/self/status";
  constexpr std::size_t kBlock = std::size_t(256) << 20;
  // What libsuperlu_dist does when it is loaded: the block stays resident.
  // A sanitizer's allocator replaces glibc's and refuses mallopt (returns 0).
  if (mallopt(M_MMAP_MAX, 0) != 1) GTEST_SKIP() << "the allocator is not glibc's (a sanitizer's?)";
  ASSERT_EQ(mallopt(M_TRIM_THRESHOLD, -1), 1);
  EXPECT_LT(returned_by_free(kBlock), 0.5 * double(kBlock));
  ASSERT_TRUE(return_freed_memory_to_the_system());
  // Reference: the block's own size; most of it (page rounding aside) goes back.
  EXPECT_GT(returned_by_free(kBlock), 0.9 * double(kBlock));
#endif
}

}  // namespace
}  // namespace kinetofem

namespace kinetofem {
namespace {

// memory_available_to_process: an address-space limit (ulimit -v) bounds the
// memory left, less what is already mapped, and says so.
TEST(ProcessMemory, AnAddressSpaceLimitBoundsTheMemoryLeft) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "sanitizers need the address space";
#endif
  const pid_t pid = ::fork();
  if (pid == 0) {
    // In a child: the limit cannot be raised again.
    const MemoryBudget before = memory_available_to_process();
    std::ifstream status("/proc/self/status");
    std::string line;
    double mapped = 0.0;
    while (std::getline(status, line))
      if (line.rfind("VmSize:", 0) == 0) mapped = std::stod(line.substr(7)) * 1024.0;
    const rlimit limit{rlim_t(mapped + 300e6), rlim_t(mapped + 300e6)};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(2);
    const MemoryBudget after = memory_available_to_process();
    const bool ok = after.bytes <= 300e6 && after.bytes > 250e6 && after.bytes <= before.bytes &&
                    after.limited_by.find("RLIMIT_AS") != std::string::npos;
    ::_exit(ok ? 0 : 1);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace kinetofem
