#pragma once
// Meshing a geometry file with Gmsh into a fem::Mesh.
//
// Accepted files: Gmsh .geo scripts (any kernel; physical groups as the
// script defines them), and STEP (.step/.stp), IGES (.iges/.igs) and BREP
// (.brep) through OpenCASCADE. STEP and IGES are converted to metres from
// the unit stored in the file; .geo and .brep files carry no unit and are
// taken to be in metres (the files in meshes/geometry are). An imported
// STEP/IGES/BREP shape has no physical groups; mesh_geometry gives all its
// volumes the group "body". Physical groups become node, face and element
// sets as in read_msh (msh_io.hpp).
//
// A .geo script that merges a STEP/IGES file gets it in mm (OpenCASCADE's
// default target unit, set explicitly before each .geo is read, since
// OpenCASCADE keeps the unit of the last import process-wide) unless the
// script sets Geometry.OCCTargetUnit itself.
//
// Mesh options set here override Mesh.* options set in a .geo script.
//
// Parts in other units, with named faces by bounding box: part_file.hpp.
#include <filesystem>
#include <map>
#include <string>

#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

enum class ElementFamily {
  Tetrahedra,  // TET4 / TET10 (Gmsh's Delaunay)
  // Hexahedra by splitting every tetrahedron into four (Gmsh's
  // Mesh.SubdivisionAlgorithm = 2): all-hex HEX8 / HEX20 on any geometry,
  // but of poorer shape than a structured hex mesh. Gmsh's hex-dominant
  // meshes are not offered: they contain prisms and pyramids, which the
  // solver has no elements for.
  Hexahedra,
};

struct MeshOptions {
  double element_size_m = 0.01;  // target (maximum) element edge length, m; > 0
  int order = 2;                 // 1: TET4/HEX8, 2: TET10/HEX20 (mid-nodes on the geometry)
  ElementFamily family = ElementFamily::Tetrahedra;
  // Refine curved surfaces to at least this many elements per full circle
  // (Gmsh's Mesh.MeshSizeFromCurvature); 0 = element_size_m everywhere.
  int elements_per_circle = 16;
  // Improve element shape after meshing (Gmsh's Optimize and, for order 2,
  // the high-order optimizer that untangles curved elements). Costs time.
  bool optimize = true;
  bool verbose = false;  // let Gmsh print its progress
  // Wall-clock limit for reading and meshing one geometry file, s; > 0. Gmsh
  // runs in a child process that is stopped there, an error naming the file
  // (meshing_process.hpp; the case key mesh.time_limit_s). Not part of the
  // mesh cache key: it does not change the mesh.
  double time_limit_s = 600.0;
  // Mesh cache: when set, a mesh is stored there as .msh (binary) under a
  // content hash of the geometry file's text, the parameters and these
  // options, and read back instead of meshing again. Empty: no cache.
  std::filesystem::path cache_dir;

  void validate() const;  // throws Error naming the bad option
};

// The number of volume elements Gmsh makes for `volume_m3` at
// options.element_size_m, roughly (6 tetrahedra per element size cubed, 4
// hexahedra per tetrahedron). mesh_geometry refuses a geometry whose estimate
// exceeds kMaxEstimatedElements before meshing: such a mesh would not fit in
// memory or keep Gmsh busy for hours.
double estimated_element_count(double volume_m3, const MeshOptions& options);
inline constexpr double kMaxEstimatedElements = 5e6;

// ONELAB parameters ("Group/name" -> value) set before a .geo file is read:
// they override the file's DefineConstant[] defaults of the same name. Gmsh
// ignores names the file does not define.
using GeometryParameters = std::map<std::string, double>;

// Meshes the geometry in `file`; throws Error naming the file if it is
// missing, cannot be read or meshed, or the mesh has no volume elements.
// Gmsh reads and meshes the file in a child process (a crash, an exit from
// inside Gmsh, or options.time_limit_s passing is an Error naming the file).
fem::Mesh mesh_geometry(const std::filesystem::path& file, const MeshOptions& options,
                        const GeometryParameters& parameters = {});

}  // namespace kinetofem::meshes
