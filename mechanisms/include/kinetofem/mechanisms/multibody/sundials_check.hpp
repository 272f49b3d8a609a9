#pragma once
// One checked entry point for every SUNDIALS call: a negative return flag (or a
// null pointer from a constructor) throws kinetofem::Error naming the function,
// the flag and the context (e.g. the time reached).
#include <string>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

inline int sundials_check(int flag, const char* function, const std::string& context = {}) {
  if (flag < 0)
    fail("SUNDIALS {} failed with flag {}{}{}", function, flag, context.empty() ? "" : ": ", context);
  return flag;
}

template <typename T>
T* sundials_check_ptr(T* pointer, const char* function) {
  if (pointer == nullptr) fail("SUNDIALS {} returned null (out of memory?)", function);
  return pointer;
}

}  // namespace kinetofem::mech
