// The replaceable global allocation functions of the fuzz targets, so that a
// failed allocation throws std::bad_alloc as in a normal build. AddressSanitizer's
// own operator new aborts instead (compiler-rt 14, asan_new_delete.cpp:
// ReportOutOfMemory, whatever allocator_may_return_null says), and a corrupt
// binary .msh makes Gmsh ask for ~2e18 bytes: in the program that is
// `cube.msh: gmsh::open failed: std::bad_alloc`, a proper error, which the fuzz
// target must see too. These forward to malloc/free, which ASan still checks
// (fuzz.sh sets allocator_may_return_null=1, so malloc returns null).
#include <algorithm>
#include <cstdlib>
#include <new>

namespace {

void* allocate(std::size_t size) noexcept { return std::malloc(size ? size : 1); }

void* allocate_aligned(std::size_t size, std::align_val_t alignment) noexcept {
  void* p = nullptr;
  const std::size_t a = std::max(std::size_t(alignment), sizeof(void*));
  return posix_memalign(&p, a, size ? size : 1) == 0 ? p : nullptr;
}

void* or_throw(void* p) {
  if (!p) throw std::bad_alloc();
  return p;
}

}  // namespace

void* operator new(std::size_t n) { return or_throw(allocate(n)); }
void* operator new[](std::size_t n) { return or_throw(allocate(n)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return allocate(n); }
void* operator new(std::size_t n, std::align_val_t a) { return or_throw(allocate_aligned(n, a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return or_throw(allocate_aligned(n, a)); }
void* operator new(std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate_aligned(n, a); }
void* operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t&) noexcept { return allocate_aligned(n, a); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { std::free(p); }
