#include "kinetofem/meshes/geometry_text.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes {

namespace {

// A fresh directory (mkdtemp) removed with everything in it on destruction.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (std::filesystem::temp_directory_path() / "kinetofem-geometry-XXXXXX").string();
    require(::mkdtemp(pattern.data()) != nullptr, "cannot create a temporary directory {}: {}", pattern,
            std::strerror(errno));
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TemporaryDirectory(const TemporaryDirectory&) = delete;
  TemporaryDirectory& operator=(const TemporaryDirectory&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace

fem::Mesh mesh_geometry_text(std::string_view file_name, std::string_view text, const MeshOptions& options,
                             const GeometryParameters& parameters) {
  const std::filesystem::path name(file_name);
  require(!name.empty() && name == name.filename(), "geometry text: '{}' must be a plain file name",
          std::string(file_name));
  const TemporaryDirectory directory;
  const std::filesystem::path file = directory.path() / name;
  {
    std::ofstream out(file, std::ios::binary);
    out.write(text.data(), std::streamsize(text.size()));
    out.close();
    require(bool(out), "{}: cannot write the geometry text", file.string());
  }
  return mesh_geometry(file, options, parameters);
}

}  // namespace kinetofem::meshes
