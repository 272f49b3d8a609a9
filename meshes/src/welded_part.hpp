#pragma once
// Internal: a part welded from several solids (part_file.hpp, PartSolid).
//
// load_welded_part builds Gmsh's model of the part: it imports the part file
// and every solid file into one OpenCASCADE model, in the model's unit, names
// each solid, fragments them together with the weld tolerance as
// OpenCASCADE's fuzzy value (Geometry.ToleranceBoolean) and checks the result
// (no overlap thicker than the tolerance, every solid connected to the others
// through shared faces). It adds the physical volumes "body" (all) and
// "solid.<name>" (each solid's pieces). A part file of one solid with no
// PartSolid is imported exactly as a one-solid part always was: "body" only,
// no fragment.
//
// add_weld_sets adds to a meshed part the face and node sets
// "weld.<a>.<b>" of every seam, from its "solid.*" element sets.
#include <filesystem>
#include <string>
#include <vector>

#include "kinetofem/meshes/gmsh_session.hpp"
#include "kinetofem/meshes/part_file.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes::detail {

struct WeldedPartJob {
  std::filesystem::path part_file;  // empty: the part is the union of the solids' files
  std::vector<PartSolid> solids;
  // Metres per unit of Gmsh's model (mesh_geometry's GeometryJob::model_unit_m).
  double model_unit_m = 1.0;
  // Metres per unit of a .brep file (the part's length unit); 0 when none is given.
  double brep_unit_m = 0.0;
  double tolerance_m = kDefaultWeldToleranceM;
  // The mesh size of the surface meshes that measure a gap (error path only), m.
  double element_size_m = 0.01;
};

void load_welded_part(GmshSession& session, const std::string& context, const WeldedPartJob& job);

void add_weld_sets(fem::Mesh& mesh);

// Makes each node set "solid.<name>" the nodes of the solid's elements: Gmsh
// 4.8's nodes of a fragmented volume with its boundary (getNodes with
// includeBoundary) can hold every node of the model, and a .msh file (the
// mesh cache) holds a set's node list only as its elements' nodes.
void fix_solid_node_sets(fem::Mesh& mesh);

}  // namespace kinetofem::meshes::detail
