#include "kinetofem/solver/blas_threads.hpp"

#include <dlfcn.h>

namespace kinetofem::fem {

namespace {

// OpenBLAS's own entry points, looked up among the loaded libraries at run
// time: present with OpenBLAS, absent with any other BLAS (the reference BLAS
// has no threads to limit). Not declared weak: a weak reference the static
// linker cannot see defined may be bound to null for good.
using SetThreads = void (*)(int);
using GetThreads = int (*)();

SetThreads set_threads() { return reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads")); }
GetThreads get_threads() { return reinterpret_cast<GetThreads>(dlsym(RTLD_DEFAULT, "openblas_get_num_threads")); }

}  // namespace

bool BlasThreadLimit::available() { return set_threads() != nullptr && get_threads() != nullptr; }

int BlasThreadLimit::threads() { return available() ? get_threads()() : 1; }

BlasThreadLimit::BlasThreadLimit(int threads) {
  if (!available()) return;
  previous_ = get_threads()();
  set_threads()(threads < 1 ? 1 : threads);
}

BlasThreadLimit::~BlasThreadLimit() {
  if (previous_ > 0) set_threads()(previous_);
}

}  // namespace kinetofem::fem
