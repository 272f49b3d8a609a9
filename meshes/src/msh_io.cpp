#include "kinetofem/meshes/msh_io.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>

#include <gmsh.h>

#include "gmsh_model.hpp"
#include "msh_structure.hpp"
#include "kinetofem/core/error.hpp"
#include "kinetofem/solver/assembly.hpp"

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

// Gmsh 4.8 crashes (a null dereference in GModel::setPhysicalName, found by
// fuzz/fuzz_read_msh) on a $PhysicalNames entry whose dimension is not 0..3,
// so check that section, which comes first after $MeshFormat and is text
// even in binary files, before Gmsh reads the file.
void check_physical_names(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string line;
  auto next = [&] {
    const bool ok = bool(std::getline(in, line));
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return ok;
  };
  while (next() && line != "$EndMeshFormat") {
  }
  if (!next() || line != "$PhysicalNames") return;
  long count = -1;
  require(next() && std::sscanf(line.c_str(), "%ld", &count) == 1 && count >= 0,
          "{}: $PhysicalNames: expected the number of names, got '{}'", file.string(), line);
  for (long k = 0; k < count; ++k) {
    int dim = -1, tag = 0, consumed = 0;
    require(next() && std::sscanf(line.c_str(), "%d %d %n", &dim, &tag, &consumed) == 2,
            "{}: $PhysicalNames: entry {} of {} is not 'dimension tag \"name\"': '{}'",
            file.string(), k + 1, count, line);
    require(dim >= 0 && dim <= 3, "{}: $PhysicalNames: physical group '{}' has dimension {} (must be 0 to 3)",
            file.string(), line, dim);
    require(tag > 0, "{}: $PhysicalNames: physical group '{}' has tag {} (must be positive)", file.string(),
            line, tag);
  }
  require(next() && line == "$EndPhysicalNames",
          "{}: $PhysicalNames: {} names announced, then '{}' instead of $EndPhysicalNames", file.string(),
          count, line);
}

}  // namespace

fem::Mesh read_msh(const std::filesystem::path& file) {
  check_msh_file(file);
  check_physical_names(file);
  detail::check_msh41_structure(file);
  const std::string context = file.string();
  GmshSession session;
  session.call(context, "gmsh::open", [&] { gmsh::open(context); });
  auto mesh = detail::mesh_from_model(session, context);
  // A hand-made or exported file may hold non-finite coordinates or inverted
  // elements: reject them here, naming the file, rather than later in the
  // analysis where the message could not say where the mesh came from.
  try {
    mesh.validate();
    fem::check_element_jacobians(mesh);
  } catch (const Error& e) {
    fail("{}: {}", context, e.what());
  }
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
