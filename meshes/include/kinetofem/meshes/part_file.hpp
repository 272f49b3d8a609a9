#pragma once
// Meshing a user's CAD part of a mechanism link: a STEP (.step/.stp), IGES
// (.iges/.igs), BREP (.brep) or Gmsh .geo file, or an existing .msh 4.1
// mesh, in the file's own frame, converted to metres, with named face sets
// for the faces where joints and loads act.
//
// Units. STEP and IGES files record their length unit: they are imported in
// metres (OpenCASCADE converts, Gmsh's Geometry.OCCTargetUnit = "M", as in
// mesh_geometry). .brep, .geo and .msh files carry no unit: length_unit_m is
// required for them (1e-3 for a part drawn in mm). Such a part is meshed in
// its own unit with the element size converted to it, and its nodes are
// multiplied by length_unit_m afterwards (Gmsh's Geometry.OCCScaling would
// scale a .brep on import, but a .geo's own geometry not: one path for all).
// For a STEP/IGES file length_unit_m is optional; given, it must agree with
// the unit the file declares (read from its text, cad_file_length_unit_m).
// A .geo that merges a STEP file gets it in mm (OpenCASCADE's default),
// unless the script sets Geometry.OCCTargetUnit itself.
//
// Frame: the file's own coordinates, in metres; no placement (the caller
// turns and offsets the mesh into the body frame).
//
// Named faces. Physical groups of a .geo or .msh file become sets as in
// read_msh (msh_io.hpp); an imported STEP/IGES/BREP shape gets the element
// and node set "body" (mesh_geometry.hpp). Each FaceSelection adds a
// physical surface of its name made of every surface of the model lying
// entirely inside its box (gmsh::model::getEntitiesInBoundingBox, dimension
// 2, OpenCASCADE's bounding box of each surface, which carries its tolerance
// of about 1e-7 m: make the box a little larger than the face). It becomes a
// face set and a node set of that name, oriented out of the body.
//
// .msh files are read with read_msh (all its checks) and scaled; MeshOptions
// other than their validity do not apply to them. With face selections the
// file is opened once more in Gmsh to find its surfaces in the boxes.
//
// Mesh cache (MeshOptions::cache_dir): for geometry files the key covers the
// file's text, every file a .geo reads (geo_file_scan.hpp), the options, the
// length unit, every selection (name and box), the weld tolerance and every
// PartSolid (name, point, and its file's text). .msh files are not cached.
//
// Face selections take only surfaces on the outside of the part (a seam
// between two welded solids is inside).
//
// Errors (kinetofem::Error, one line naming the file, and the selection for
// a selection): a missing file; an unknown extension (the accepted ones are
// listed); a missing, non-positive or (STEP/IGES) disagreeing length unit;
// a .geo command that reaches outside geometry (PartFileOptions::trusted);
// Gmsh failing to read or mesh the file; a mesh of several separate solids
// (a part is one body: its elements connected through shared nodes); no volumes or no volume elements; a
// selection with an empty name, a name given twice or equal to a physical
// group the file already has ("body" for STEP/IGES/BREP), a box whose corners
// are not finite or with min > max, a box that holds no surface (the message
// gives the box and the part's extent in mm).
//
// Not thread-safe (one Gmsh session per call, gmsh_session.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "kinetofem/meshes/mesh_geometry.hpp"
#include "kinetofem/solver/mesh.hpp"

namespace kinetofem::meshes {

struct FaceSelection {
  std::string name;  // the face set (and node set) to create
  // Corners of the box in the file's own coordinates, converted to metres
  // (for a part drawn in mm: the mm values times 1e-3).
  Eigen::Vector3d box_min_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d box_max_m = Eigen::Vector3d::Zero();
};

// A part welded from several solids (docs/meshes.md, "Welded parts"). The
// solids of a STEP/IGES/BREP part file and of its PartSolid files are
// imported into one OpenCASCADE model and fragmented together
// (gmsh::model::occ::fragment, with Geometry.ToleranceBoolean set to the weld
// tolerance), so solids that touch, or nearly touch within the tolerance,
// share their interface faces and the mesh is conformal: they are welded
// (bonded) along the whole interface.
//
// Each solid keeps its name: the element set "solid.<name>" (solid_set_name).
// Every seam where two solids meet is a face set and a node set
// "weld.<a>.<b>" (weld_set_name, a < b alphabetically): the element faces
// shared by an element of solid a and one of solid b, oriented out of solid a.
// The element and node set "body" is the whole part, as for one solid.
//
// Names: a PartSolid's name; the solids of the part file that no PartSolid
// names are "solid1", "solid2", ... by their position in the file. A part file
// of one solid with no PartSolid is meshed exactly as before (no solid or weld
// sets).
//
// Errors (one line, naming the file and the solids): a solid connected to no
// other through shared faces after the fragment (a gap above the tolerance:
// the two nearest solids of different groups and their gap in mm, measured
// between their surface meshes); two solids overlapping (a fragment piece
// inside both) with a piece thicker than the tolerance (the overlap's volume
// in mm^3 and its thickness, the least extent of its box, in mm); a PartSolid
// with both or (for a part file of several solids) neither of file and
// inside_m, a point in no solid, two PartSolids naming one solid, a name given
// twice or empty; a PartSolid file that is not STEP/IGES/BREP or holds other
// than one solid; solids for a .geo or .msh part file.
struct PartSolid {
  std::string name;  // element set "solid.<name>"; letters, digits, '_' and '-'
  // Its own STEP/IGES/BREP file (a .brep in the part's length unit), or empty:
  // a solid of the part's file.
  std::filesystem::path file;
  // A point inside a solid of the part's file, its own coordinates in metres
  // (for a part drawn in mm: the mm values times 1e-3). Without a file and
  // without this point, the PartSolid names the part file's only solid.
  std::optional<Eigen::Vector3d> inside_m;
};

// Default weld tolerance, m: 0.05 mm, a tenth of a typical CAD gap between
// parts drawn as "touching" by offsetting (0.5 mm and more is a real gap), and
// far above OpenCASCADE's own precision (1e-7 m).
inline constexpr double kDefaultWeldToleranceM = 0.05e-3;

// "solid.<name>" and "weld.<a>.<b>" with a < b (the order of the arguments
// does not matter).
std::string solid_set_name(const std::string& solid);
std::string weld_set_name(const std::string& solid_a, const std::string& solid_b);
inline constexpr const char* kSolidSetPrefix = "solid.";
inline constexpr const char* kWeldSetPrefix = "weld.";

// The solids of a meshed part: their names in alphabetical order (the element
// sets "solid.<name>") and each element's solid as an index into them (-1: in
// none; element order of the blocks). No names: not a welded part.
struct ElementSolids {
  std::vector<std::string> names;
  std::vector<int> of_element;
};
ElementSolids element_solids(const fem::Mesh& mesh);

// Where `node` lies in a welded part, for messages: "solid hub", "solid hub,
// seam weld.hub.plate" (on a seam: the solid first by name); "" for a part of
// one solid.
std::string place_in_welded_part(const fem::Mesh& mesh, fem::Index node);

struct PartFileOptions {
  // Metres per file unit: 1e-3 for mm, 1 for m. Required for .geo, .brep
  // and .msh; for STEP/IGES the file's own unit is used and, if this is
  // given too, checked against it.
  std::optional<double> length_unit_m;
  std::vector<FaceSelection> face_sets;  // extra named face sets by bounding box
  // What a .geo part file (and a "<file>.opt" Gmsh would merge) may do
  // besides geometry, checked before Gmsh reads it (geo_file_scan.hpp): read
  // files inside case_folder or its own folder only, by plain names, and no
  // program runs, exits or file writes, unless trusted (the person running
  // kinetofem trusts the file: --trust-part-files). Empty case_folder: its
  // own folder only.
  std::filesystem::path case_folder;
  bool trusted = false;
  // The named solids of a welded part (PartSolid above); empty: the solids of
  // the part file, named by position.
  std::vector<PartSolid> solids;
  // Solids closer than this are joined (welded) by the fragment; m, >= 0.
  double weld_tolerance_m = kDefaultWeldToleranceM;
};

// The mesh of the part in `file`, in metres, in the file's frame, with the
// face sets of `part`. `file` may be empty when every PartSolid has its own
// file (the part is their union; the first solid's file then stands for the
// part in messages). Throws Error as described above.
fem::Mesh mesh_part_file(const std::filesystem::path& file, const PartFileOptions& part,
                         const MeshOptions& mesh);

// The extensions mesh_part_file accepts (lower case; matching is
// case-insensitive): .step .stp .iges .igs .brep .geo .msh.
const std::vector<std::string>& part_file_extensions();

// The length unit a STEP or IGES file declares, in metres per file unit
// (1e-3 for mm, 0.0254 for inch), read from its text: STEP, the length unit
// of its GLOBAL_UNIT_ASSIGNED_CONTEXT (SI_UNIT with prefix, or a
// CONVERSION_BASED_UNIT over one); IGES, the units flag (and name) of its
// global section. nullopt when the file declares none, several different
// ones, or one this reader does not know. Throws Error if the file cannot be
// read or is neither STEP nor IGES.
std::optional<double> cad_file_length_unit_m(const std::filesystem::path& file);

}  // namespace kinetofem::meshes
