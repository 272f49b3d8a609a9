#include "kinetofem/meshes/geometry_text.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include "kinetofem/core/error.hpp"
#include "temporary_directory.hpp"

namespace kinetofem::meshes {

fem::Mesh mesh_geometry_text(std::string_view file_name, std::string_view text, const MeshOptions& options,
                             const GeometryParameters& parameters) {
  const std::filesystem::path name(file_name);
  require(!name.empty() && name == name.filename(), "geometry text: '{}' must be a plain file name",
          std::string(file_name));
  detail::TemporaryDirectory directory("kinetofem-geometry");
  const std::filesystem::path file = directory.file(name.string());
  {
    std::ofstream out(file, std::ios::binary);
    out.write(text.data(), std::streamsize(text.size()));
    out.close();
    require(bool(out), "{}: cannot write the geometry text", file.string());
  }
  return mesh_geometry(file, options, parameters);
}

}  // namespace kinetofem::meshes
