#pragma once
// Geometry texts compiled into the program, and meshing a geometry given as
// text. The program needs no source tree at run time: the .geo files of
// meshes/geometry are embedded at build time (cmake/KinetofemEmbed.cmake,
// regenerated when a file changes), and Gmsh, which opens only files, gets a
// temporary copy.
#include <string_view>

#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

// The text of meshes/geometry/lever.geo (lever.hpp) and arm.geo (arm.hpp).
std::string_view lever_geometry_text();
std::string_view arm_geometry_text();

// Meshes a geometry given as text, as mesh_geometry meshes a file named
// `file_name` ("lever.geo": its extension chooses the reader). The text is
// written to `file_name` in a fresh directory under
// std::filesystem::temp_directory_path() (unique per call, so concurrent
// calls and processes do not meet), meshed, and the directory removed again,
// also when meshing throws and when the program is ended by SIGINT, SIGTERM
// or SIGHUP (core/termination_cleanup.hpp). The mesh cache key (MeshOptions::cache_dir) is
// the file name's stem and a hash of the text, so it is that of the file
// itself; messages name "built-in geometry <file_name>", never the
// temporary path.
fem::Mesh mesh_geometry_text(std::string_view file_name, std::string_view text,
                             const MeshOptions& options, const GeometryParameters& parameters = {});

}  // namespace kinetofem::meshes
