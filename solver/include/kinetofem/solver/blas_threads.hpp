#pragma once
// BlasThreadLimit — the number of threads the BLAS library (OpenBLAS) uses,
// limited for the lifetime of the object and restored after it.
//
// Why: CHOLMOD's supernodal factorization runs its dense work in BLAS. Two
// independent factorizations side by side, each on one BLAS thread, keep both
// cores busy better than one after the other on two BLAS threads (about 1.4x
// for two threads on one factorization). OpenBLAS's thread count is one
// setting of the whole process, so the limit is set once by the thread that
// starts the concurrent work, around all of it.
//
// With a BLAS that is not OpenBLAS the object does nothing (available() is
// false): the symbols are looked up weakly, not required at link time.
//
// Usage:
//   {
//     fem::BlasThreadLimit one_each(1);
//     ... run the factorizations on their own std::threads ...
//   }  // the previous thread count is back
namespace kinetofem::fem {

class BlasThreadLimit {
 public:
  explicit BlasThreadLimit(int threads);
  ~BlasThreadLimit();
  BlasThreadLimit(const BlasThreadLimit&) = delete;
  BlasThreadLimit& operator=(const BlasThreadLimit&) = delete;

  static bool available();  // the BLAS lets its thread count be set
  static int threads();     // the BLAS's thread count now (1 when not available)

 private:
  int previous_ = 0;
};

}  // namespace kinetofem::fem
