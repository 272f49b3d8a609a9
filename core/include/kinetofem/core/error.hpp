#pragma once
// kinetofem::Error — the one exception type of the toolkit.
//
// Every failure (bad input, a library call that failed, a singular system, a
// mechanism that cannot be assembled) is thrown as an Error whose message is a
// single line naming the file / key / value / element / time concerned and what
// is wrong. The CLI catches it once, prints it and exits non-zero.
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace kinetofem {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

// Throws Error with a fmt-formatted message.
template <typename... Args>
[[noreturn]] void fail(fmt::format_string<Args...> format, Args&&... args) {
  throw Error(fmt::format(format, std::forward<Args>(args)...));
}

// Throws Error unless condition holds.
template <typename... Args>
void require(bool condition, fmt::format_string<Args...> format, Args&&... args) {
  if (!condition) throw Error(fmt::format(format, std::forward<Args>(args)...));
}

}  // namespace kinetofem
