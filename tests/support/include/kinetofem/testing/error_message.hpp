#pragma once
// The message of the kinetofem::Error a call throws, for tests that check
// what a user would read; a test failure (and "") when it throws none.
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "kinetofem/core/error.hpp"

namespace kinetofem::testing {

inline std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const Error& error) {
    return error.what();
  }
  ADD_FAILURE() << "no Error thrown";
  return {};
}

}  // namespace kinetofem::testing
