#pragma once
// The C library's allocator policy for this process, set once at a
// program's entry (main), like its signal handlers.
//
// Why: libsuperlu_dist (a dependency of hypre, which the iterative solver
// links) sets glibc's M_MMAP_MAX to 0 and M_TRIM_THRESHOLD to -1 as soon as
// it is loaded. Every allocation then comes from the heap and freed memory
// is never returned to the system: a Cholesky factor freed after its last
// solve (fem::LinearStaticAnalysis::release_factor) stays in the resident
// memory, and the parts of a large model that are factorized one at a time
// add up as if they were all kept.
#include <cstddef>
#include <string>

namespace kinetofem {

// Large blocks (from kLargeAllocationBytes, glibc's own steady-state
// threshold) are mapped on their own again and unmapped when freed; the heap
// is trimmed above twice that. A no-op where the C library is not glibc.
// Returns false when the C library refused a setting.
inline constexpr std::size_t kLargeAllocationBytes = std::size_t(32) << 20;  // 32 MiB
bool return_freed_memory_to_the_system();

// The memory this process may still take, bytes, and what bounds it: the
// least of the physical memory ("physical memory"), the address-space limit
// (RLIMIT_AS, `ulimit -v`) less the address space already mapped, and the
// memory limit of the process's cgroup (v2 memory.max, v1
// memory.limit_in_bytes) less the cgroup's current use. An allocation past
// such a limit is refused (or the process killed), so a memory budget (the
// Cholesky factor's) must stay below it.
struct MemoryBudget {
  double bytes = 0.0;
  std::string limited_by;  // e.g. "the address-space limit (RLIMIT_AS, ulimit -v) of 0.461 GB, 0.312 GB in use"
};
MemoryBudget memory_available_to_process();

}  // namespace kinetofem
