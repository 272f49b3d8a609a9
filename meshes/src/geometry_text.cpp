#include "kinetofem/meshes/geometry_text.hpp"

#include <filesystem>
#include <fstream>
#include <string>

#include "kinetofem/core/error.hpp"
#include "temporary_directory.hpp"

namespace kinetofem::meshes {
namespace {

std::string replace_all(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size()))
    text.replace(at, from.size(), to);
  return text;
}

}  // namespace

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
  try {
    return mesh_geometry(file, options, parameters);
  } catch (const Error& error) {
    // The temporary copy is an implementation detail: a message names the
    // built-in geometry the user chose, never a path under $TMPDIR.
    throw Error(replace_all(error.what(), file.string(), "built-in geometry " + name.string()));
  }
}

}  // namespace kinetofem::meshes
