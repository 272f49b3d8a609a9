#pragma once
// Internal: the one code path that meshes a geometry file, shared by
// mesh_geometry (mesh_geometry.hpp) and mesh_part_file (part_file.hpp).
#include <filesystem>
#include <functional>
#include <string>

#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes::detail {

struct GeometryJob {
  // ONELAB parameters, .geo files only.
  GeometryParameters parameters;
  // Metres per unit of Gmsh's model once the file is loaded: 1 for STEP/IGES
  // (imported in metres, Geometry.OCCTargetUnit = "M") and for files in
  // metres; 1e-3 for a .geo/.brep drawn in mm. Meshing uses
  // element_size_m / model_unit_m (the model's own unit) and the nodes are
  // multiplied by model_unit_m afterwards, so the mesh is in metres.
  double model_unit_m = 1.0;
  // Loads the model in place of importing `file` (CAD files only): e.g.
  // several files fragmented into one welded part. Unset: `file` is imported
  // (a .geo opened) and its volumes are the physical group "body".
  std::function<void(GmshSession& session, const std::string& context)> load_model;
  // Called with the loaded model (after the volume check, before meshing):
  // e.g. adds physical groups. `context` is the file name for messages.
  std::function<void(GmshSession& session, const std::string& context)> before_meshing;
  // Called with the mesh in metres as it comes back from the child process,
  // before it is cached: e.g. corrects sets.
  std::function<void(fem::Mesh& mesh)> after_meshing;
  // Appended to the mesh cache key: everything of the job that changes the
  // mesh beyond the file, the parameters and the options. Empty for
  // mesh_geometry (its cache keys are those of earlier versions).
  std::string cache_key_extra;
};

// Checks the options, then meshes `file` (.geo, .step/.stp, .iges/.igs,
// .brep) as mesh_geometry documents, through the cache of
// options.cache_dir when set.
fem::Mesh mesh_geometry_file(const std::filesystem::path& file, const MeshOptions& options,
                             const GeometryJob& job);

// The file's extension in lower case (".step").
std::string lower_extension(const std::filesystem::path& file);

}  // namespace kinetofem::meshes::detail
