#pragma once
// TMPDIR pointed at a folder for a test's lifetime (restored, or unset, at its
// end): where the program under test, or a child it starts, makes its
// temporary files, so a test can check that none is left.
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

namespace kinetofem::testing {

class ScopedTmpdir {
 public:
  explicit ScopedTmpdir(const std::filesystem::path& dir) {
    if (const char* old = std::getenv("TMPDIR")) old_ = old;
    ::setenv("TMPDIR", dir.c_str(), 1);
  }
  ~ScopedTmpdir() {
    if (old_)
      ::setenv("TMPDIR", old_->c_str(), 1);
    else
      ::unsetenv("TMPDIR");
  }
  ScopedTmpdir(const ScopedTmpdir&) = delete;
  ScopedTmpdir& operator=(const ScopedTmpdir&) = delete;

 private:
  std::optional<std::string> old_;
};

}  // namespace kinetofem::testing
