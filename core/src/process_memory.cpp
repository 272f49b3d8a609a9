#include "kinetofem/core/process_memory.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace kinetofem {

bool return_freed_memory_to_the_system() {
#if defined(__GLIBC__)
  // 65536: glibc's default number of mapped blocks.
  return mallopt(M_MMAP_MAX, 65536) == 1 && mallopt(M_MMAP_THRESHOLD, int(kLargeAllocationBytes)) == 1 &&
         mallopt(M_TRIM_THRESHOLD, int(2 * kLargeAllocationBytes)) == 1;
#else
  return true;
#endif
}

}  // namespace kinetofem
