#include "kinetofem/meshes/msh_io.hpp"

#include <algorithm>
#include <fstream>

#include <gmsh.h>

#include "gmsh_model.hpp"
#include "kinetofem/core/error.hpp"

namespace kinetofem::meshes {

namespace {

// Gmsh 4.8 accepts a missing or empty file silently and reads a file cut
// after its last complete section without complaint, so check the ends of
// the file first: it must start with "$MeshFormat" and its last line must
// close a section ("$End...").
void check_msh_file(const std::filesystem::path& file) {
  std::error_code error;
  require(std::filesystem::is_regular_file(file, error), "{}: no such mesh file", file.string());
  const auto size = std::filesystem::file_size(file, error);
  require(!error, "{}: cannot read the file size ({})", file.string(), error.message());
  require(size > 0, "{}: the mesh file is empty", file.string());
  std::ifstream in(file, std::ios::binary);
  require(bool(in), "{}: cannot open the mesh file", file.string());
  std::string head(11, '\0');
  in.read(head.data(), std::streamsize(head.size()));
  require(in && head == "$MeshFormat",
          "{}: not a Gmsh .msh file (it does not start with $MeshFormat)", file.string());
  const std::uintmax_t tail_size = std::min<std::uintmax_t>(size, 256);
  std::string tail(tail_size, '\0');
  in.seekg(std::streamoff(size - tail_size));
  in.read(tail.data(), std::streamsize(tail_size));
  require(bool(in), "{}: cannot read the end of the mesh file", file.string());
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back()))) tail.pop_back();
  const auto line_start = tail.find_last_of("\r\n");
  const std::string last_line = tail.substr(line_start == std::string::npos ? 0 : line_start + 1);
  require(last_line.rfind("$End", 0) == 0,
          "{}: the mesh file is truncated (its last line is not a closing $End... section "
          "marker)",
          file.string());
}

}  // namespace

fem::Mesh read_msh(const std::filesystem::path& file) {
  check_msh_file(file);
  const std::string context = file.string();
  GmshSession session;
  session.call(context, "gmsh::open", [&] { gmsh::open(context); });
  auto mesh = detail::mesh_from_model(session, context);
  mesh.validate();
  return mesh;
}

void write_msh(const fem::Mesh& mesh, const std::filesystem::path& file, MshEncoding encoding) {
  const std::string context = file.string();
  require(file.extension() == ".msh", "{}: write_msh writes .msh files only", context);
  GmshSession session;
  detail::model_from_mesh(session, mesh, context);
  session.call(context, "gmsh::write", [&] {
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", encoding == MshEncoding::Binary ? 1 : 0);
    // All elements, not only those of physical groups (the default when
    // groups exist), so that volume elements outside every set survive.
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::write(context);
  });
  // Gmsh logs but does not throw when it cannot open the output file.
  require(std::filesystem::is_regular_file(file), "{}: the mesh file was not written", context);
}

}  // namespace kinetofem::meshes
