#pragma once
// One checked entry point for every SUNDIALS call: a negative return flag (or a
// null pointer from a constructor) throws kinetofem::Error naming the function,
// the flag by its name with its plain meaning and what a user can change
// (sundials_flag_text), and the context (e.g. the time reached).
#include <string>

#include "kinetofem/core/error.hpp"

namespace kinetofem::mech {

// A negative flag of an IDA* or CVode* function (the package is told by the
// function's name) in words: "the corrector did not converge, ...
// (IDA_CONV_FAIL)"; the name alone where no plain meaning is known; "flag N"
// for any other function.
std::string sundials_flag_text(const char* function, int flag);
// What a user can change about that failure ("what can be changed: ..."), or "".
std::string sundials_flag_advice(const char* function, int flag);

inline int sundials_check(int flag, const char* function, const std::string& context = {}) {
  if (flag < 0) {
    const std::string advice = sundials_flag_advice(function, flag);
    fail("SUNDIALS {}: {}{}{}{}{}", function, sundials_flag_text(function, flag), context.empty() ? "" : " at ",
         context, advice.empty() ? "" : "; ", advice);
  }
  return flag;
}

template <typename T>
T* sundials_check_ptr(T* pointer, const char* function) {
  if (pointer == nullptr) fail("SUNDIALS {} returned null (out of memory?)", function);
  return pointer;
}

}  // namespace kinetofem::mech
