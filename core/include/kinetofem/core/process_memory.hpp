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

namespace kinetofem {

// Large blocks (from kLargeAllocationBytes, glibc's own steady-state
// threshold) are mapped on their own again and unmapped when freed; the heap
// is trimmed above twice that. A no-op where the C library is not glibc.
// Returns false when the C library refused a setting.
inline constexpr std::size_t kLargeAllocationBytes = std::size_t(32) << 20;  // 32 MiB
bool return_freed_memory_to_the_system();

}  // namespace kinetofem
