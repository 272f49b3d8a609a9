#include "temporary_directory.hpp"

#include <stdlib.h>

#include <cerrno>
#include <cstring>
#include <system_error>

#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes::detail {

TemporaryDirectory::TemporaryDirectory(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  require(::mkdtemp(pattern.data()) != nullptr, "cannot create a temporary folder {}: {}", pattern,
          std::strerror(errno));
  path_ = pattern;
  try {
    registered_.emplace_back(path_);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(path_, ignored);
    throw;
  }
}

TemporaryDirectory::~TemporaryDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::filesystem::path TemporaryDirectory::file(const std::string& name) {
  const std::filesystem::path file = path_ / name;
  registered_.emplace_back(file);
  return file;
}

}  // namespace kinetofem::meshes::detail
